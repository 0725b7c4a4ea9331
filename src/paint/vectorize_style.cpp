// Painting by Feature (Lukáč et al. 2013, thesis §3.4): vector image stylization. Line features
// are assigned to a drawing's stroked paths and area features to its filled shapes by colour or
// class; the fills are rendered first, the strokes over them. The chapter paints the line features
// first and fills between them; here the fill comes first and the strokes cover the shapes'
// borders, so a fill never has to continue a stroke (docs/feature.md).

#include "exemplar/paint/vectorize_style.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/paint.hpp"

namespace exemplar::paint {
namespace {

using nlohmann::json;

// The view box mapping: canvas = (user - origin) * scale.
struct ViewMapping {
    double sx = 1.0, sy = 1.0, ox = 0.0, oy = 0.0;
};
ViewMapping view_mapping(const sketch::Drawing& drawing, int width, int height) {
    ViewMapping m;
    if (drawing.view_width > 0.0 && drawing.view_height > 0.0) {
        m.sx = width / drawing.view_width;
        m.sy = height / drawing.view_height;
        m.ox = drawing.view_x;
        m.oy = drawing.view_y;
    }
    return m;
}

// Looks a path's key up in an assignment table: its classes, its colour, "default". Returns the
// feature name, or "" if none applies.
std::string assigned(const std::vector<std::pair<std::string, std::string>>& table,
                     const std::string& classes, const std::string& colour) {
    auto find = [&](const std::string& key) -> const std::string* {
        for (const auto& [k, name] : table) {
            if (k == key) return &name;
        }
        return nullptr;
    };
    std::istringstream words(classes);
    for (std::string c; words >> c;) {
        if (const std::string* name = find("." + c)) return *name;
    }
    if (const std::string* name = find(colour)) return *name;
    if (const std::string* name = find("default")) return *name;
    return "";
}

// Assignment keys as the drawing spells them: colours normalized, classes and "default" kept.
std::string normalized_key(const std::string& key) {
    if (key == "default" || key.rfind('.', 0) == 0) return key;
    return sketch::normalize_colour(key);
}

template <class Feature>
std::string defined_names(const std::vector<Feature>& features) {
    std::string names;
    for (const Feature& f : features) names += (names.empty() ? "" : ", ") + f.name;
    return names.empty() ? "none" : names;
}

// [[x, y], ...] into points; false if malformed.
bool read_points(const json& value, std::vector<StrokePoint>& points) {
    if (!value.is_array()) return false;
    for (const json& p : value) {
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) return false;
        points.push_back({p[0].get<float>(), p[1].get<float>()});
    }
    return true;
}

Status check_keys(const json& object, std::initializer_list<const char*> known,
                  const std::string& where) {
    for (const auto& [key, value] : object.items()) {
        if (std::none_of(known.begin(), known.end(), [&](const char* k) { return key == k; })) {
            std::string list;
            for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
            return invalid_argument(where + "unknown key '" + key + "' (known: " + list + ")");
        }
    }
    return Status::ok();
}

// "strokes" or "fills": {key: feature name}.
Status read_assignments(const json& doc, const char* field, const std::string& where,
                        std::vector<std::pair<std::string, std::string>>& out) {
    if (!doc.contains(field)) return Status::ok();
    const json& table = doc[field];
    if (!table.is_object()) {
        return invalid_argument(where + field + ": must be an object {colour or .class: name}");
    }
    for (const auto& [key, value] : table.items()) {
        if (!value.is_string()) {
            return invalid_argument(where + field + ": \"" + key + "\" must name a feature");
        }
        out.emplace_back(normalized_key(key), value.get<std::string>());
    }
    return Status::ok();
}

// The pixels of `image` in `box`.
Image crop(const Image& image, const PixelRect& box) {
    Image out(box.x1 - box.x0, box.y1 - box.y0, image.channels());
    out.set_channel_names(image.channel_names());
    for (int y = 0; y < out.height(); ++y) {
        std::copy_n(
            image.pixel(box.x0, box.y0 + y),
            static_cast<std::size_t>(out.width()) * static_cast<std::size_t>(image.channels()),
            out.pixel(0, y));
    }
    return out;
}

// doc[key] as {name: {...}}: `read(name, object, at)` for each entry, `at` the message prefix.
template <class Read>
Status read_features(const json& doc, const char* key, const std::string& where, Read read) {
    if (!doc.contains(key)) return Status::ok();
    if (!doc[key].is_object()) {
        return invalid_argument(where + key + ": must be an object {name: feature}");
    }
    for (const auto& [name, f] : doc[key].items()) {
        const std::string at = where + key + ": \"" + name + "\": ";
        if (!f.is_object()) return invalid_argument(at + "must be an object");
        EXEMPLAR_RETURN_IF_ERROR(read(name, f, at));
    }
    return Status::ok();
}

// The feature called `name` (validate made sure it exists).
template <class Feature>
const Feature& named(const std::vector<Feature>& features, const std::string& name) {
    return *std::find_if(features.begin(), features.end(),
                         [&](const Feature& f) { return f.name == name; });
}

// Pastes `piece` into `picture` at (x0, y0) where `mask` (piece size) is inside.
void paste_inside(Image& picture, const Image& piece, const Image& mask, int x0, int y0) {
    for (int y = 0; y < piece.height(); ++y) {
        for (int x = 0; x < piece.width(); ++x) {
            if (mask.at(x, y, 0) <= 0.5f) continue;
            std::copy_n(piece.pixel(x, y), 4, picture.pixel(x0 + x, y0 + y));
        }
    }
}

// Composites the RGBA `layer` over the RGBA `picture` within `rect` ("over", straight alpha).
void composite_rect(Image& picture, const Image& layer, const PixelRect& rect) {
    for (int y = std::max(0, rect.y0); y < std::min(picture.height(), rect.y1); ++y) {
        for (int x = std::max(0, rect.x0); x < std::min(picture.width(), rect.x1); ++x) {
            const float* f = layer.pixel(x, y);
            const float fa = f[3];
            if (fa <= 0.0f) continue;
            float* b = picture.pixel(x, y);
            const float ba = b[3];
            const float a = fa + ba * (1.0f - fa);
            for (int c = 0; c < 3; ++c) b[c] = (f[c] * fa + b[c] * ba * (1.0f - fa)) / a;
            b[3] = a;
        }
    }
}

}  // namespace

