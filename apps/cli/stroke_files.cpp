// Stroke files: the strokes JSON of docs/paint.md and SVG drawings (sketch::load_svg).

#include "stroke_files.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/vectorize_style.hpp"
#include "exemplar/sketch/svg.hpp"

namespace exemplar::cli {

namespace {

using nlohmann::json;

bool has_extension(const std::string& path, const std::string& ext) {
    if (path.size() < ext.size()) return false;
    std::string tail = path.substr(path.size() - ext.size());
    for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return tail == ext;
}

// `[{"points": [[x, y], ...], "width": 40, "comb": false, "label": 2}, ...]`, coordinates in
// canvas pixels.
Result<std::vector<paint::Stroke>> read_json_strokes(const std::string& flag,
                                                     const std::string& path, bool labels) {
    std::ifstream file(path);
    if (!file) return io_error(flag + " " + path + ": cannot be read");
    std::stringstream text;
    text << file.rdbuf();
    const json doc = json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
    if (doc.is_discarded()) return invalid_argument(flag + " " + path + ": not valid JSON");
    if (!doc.is_array()) {
        return invalid_argument(flag + " " + path + ": must be an array of strokes");
    }
    std::vector<paint::Stroke> strokes;
    for (std::size_t i = 0; i < doc.size(); ++i) {
        const json& s = doc[i];
        const std::string where = flag + " " + path + ": stroke " + std::to_string(i) + ": ";
        if (!s.is_object()) return invalid_argument(where + "must be an object");
        for (const auto& [key, value] : s.items()) {
            if (key == "label" && !labels) {
                return invalid_argument(where + "'label' is read only with --source-labels");
            }
            if (key != "points" && key != "width" && key != "comb" && key != "label") {
                return invalid_argument(where + "unknown key '" + key +
                                        "' (known: points, width, comb)");
            }
        }
        paint::Stroke stroke;
        if (!s.contains("points") || !s["points"].is_array()) {
            return invalid_argument(where + "'points' must be an array of [x, y]");
        }
        for (const json& p : s["points"]) {
            if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) {
                return invalid_argument(where + "'points' must be an array of [x, y]");
            }
            stroke.points.push_back({p[0].get<float>(), p[1].get<float>()});
        }
        if (s.contains("width")) {
            if (!s["width"].is_number())
                return invalid_argument(where + "'width' must be a number");
            stroke.width_px = s["width"].get<float>();
        }
        if (s.contains("comb")) {
            if (!s["comb"].is_boolean())
                return invalid_argument(where + "'comb' must be true or false");
            stroke.comb = s["comb"].get<bool>();
        }
        if (s.contains("label")) {
            auto label = parse_label(s["label"].is_string() ? s["label"].get<std::string>()
                                                            : s["label"].dump());
            if (!label.ok())
                return invalid_argument(where + "'label': " + label.status().message());
            stroke.label = *label;
        }
        if (Status st = paint::validate(stroke); !st.is_ok()) {
            return invalid_argument(where + st.message());
        }
        strokes.push_back(std::move(stroke));
    }
    return strokes;
}

// Every SVG path is a painting stroke (paint::drawing_strokes), empty paths left out.
Result<std::vector<paint::Stroke>> read_svg_strokes(const std::string& flag,
                                                    const std::string& path, int width, int height,
                                                    bool labels) {
    auto drawing = sketch::load_svg(path);
    if (!drawing.ok()) return drawing.status();
    std::vector<paint::Stroke> all = paint::drawing_strokes(*drawing, width, height);
    std::vector<paint::Stroke> strokes;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (drawing->paths[i].empty()) continue;
        if (labels && i < drawing->strokes.size() && !drawing->strokes[i].empty() &&
            drawing->strokes[i] != "none") {
            auto label = parse_label(drawing->strokes[i]);
            if (!label.ok()) {
                return invalid_argument(flag + " " + path + ": path " + std::to_string(i) +
                                        ": stroke colour: " + label.status().message());
            }
            all[i].label = *label;
        }
        if (Status st = paint::validate(all[i]); !st.is_ok()) {
            return invalid_argument(flag + " " + path + ": path " + std::to_string(i) + ": " +
                                    st.message());
        }
        strokes.push_back(std::move(all[i]));
    }
    return strokes;
}

}  // namespace

Status check_stroke_file(const std::string& flag, const std::string& path) {
    if (has_extension(path, ".json") || has_extension(path, ".svg")) return Status::ok();
    return invalid_argument(flag + " " + path + ": must be a .json or .svg file");
}

Result<std::vector<paint::Stroke>> read_strokes(const std::string& flag, const std::string& path,
                                                int width, int height, bool labels) {
    EXEMPLAR_RETURN_IF_ERROR(check_stroke_file(flag, path));
    return has_extension(path, ".json") ? read_json_strokes(flag, path, labels)
                                        : read_svg_strokes(flag, path, width, height, labels);
}

Result<int> parse_label(const std::string& text) {
    const std::string valid =
        "'" + text + "' is invalid (must be 0..255, a grey level, or #rrggbb)";
    if (!text.empty() && text[0] == '#') {
        std::string hex = text.substr(1);
        if (hex.size() == 3) hex = {hex[0], hex[0], hex[1], hex[1], hex[2], hex[2]};
        if (hex.size() != 6 || !std::all_of(hex.begin(), hex.end(), [](char c) {
                return std::isxdigit(static_cast<unsigned char>(c)) != 0;
            })) {
            return invalid_argument(valid);
        }
        return static_cast<int>(std::stol(hex, nullptr, 16));
    }
    if (text.empty() || text.size() > 3 || !std::all_of(text.begin(), text.end(), [](char c) {
            return std::isdigit(static_cast<unsigned char>(c)) != 0;
        })) {
        return invalid_argument(valid);
    }
    const int grey = std::stoi(text);
    if (grey > 255) return invalid_argument(valid);
    return grey * 0x010101;
}

std::string label_colour(int label) {
    char text[8];
    std::snprintf(text, sizeof text, "#%06x", static_cast<unsigned>(label) & 0xffffffu);
    return text;
}

Status check_canvas_size(const std::string& canvas, int width, int height) {
    if (canvas.empty() && (width <= 0 || height <= 0)) {
        return invalid_argument("--width/--height: " + std::to_string(width) + "x" +
                                std::to_string(height) +
                                " is invalid (both must be > 0, or give --canvas)");
    }
    if (width > 32768 || height > 32768) {
        return invalid_argument("--width/--height: at most 32768 px");
    }
    return Status::ok();
}

Result<Canvas> load_canvas(const std::string& canvas, int width, int height) {
    if (canvas.empty()) return Canvas{Image(), width, height};
    auto bg = load_image(canvas);
    if (!bg.ok()) return bg.status();
    if (bg->channels() != 3 && bg->channels() != 4) {
        return invalid_argument("--canvas " + canvas + ": must be RGB or RGBA");
    }
    if ((width > 0 && width != bg->width()) || (height > 0 && height != bg->height())) {
        return invalid_argument("--canvas " + canvas + ": is " + std::to_string(bg->width()) + "x" +
                                std::to_string(bg->height()) + " but --width/--height " +
                                std::to_string(width) + "x" + std::to_string(height));
    }
    const int w = bg->width(), h = bg->height();
    return Canvas{std::move(bg).value(), w, h};
}

}  // namespace exemplar::cli