std::vector<Stroke> drawing_strokes(const sketch::Drawing& drawing, int width, int height) {
    const ViewMapping m = view_mapping(drawing, width, height);
    std::vector<Stroke> strokes(drawing.paths.size());
    for (std::size_t i = 0; i < drawing.paths.size(); ++i) {
        const sketch::Path& p = drawing.paths[i];
        Stroke& stroke = strokes[i];
        const double user_width = i < drawing.stroke_widths.size() ? drawing.stroke_widths[i] : 1.0;
        stroke.width_px = static_cast<float>(user_width * std::sqrt(std::abs(m.sx * m.sy)));
        if (p.empty()) continue;
        auto add = [&](sketch::Vec2 v) {
            stroke.points.push_back(
                {static_cast<float>((v.x - m.ox) * m.sx), static_cast<float>((v.y - m.oy) * m.sy)});
        };
        add(p.start());
        for (const sketch::Cubic& c : p.segments) {
            const double length = sketch::distance(c.p0, c.c1) + sketch::distance(c.c1, c.c2) +
                                  sketch::distance(c.c2, c.p3);
            const int steps = std::clamp(static_cast<int>(std::ceil(length * m.sx)), 1, 4096);
            for (int k = 1; k <= steps; ++k) add(c.point(static_cast<double>(k) / steps));
        }
    }
    return strokes;
}

Image polygon_mask(std::span<const std::vector<StrokePoint>> polygons, int width, int height,
                   bool even_odd) {
    Image mask(width, height, 1);
    std::vector<std::pair<float, int>> crossings;  // x, winding direction
    for (int y = 0; y < height; ++y) {
        const float cy = static_cast<float>(y) + 0.5f;
        crossings.clear();
        for (const std::vector<StrokePoint>& polygon : polygons) {
            const std::size_t n = polygon.size();
            for (std::size_t i = 0; i < n && n >= 3; ++i) {
                const StrokePoint& a = polygon[i];
                const StrokePoint& b = polygon[(i + 1) % n];
                // Half-open in y, so a vertex on the scan line counts once.
                if ((a.y <= cy) == (b.y <= cy)) continue;
                const float t = (cy - a.y) / (b.y - a.y);
                crossings.emplace_back(a.x + t * (b.x - a.x), b.y > a.y ? 1 : -1);
            }
        }
        std::sort(crossings.begin(), crossings.end());
        int winding = 0;
        for (std::size_t k = 0; k + 1 < crossings.size(); ++k) {
            winding += even_odd ? 1 : crossings[k].second;
            const bool inside = even_odd ? (winding & 1) != 0 : winding != 0;
            if (!inside) continue;
            // Pixel centres x + 0.5 in [crossing k, crossing k + 1).
            const int x0 = std::max(0, static_cast<int>(std::ceil(crossings[k].first - 0.5f)));
            const int x1 =
                std::min(width, static_cast<int>(std::ceil(crossings[k + 1].first - 0.5f)));
            for (int x = x0; x < x1; ++x) mask.at(x, y, 0) = 1.0f;
        }
    }
    return mask;
}

std::pair<int, int> drawing_canvas_size(const sketch::Drawing& drawing, int width) {
    double w = drawing.view_width * drawing.pixels_per_unit;
    double h = drawing.view_height * drawing.pixels_per_unit;
    if (!(w > 0.0 && h > 0.0)) {
        w = h = 1.0;
        for (const sketch::Path& p : drawing.paths) {
            for (const sketch::Cubic& c : p.segments) {
                for (const sketch::Vec2& v : {c.p0, c.c1, c.c2, c.p3}) {
                    w = std::max(w, v.x);
                    h = std::max(h, v.y);
                }
            }
        }
    }
    if (width > 0) {
        h *= width / w;
        w = width;
    }
    return {std::max(1, static_cast<int>(std::lround(w))),
            std::max(1, static_cast<int>(std::lround(h)))};
}

Status validate(const StylePalette& palette) {
    const int channels = palette.palette.channels();
    if (palette.palette.empty()) return invalid_argument("palette: is empty");
    if (channels != 1 && channels != 3 && channels != 4) {
        return invalid_argument("palette: has " + std::to_string(channels) +
                                " channels (must be grey, RGB or RGBA)");
    }
    std::set<std::string> lines, areas;
    for (const StyleLineFeature& f : palette.line_features) {
        if (!lines.insert(f.name).second) {
            return invalid_argument("line_features: \"" + f.name + "\" is defined twice");
        }
        if (!(f.brush_width_px >= 0.0f && f.brush_width_px <= 4096.0f)) {
            return invalid_argument("line_features: \"" + f.name + "\": brush_width " +
                                    std::to_string(f.brush_width_px) +
                                    " is invalid (must be 0..4096; 0 = the paths' widths)");
        }
    }
    for (const StyleAreaFeature& f : palette.area_features) {
        if (!areas.insert(f.name).second) {
            return invalid_argument("area_features: \"" + f.name + "\" is defined twice");
        }
        if (!f.region.same_size(palette.palette)) {
            return invalid_argument("area_features: \"" + f.name + "\": region is " +
                                    size_str(f.region) + " but the palette is " +
                                    size_str(palette.palette));
        }
    }
    for (const auto& [key, name] : palette.strokes) {
        if (!lines.contains(name)) {
            return invalid_argument(
                "strokes: \"" + key + "\" names line feature \"" + name +
                "\", which is not defined (defined: " + defined_names(palette.line_features) + ")");
        }
    }
    for (const auto& [key, name] : palette.fills) {
        if (!areas.contains(name)) {
            return invalid_argument(
                "fills: \"" + key + "\" names area feature \"" + name +
                "\", which is not defined (defined: " + defined_names(palette.area_features) + ")");
        }
    }
    if (!palette.background.empty() && !areas.contains(palette.background)) {
        return invalid_argument(
            "background: names area feature \"" + palette.background +
            "\", which is not defined (defined: " + defined_names(palette.area_features) + ")");
    }
    return Status::ok();
}

Result<StylePalette> load_style_palette(const std::string& path) {
    std::ifstream file(path);
    if (!file) return io_error(path + ": cannot be read");
    std::stringstream text;
    text << file.rdbuf();
    const json doc = json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
    const std::string where = path + ": ";
    if (doc.is_discarded()) return invalid_argument(where + "not valid JSON");
    if (!doc.is_object()) return invalid_argument(where + "must be a JSON object");
    EXEMPLAR_RETURN_IF_ERROR(check_keys(
        doc, {"palette", "line_features", "area_features", "strokes", "fills", "background"},
        where));
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    auto image_at = [&](const std::string& key, const std::string& file_name) -> Result<Image> {
        auto image = load_image((folder / file_name).string());
        if (!image.ok()) return invalid_argument(where + key + ": " + image.status().message());
        return image;
    };

    StylePalette palette;
    if (!doc.contains("palette") || !doc["palette"].is_string()) {
        return invalid_argument(where + "palette: must name the palette image");
    }
    auto image = image_at("palette", doc["palette"].get<std::string>());
    if (!image.ok()) return image.status();
    palette.palette = std::move(image).value();

    const auto read_line = [&](const std::string& name, const json& f,
                               const std::string& at) -> Status {
        EXEMPLAR_RETURN_IF_ERROR(check_keys(f, {"path", "width", "brush_width", "snap"}, at));
        StyleLineFeature feature;
        feature.name = name;
        if (!f.contains("path") || !read_points(f["path"], feature.selection.points)) {
            return invalid_argument(at + "path: must be an array of [x, y] palette pixels");
        }
        if (f.contains("width")) {
            if (!f["width"].is_number()) return invalid_argument(at + "width: not a number");
            feature.selection.width_px = f["width"].get<float>();
        }
        if (f.contains("brush_width")) {
            if (!f["brush_width"].is_number()) {
                return invalid_argument(at + "brush_width: not a number");
            }
            feature.brush_width_px = f["brush_width"].get<float>();
        }
        if (f.contains("snap")) {
            if (!f["snap"].is_boolean()) return invalid_argument(at + "snap: not true/false");
            feature.snap = f["snap"].get<bool>();
        }
        palette.line_features.push_back(std::move(feature));
        return Status::ok();
    };
    const auto read_area = [&](const std::string& name, const json& f,
                               const std::string& at) -> Status {
        EXEMPLAR_RETURN_IF_ERROR(check_keys(f, {"region", "polygon"}, at));
        StyleAreaFeature feature;
        feature.name = name;
        if (f.contains("region") == f.contains("polygon")) {
            return invalid_argument(at + "needs either region (an image) or polygon");
        }
        if (f.contains("region")) {
            if (!f["region"].is_string()) return invalid_argument(at + "region: not a file");
            auto region =
                image_at("area_features: \"" + name + "\": region", f["region"].get<std::string>());
            if (!region.ok()) return region.status();
            feature.region = std::move(region).value();
        } else {
            std::vector<StrokePoint> polygon;
            if (!read_points(f["polygon"], polygon) || polygon.size() < 3) {
                return invalid_argument(
                    at + "polygon: must be an array of at least 3 [x, y] palette pixels");
            }
            feature.region =
                polygon_mask({&polygon, 1}, palette.palette.width(), palette.palette.height());
        }
        palette.area_features.push_back(std::move(feature));
        return Status::ok();
    };
    EXEMPLAR_RETURN_IF_ERROR(read_features(doc, "line_features", where, read_line));
    EXEMPLAR_RETURN_IF_ERROR(read_features(doc, "area_features", where, read_area));
    EXEMPLAR_RETURN_IF_ERROR(read_assignments(doc, "strokes", where, palette.strokes));
    EXEMPLAR_RETURN_IF_ERROR(read_assignments(doc, "fills", where, palette.fills));
    if (doc.contains("background")) {
        if (!doc["background"].is_string()) {
            return invalid_argument(where + "background: must name an area feature");
        }
        palette.background = doc["background"].get<std::string>();
    }
    if (Status st = validate(palette); !st.is_ok()) return invalid_argument(where + st.message());
    return palette;
}

Result<Image> vectorize_style(const sketch::Drawing& drawing, const StylePalette& palette,
                              int width, int height, const VectorizeStyleOptions& options,
                              const RunContext& context) {
    // Checks: the palette, the options, the canvas, the drawing's paths and their features.
    EXEMPLAR_RETURN_IF_ERROR(validate(palette));
    EXEMPLAR_RETURN_IF_ERROR(validate(options.brush));
    EXEMPLAR_RETURN_IF_ERROR(validate(options.fill));
    if (width <= 0 || height <= 0 || width > 32768 || height > 32768) {
        return invalid_argument("canvas: " + std::to_string(width) + "x" + std::to_string(height) +
                                " is invalid (1..32768 each)");
    }
    const std::size_t n = drawing.paths.size();
    if (std::none_of(drawing.paths.begin(), drawing.paths.end(),
                     [](const sketch::Path& p) { return !p.empty(); })) {
        return invalid_argument("drawing: holds no path");
    }
    auto at = [](const auto& v, std::size_t i, auto fallback) {
        return i < v.size() ? v[i] : fallback;
    };
    const std::vector<Stroke> strokes = drawing_strokes(drawing, width, height);
    // Per path: its line feature ("" = not stroked); per element: its fill's area feature.
    std::vector<std::string> line_of(n);
    std::map<int, std::string> area_of;
    for (std::size_t i = 0; i < n; ++i) {
        if (drawing.paths[i].empty()) continue;
        const std::string classes = at(drawing.classes, i, std::string());
        const std::string stroke = at(drawing.strokes, i, std::string("#000000"));
        const std::string fill = at(drawing.fills, i, std::string("none"));
        const std::string path_name = "drawing: path " + std::to_string(i);
        if (stroke != "none" && strokes[i].width_px > 0.0f) {
            line_of[i] = assigned(palette.strokes, classes, stroke);
            if (line_of[i].empty()) {
                return invalid_argument(path_name + " (stroke " + stroke +
                                        "): no line feature is assigned (strokes has no key for "
                                        "it and no \"default\")");
            }
        }
        if (fill != "none") {
            std::string area = assigned(palette.fills, classes, fill);
            if (area.empty()) {
                return invalid_argument(path_name + " (fill " + fill +
                                        "): no area feature is assigned (fills has no key for it "
                                        "and no \"default\")");
            }
            area_of[at(drawing.elements, i, static_cast<int>(i))] = area;
        }
    }
    auto area_feature = [&](const std::string& name) -> const StyleAreaFeature& {
        return named(palette.area_features, name);
    };
    const Image palette_rgba = with_channels(palette.palette, 4);

    // The background: the whole canvas, free-standing.
    Image picture(width, height, 4);
    picture.set_channel_names({"R", "G", "B", "A"});
    if (!palette.background.empty()) {
        auto filled = fill_area(palette_rgba, area_feature(palette.background).region, Image(),
                                Image(width, height, 1, 1.0f), options.fill, context);
        if (!filled.ok()) {
            return invalid_argument("area feature \"" + palette.background +
                                    "\": " + filled.status().message());
        }
        picture = std::move(filled).value();
    }

    // The filled shapes, each in its bounding box grown by a margin: over the background, the
    // patches across the border continue it; without one, the shape stands free.
    for (const auto& [element, name] : area_of) {
        if (context.cancelled()) return cancelled();
        std::vector<std::vector<StrokePoint>> polygons;
        bool even_odd = false;
        for (std::size_t i = 0; i < n; ++i) {
            if (at(drawing.elements, i, static_cast<int>(i)) != element) continue;
            if (strokes[i].points.size() >= 3) polygons.push_back(strokes[i].points);
            even_odd = at(drawing.even_odd, i, static_cast<unsigned char>(0)) != 0;
        }
        const Image shape = polygon_mask(polygons, width, height, even_odd);
        PixelRect box{width, height, 0, 0};
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                if (shape.at(x, y, 0) <= 0.5f) continue;
                box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x + 1),
                       std::max(box.y1, y + 1)};
            }
        }
        if (box.empty()) continue;  // too thin to hold a pixel centre
        const int margin = 4 * options.fill.patch_size;
        box = {std::max(0, box.x0 - margin), std::max(0, box.y0 - margin),
               std::min(width, box.x1 + margin), std::min(height, box.y1 + margin)};
        const Image target = crop(shape, box);
        const Image canvas = palette.background.empty() ? Image() : crop(picture, box);
        auto filled = fill_area(palette_rgba, area_feature(name).region, canvas, target,
                                options.fill, context);
        if (!filled.ok()) {
            return invalid_argument("area feature \"" + name + "\": " + filled.status().message());
        }
        paste_inside(picture, *filled, target, box.x0, box.y0);
    }

    // The line features, each selected once, then every stroked path in document order.
    std::map<std::string, LineFeature> features;
    for (std::size_t i = 0; i < n; ++i) {
        if (line_of[i].empty() || features.contains(line_of[i])) continue;
        const StyleLineFeature& spec = named(palette.line_features, line_of[i]);
        auto feature = pick_line_feature(palette.palette, spec.selection, options.brush, spec.snap,
                                         context.threads);
        if (!feature.ok()) {
            return invalid_argument("line feature \"" + spec.name +
                                    "\": " + feature.status().message());
        }
        features.emplace(spec.name, std::move(feature).value());
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (line_of[i].empty()) continue;
        if (context.cancelled()) return cancelled();
        const LineFeature& feature = features.at(line_of[i]);
        const StyleLineFeature& spec = named(palette.line_features, line_of[i]);
        const float brush_width =
            spec.brush_width_px > 0.0f ? spec.brush_width_px : strokes[i].width_px;
        if (Status st = validate(Stroke{strokes[i].points, brush_width, false}); !st.is_ok()) {
            return invalid_argument("drawing: path " + std::to_string(i) + ": " + st.message());
        }
        BrushStroke stroke(feature, width, height, brush_width, i, context.threads);
        auto changed = stroke.add_points(strokes[i].points);
        if (!changed.ok()) {
            return invalid_argument("drawing: path " + std::to_string(i) + ": " +
                                    changed.status().message());
        }
        composite_rect(picture, stroke.layer(), *changed);
    }
    return picture;
}

}  // namespace exemplar::paint
