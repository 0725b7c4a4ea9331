// SVG import (tinyxml2) and export of stroke drawings. The path-data and transform grammars are
// parsed here (they are attribute micro-syntaxes, not XML); arcs follow the SVG 1.1 endpoint to
// centre conversion (implementation notes F.6.5–F.6.6).

#include "exemplar/sketch/svg.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "exemplar/io/atomic_write.hpp"

namespace exemplar::sketch {

namespace {

// A cursor over an attribute's text: numbers separated by white space and/or commas.
class Scanner {
public:
    explicit Scanner(const char* text) : p_(text == nullptr ? "" : text) {}

    void skip_separators() {
        while (*p_ != '\0' && (std::isspace(static_cast<unsigned char>(*p_)) || *p_ == ',')) ++p_;
    }
    bool at_end() {
        skip_separators();
        return *p_ == '\0';
    }
    bool at_number() {
        skip_separators();
        return *p_ == '-' || *p_ == '+' || *p_ == '.' ||
               std::isdigit(static_cast<unsigned char>(*p_));
    }
    char peek() {
        skip_separators();
        return *p_;
    }
    char take() { return *p_ == '\0' ? '\0' : *p_++; }
    bool number(double& value) {
        if (!at_number()) return false;
        char* end = nullptr;
        value = std::strtod(p_, &end);
        if (end == p_ || !std::isfinite(value)) return false;
        p_ = end;
        return true;
    }
    // An arc flag: a single '0' or '1' that may be followed directly by the next number.
    bool flag(bool& value) {
        skip_separators();
        if (*p_ != '0' && *p_ != '1') return false;
        value = *p_++ == '1';
        return true;
    }
    const char* rest() const { return p_; }

private:
    const char* p_;
};

// Builds subpaths from path commands, tracking the current point and the last control point.
class PathBuilder {
public:
    void move_to(Vec2 p) {
        finish();
        current_ = start_ = p;
        last_control_ = p;
        last_quad_ = p;
    }
    void cubic_to(Vec2 c1, Vec2 c2, Vec2 p) {
        path_.segments.push_back({current_, c1, c2, p});
        last_control_ = c2;
        last_quad_ = p;
        current_ = p;
    }
    void quad_to(Vec2 q, Vec2 p) {
        cubic_to(current_ + (q - current_) * (2.0 / 3.0), p + (q - p) * (2.0 / 3.0), p);
        last_quad_ = q;
    }
    void line_to(Vec2 p) {
        cubic_to(lerp(current_, p, 1.0 / 3.0), lerp(current_, p, 2.0 / 3.0), p);
    }
    void arc_to(double rx, double ry, double rotation_deg, bool large, bool sweep, Vec2 p);
    void close() {
        if (path_.empty()) return;
        if (distance(current_, start_) > 1e-9) line_to(start_);
        path_.closed = true;
        const Vec2 s = start_;
        finish();
        current_ = start_ = last_control_ = last_quad_ = s;
    }
    // Ends the current subpath; a lone `M` (no drawing command) still counts as a (degenerate)
    // stroke so that callers can reject it with a clear message.
    void finish() {
        if (!path_.empty() || pending_move_) paths_.push_back(path_);
        path_ = Path{};
        pending_move_ = false;
    }
    void mark_move() { pending_move_ = true; }
    void clear_move() { pending_move_ = false; }

    Vec2 current() const { return current_; }
    Vec2 reflected_control() const { return current_ * 2.0 - last_control_; }
    Vec2 reflected_quad() const { return current_ * 2.0 - last_quad_; }
    void reset_cubic_control() { last_control_ = current_; }
    void reset_quad_control() { last_quad_ = current_; }
    std::vector<Path>& paths() { return paths_; }

private:
    Path path_;
    std::vector<Path> paths_;
    Vec2 current_, start_, last_control_, last_quad_;
    bool pending_move_ = false;
};

void PathBuilder::arc_to(double rx, double ry, double rotation_deg, bool large, bool sweep,
                         Vec2 p) {
    const Vec2 p0 = current_;
    rx = std::abs(rx);
    ry = std::abs(ry);
    if (distance(p0, p) < 1e-12) return;
    if (rx < 1e-12 || ry < 1e-12) {
        line_to(p);
        return;
    }
    const double phi = rotation_deg * std::numbers::pi / 180.0;
    const double cp = std::cos(phi), sp = std::sin(phi);
    const Vec2 h = (p0 - p) / 2.0;
    const double x1 = cp * h.x + sp * h.y, y1 = -sp * h.x + cp * h.y;
    const double lambda = x1 * x1 / (rx * rx) + y1 * y1 / (ry * ry);
    if (lambda > 1.0) {
        rx *= std::sqrt(lambda);
        ry *= std::sqrt(lambda);
    }
    const double num = rx * rx * ry * ry - rx * rx * y1 * y1 - ry * ry * x1 * x1;
    const double den = rx * rx * y1 * y1 + ry * ry * x1 * x1;
    double coef = den > 0.0 ? std::sqrt(std::max(0.0, num / den)) : 0.0;
    if (large == sweep) coef = -coef;
    const double cx1 = coef * rx * y1 / ry, cy1 = -coef * ry * x1 / rx;
    const Vec2 mid = (p0 + p) / 2.0;
    const Vec2 center{cp * cx1 - sp * cy1 + mid.x, sp * cx1 + cp * cy1 + mid.y};
    const double theta1 = std::atan2((y1 - cy1) / ry, (x1 - cx1) / rx);
    double dtheta = std::atan2((-y1 - cy1) / ry, (-x1 - cx1) / rx) - theta1;
    if (sweep && dtheta < 0) dtheta += 2 * std::numbers::pi;
    if (!sweep && dtheta > 0) dtheta -= 2 * std::numbers::pi;
    const Path arc = ellipse_arc_path(center, rx, ry, phi, theta1, dtheta);
    for (const Cubic& c : arc.segments) cubic_to(c.c1, c.c2, c.p3);
    current_ = p;  // exact endpoint despite rounding
    path_.segments.back().p3 = p;
}

// Parses path data into subpaths; returns an error message or "".
std::string parse_path_data(const char* d, std::vector<Path>& out) {
    Scanner s(d);
    PathBuilder b;
    char command = '\0';
    auto read = [&](double& v) { return s.number(v); };
    auto read_point = [&](Vec2& v, bool relative) {
        if (!read(v.x) || !read(v.y)) return false;
        if (relative) v += b.current();
        return true;
    };
    while (!s.at_end()) {
        if (std::isalpha(static_cast<unsigned char>(s.peek()))) {
            command = s.take();
        } else if (command == '\0') {
            return std::string("path data must start with a command, found '") + s.peek() + "'";
        } else if (command == 'M' || command == 'm') {
            command = command == 'M' ? 'L' : 'l';  // extra pairs after M are line-tos
        } else if (command == 'Z' || command == 'z') {
            return "numbers after Z";
        }
        const bool rel = std::islower(static_cast<unsigned char>(command)) != 0;
        const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(command)));
        bool ok = true;
        switch (upper) {
            case 'M': {
                Vec2 p;
                ok = read_point(p, rel);
                if (ok) {
                    b.move_to(p);
                    b.mark_move();
                }
                break;
            }
            case 'L': {
                Vec2 p;
                ok = read_point(p, rel);
                if (ok) b.line_to(p);
                break;
            }
            case 'H': {
                double x = 0;
                ok = read(x);
                if (ok) b.line_to({rel ? b.current().x + x : x, b.current().y});
                break;
            }
            case 'V': {
                double y = 0;
                ok = read(y);
                if (ok) b.line_to({b.current().x, rel ? b.current().y + y : y});
                break;
            }
            case 'C': {
                const Vec2 base = b.current();
                Vec2 c1, c2, p;
                ok = read(c1.x) && read(c1.y) && read(c2.x) && read(c2.y) && read(p.x) && read(p.y);
                if (ok && rel) {
                    c1 += base;
                    c2 += base;
                    p += base;
                }
                if (ok) b.cubic_to(c1, c2, p);
                break;
            }
            case 'S': {
                const Vec2 base = b.current();
                Vec2 c2, p;
                ok = read(c2.x) && read(c2.y) && read(p.x) && read(p.y);
                if (ok && rel) {
                    c2 += base;
                    p += base;
                }
                if (ok) b.cubic_to(b.reflected_control(), c2, p);
                break;
            }
            case 'Q': {
                const Vec2 base = b.current();
                Vec2 q, p;
                ok = read(q.x) && read(q.y) && read(p.x) && read(p.y);
                if (ok && rel) {
                    q += base;
                    p += base;
                }
                if (ok) b.quad_to(q, p);
                break;
            }
            case 'T': {
                Vec2 p;
                ok = read_point(p, rel);
                if (ok) b.quad_to(b.reflected_quad(), p);
                break;
            }
            case 'A': {
                double rx = 0, ry = 0, rot = 0;
                bool large = false, sweep = false;
                Vec2 p;
                ok = read(rx) && read(ry) && read(rot) && s.flag(large) && s.flag(sweep) &&
                     read_point(p, rel);
                if (ok) b.arc_to(rx, ry, rot, large, sweep, p);
                break;
            }
            case 'Z': b.close(); break;
            default: return std::string("unknown path command '") + command + "'";
        }
        if (!ok) {
            return std::string("bad or missing numbers for path command '") + command +
                   "' near \"" + std::string(s.rest()).substr(0, 20) + "\"";
        }
        // S reflects only a previous C/S control point, T only a previous Q/T one.
        if (upper != 'C' && upper != 'S') b.reset_cubic_control();
        if (upper != 'Q' && upper != 'T') b.reset_quad_control();
        if (upper != 'M') b.clear_move();
    }
    b.finish();
    for (Path& p : b.paths()) out.push_back(std::move(p));
    return "";
}

// Parses a transform list; returns an error message or "".
std::string parse_transform(const char* text, Affine& m) {
    std::string t = text == nullptr ? "" : text;
    std::size_t pos = 0;
    m = Affine{};
    while (true) {
        while (pos < t.size() &&
               (std::isspace(static_cast<unsigned char>(t[pos])) || t[pos] == ','))
            ++pos;
        if (pos >= t.size()) break;
        const std::size_t open = t.find('(', pos);
        const std::size_t close = t.find(')', pos);
        if (open == std::string::npos || close == std::string::npos || close < open) {
            return "malformed transform \"" + t + "\"";
        }
        std::string name = t.substr(pos, open - pos);
        name.erase(
            std::remove_if(name.begin(), name.end(),
                           [](char c) { return std::isspace(static_cast<unsigned char>(c)); }),
            name.end());
        const std::string args_text = t.substr(open + 1, close - open - 1);
        Scanner s(args_text.c_str());
        std::vector<double> a;
        double v = 0;
        while (s.number(v)) a.push_back(v);
        if (!s.at_end()) return "malformed transform arguments \"" + args_text + "\"";
        Affine step;
        const double deg = std::numbers::pi / 180.0;
        if (name == "matrix" && a.size() == 6) {
            step = {a[0], a[1], a[2], a[3], a[4], a[5]};
        } else if (name == "translate" && (a.size() == 1 || a.size() == 2)) {
            step = Affine::translation({a[0], a.size() == 2 ? a[1] : 0.0});
        } else if (name == "scale" && (a.size() == 1 || a.size() == 2)) {
            step = Affine::scaling(a[0], a.size() == 2 ? a[1] : a[0]);
        } else if (name == "rotate" && (a.size() == 1 || a.size() == 3)) {
            step = Affine::rotation(a[0] * deg, a.size() == 3 ? Vec2{a[1], a[2]} : Vec2{});
        } else if (name == "skewX" && a.size() == 1) {
            step = {1, 0, std::tan(a[0] * deg), 1, 0, 0};
        } else if (name == "skewY" && a.size() == 1) {
            step = {1, std::tan(a[0] * deg), 0, 1, 0, 0};
        } else {
            return "unsupported transform \"" + name + "(" + args_text + ")\"";
        }
        m = compose(m, step);  // the list applies right to left to points
        pos = close + 1;
    }
    return "";
}

double attribute(const tinyxml2::XMLElement* e, const char* name, double fallback, bool* ok) {
    const char* text = e->Attribute(name);
    if (text == nullptr) return fallback;
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (end == text || !std::isfinite(v)) {
        *ok = false;
        return fallback;
    }
    return v;  // units such as "px" after the number are ignored
}

bool skipped_element(const std::string& name) {
    return name == "defs" || name == "symbol" || name == "clipPath" || name == "mask" ||
           name == "pattern" || name == "marker" || name == "metadata" || name == "title" ||
           name == "desc" || name == "style" || name == "text";
}

std::string describe(const tinyxml2::XMLElement* e) {
    std::string what = std::string("<") + e->Name() + ">";
    if (const char* id = e->Attribute("id")) what += " id=\"" + std::string(id) + "\"";
    what += std::string(" (line ") + std::to_string(e->GetLineNum()) + ")";
    return what;
}

// Reads the shapes of `e` (already known to be drawable) into paths; returns an error or "".
std::string element_paths(const tinyxml2::XMLElement* e, std::vector<Path>& out) {
    const std::string name = e->Name();
    bool ok = true;
    auto num = [&](const char* attr, double fallback = 0.0) {
        return attribute(e, attr, fallback, &ok);
    };
    if (name == "path") {
        return parse_path_data(e->Attribute("d"), out);
    }
    if (name == "line") {
        const Vec2 a{num("x1"), num("y1")}, b{num("x2"), num("y2")};
        if (ok) out.push_back(polyline_path({a, b}));
    } else if (name == "polyline" || name == "polygon") {
        Scanner s(e->Attribute("points"));
        std::vector<Vec2> pts;
        Vec2 p;
        while (s.number(p.x)) {
            if (!s.number(p.y)) return "odd number of coordinates in points";
            pts.push_back(p);
        }
        if (!s.at_end()) return "malformed points";
        Path path = polyline_path(pts, name == "polygon");
        if (pts.size() == 1) path.segments.clear();
        out.push_back(path);
    } else if (name == "circle" || name == "ellipse") {
        const Vec2 c{num("cx"), num("cy")};
        const double rx = name == "circle" ? num("r") : num("rx");
        const double ry = name == "circle" ? rx : num("ry");
        if (ok && rx > 0 && ry > 0) {
            out.push_back(ellipse_arc_path(c, rx, ry, 0.0, 0.0, 2 * std::numbers::pi));
        }
    } else if (name == "rect") {
        const double x = num("x"), y = num("y"), w = num("width"), h = num("height");
        double rx = num("rx", -1.0), ry = num("ry", -1.0);
        if (rx < 0) rx = ry;
        if (ry < 0) ry = rx;
        rx = std::clamp(rx, 0.0, w / 2);
        ry = std::clamp(ry, 0.0, h / 2);
        if (ok && w > 0 && h > 0) {
            if (rx <= 0 || ry <= 0) {
                out.push_back(
                    polyline_path({{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}}, true));
            } else {
                const double q = std::numbers::pi / 2;
                Path p;
                auto add = [&](const Path& piece) {
                    for (const Cubic& c : piece.segments) {
                        if (!p.empty() && distance(p.end(), c.p0) > 1e-9) {
                            p.segments.push_back(line_cubic(p.end(), c.p0));
                        }
                        p.segments.push_back(c);
                    }
                };
                add(ellipse_arc_path({x + w - rx, y + ry}, rx, ry, 0, -q, q));
                add(ellipse_arc_path({x + w - rx, y + h - ry}, rx, ry, 0, 0, q));
                add(ellipse_arc_path({x + rx, y + h - ry}, rx, ry, 0, q, q));
                add(ellipse_arc_path({x + rx, y + ry}, rx, ry, 0, 2 * q, q));
                if (distance(p.end(), p.start()) > 1e-9) {
                    p.segments.push_back(line_cubic(p.end(), p.start()));
                }
                p.closed = true;
                out.push_back(p);
            }
        }
    }
    return ok ? "" : "malformed number attribute";
}

// The element's own presentation property `name` (its `style` declaration, which wins, or its
// attribute), trimmed; "" if it sets none.
std::string property_of(const tinyxml2::XMLElement* e, const std::string& name) {
    auto trim = [](std::string text) {
        const auto b = text.find_first_not_of(" \t\r\n");
        const auto e2 = text.find_last_not_of(" \t\r\n");
        return b == std::string::npos ? std::string() : text.substr(b, e2 - b + 1);
    };
    if (const char* style = e->Attribute("style")) {
        const std::string css = style;
        for (std::size_t at = 0; at < css.size();) {
            const auto end = std::min(css.find(';', at), css.size());
            const std::string declaration = css.substr(at, end - at);
            const auto colon = declaration.find(':');
            if (colon != std::string::npos && trim(declaration.substr(0, colon)) == name) {
                return trim(declaration.substr(colon + 1));
            }
            at = end + 1;
        }
    }
    if (const char* value = e->Attribute(name.c_str())) return trim(value);
    return "";
}

// The inherited presentation properties the drawing records per path.
struct Presentation {
    double stroke_width = 1.0;     // user units; SVG's default 1
    std::string stroke = "none";   // SVG's default: no stroke
    std::string fill = "#000000";  // SVG's default: black
    bool even_odd = false;         // fill-rule
    std::string classes;           // the element's and its ancestors' `class` attributes
};

// `inherited` with the element's own properties applied.
Presentation presentation_of(const tinyxml2::XMLElement* e, Presentation inherited) {
    const std::string width_text = property_of(e, "stroke-width");
    if (!width_text.empty()) {
        char* end = nullptr;
        const double width = std::strtod(width_text.c_str(), &end);
        if (end != width_text.c_str() && std::isfinite(width) && width >= 0.0) {
            inherited.stroke_width = width;
        }
    }
    if (const std::string stroke = property_of(e, "stroke"); !stroke.empty()) {
        if (stroke != "inherit") inherited.stroke = normalize_colour(stroke);
    }
    if (const std::string fill = property_of(e, "fill"); !fill.empty()) {
        if (fill != "inherit") inherited.fill = normalize_colour(fill);
    }
    if (const std::string rule = property_of(e, "fill-rule"); !rule.empty()) {
        if (rule != "inherit") inherited.even_odd = rule == "evenodd";
    }
    if (const char* classes = e->Attribute("class")) {
        // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) about "literal" + string.
        if (!inherited.classes.empty()) inherited.classes.push_back(' ');
        inherited.classes.append(classes);
    }
    return inherited;
}

std::string walk(const tinyxml2::XMLElement* parent, const Affine& parent_transform,
                 const Presentation& parent_style, Drawing& drawing) {
    for (const tinyxml2::XMLElement* e = parent->FirstChildElement(); e != nullptr;
         e = e->NextSiblingElement()) {
        const std::string name = e->Name();
        if (skipped_element(name)) continue;
        Affine local;
        if (const char* t = e->Attribute("transform")) {
            const std::string error = parse_transform(t, local);
            if (!error.empty()) return describe(e) + ": " + error;
        }
        const Affine m = compose(parent_transform, local);
        const Presentation style = presentation_of(e, parent_style);
        if (name == "g" || name == "a" || name == "svg" || name == "switch") {
            Affine inner = m;
            if (name == "svg") {  // a nested viewport: its x/y offset
                bool ok = true;
                inner = compose(
                    m, Affine::translation({attribute(e, "x", 0, &ok), attribute(e, "y", 0, &ok)}));
            }
            const std::string error = walk(e, inner, style, drawing);
            if (!error.empty()) return error;
            continue;
        }
        std::vector<Path> paths;
        const std::string error = element_paths(e, paths);
        if (!error.empty()) return describe(e) + ": " + error;
        const std::string id = e->Attribute("id") != nullptr ? e->Attribute("id") : "";
        for (std::size_t k = 0; k < paths.size(); ++k) {
            drawing.paths.push_back(transformed(paths[k], m));
            drawing.ids.push_back(k == 0 ? id : id + std::string("#") + std::to_string(k));
            drawing.stroke_widths.push_back(style.stroke_width *
                                            std::sqrt(std::abs(m.determinant())));
            drawing.strokes.push_back(style.stroke);
            drawing.fills.push_back(style.fill);
            drawing.classes.push_back(style.classes);
            drawing.elements.push_back(drawing.element_count);
            drawing.even_odd.push_back(style.even_odd ? 1 : 0);
        }
        ++drawing.element_count;
    }
    return "";
}

std::string format_number(double v) {
    if (std::abs(v) < 5e-5) v = 0.0;
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.4f", v);
    std::string s = buffer;
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}

std::string xml_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

}  // namespace

std::string normalize_colour(const std::string& colour) {
    std::string c;
    for (char ch : colour) {
        if (!std::isspace(static_cast<unsigned char>(ch))) {
            c += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        }
    }
    auto hex = [](char ch) { return std::isxdigit(static_cast<unsigned char>(ch)) != 0; };
    if (c.size() == 4 && c[0] == '#' && hex(c[1]) && hex(c[2]) && hex(c[3])) {
        return std::string{'#', c[1], c[1], c[2], c[2], c[3], c[3]};
    }
    if (c.size() == 7 && c[0] == '#' && std::all_of(c.begin() + 1, c.end(), hex)) return c;
    if (c.rfind("rgb(", 0) == 0 && c.back() == ')') {
        Scanner s(c.c_str() + 4);
        double v[3];
        if (s.number(v[0]) && s.number(v[1]) && s.number(v[2])) {
            char out[8];
            std::snprintf(out, sizeof out, "#%02x%02x%02x",
                          static_cast<unsigned>(std::clamp(std::lround(v[0]), 0L, 255L)),
                          static_cast<unsigned>(std::clamp(std::lround(v[1]), 0L, 255L)),
                          static_cast<unsigned>(std::clamp(std::lround(v[2]), 0L, 255L)));
            return out;
        }
    }
    // CSS's basic colour keywords.
    static const std::pair<const char*, const char*> kNamed[] = {
        {"black", "#000000"},   {"silver", "#c0c0c0"}, {"gray", "#808080"},
        {"grey", "#808080"},    {"white", "#ffffff"},  {"maroon", "#800000"},
        {"red", "#ff0000"},     {"purple", "#800080"}, {"fuchsia", "#ff00ff"},
        {"green", "#008000"},   {"lime", "#00ff00"},   {"olive", "#808000"},
        {"yellow", "#ffff00"},  {"navy", "#000080"},   {"blue", "#0000ff"},
        {"teal", "#008080"},    {"aqua", "#00ffff"},   {"orange", "#ffa500"},
        {"transparent", "none"}};
    for (const auto& [name, value] : kNamed) {
        if (c == name) return value;
    }
    return c;
}

Result<Drawing> parse_svg(const std::string& text, const std::string& name) {
    tinyxml2::XMLDocument doc;
    if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS) {
        std::string reason = doc.ErrorStr() != nullptr ? doc.ErrorStr() : "parse error";
        return invalid_argument(name + ": not valid XML (" + reason + ")");
    }
    const tinyxml2::XMLElement* root = doc.RootElement();
    if (root == nullptr || std::string(root->Name()) != "svg") {
        return invalid_argument(name + ": not an SVG file (the root element is not <svg>)");
    }
    Drawing drawing;
    if (const char* vb = root->Attribute("viewBox")) {
        Scanner s(vb);
        double v[4] = {0, 0, 0, 0};
        if (!(s.number(v[0]) && s.number(v[1]) && s.number(v[2]) && s.number(v[3])) || v[2] <= 0 ||
            v[3] <= 0) {
            return invalid_argument(name + ": malformed viewBox \"" + vb + "\"");
        }
        drawing.view_x = v[0];
        drawing.view_y = v[1];
        drawing.view_width = v[2];
        drawing.view_height = v[3];
        bool ok = true;
        const double width = attribute(root, "width", 0.0, &ok);
        if (ok && width > 0 && root->Attribute("width") != nullptr &&
            std::string(root->Attribute("width")).find('%') == std::string::npos) {
            drawing.pixels_per_unit = width / v[2];
        }
    }
    Affine identity;
    const std::string error = walk(root, identity, presentation_of(root, {}), drawing);
    if (!error.empty()) return invalid_argument(name + ": " + error);
    return drawing;
}

Result<Drawing> load_svg(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return io_error(path + ": cannot read the file (missing or not readable)");
    std::ostringstream text;
    text << in.rdbuf();
    if (!in.good() && !in.eof()) return io_error(path + ": read error");
    return parse_svg(text.str(), path);
}

std::string path_data(const Path& path) {
    std::string d;
    if (path.empty()) return d;
    auto pt = [](Vec2 p) { return format_number(p.x) + " " + format_number(p.y); };
    // Built by appending: GCC 12 warns falsely (-Wrestrict) about "literal" + std::string&&.
    d.append("M").append(pt(path.start()));
    for (const Cubic& c : path.segments) {
        d.append(" C").append(pt(c.c1)).append(" ").append(pt(c.c2)).append(" ").append(pt(c.p3));
    }
    if (path.closed) d += " Z";
    return d;
}

std::array<double, 4> canvas_bounds(const Drawing& canvas, const std::vector<SvgLayer>& layers) {
    if (canvas.view_width > 0 && canvas.view_height > 0) {
        return {canvas.view_x, canvas.view_y, canvas.view_width, canvas.view_height};
    }
    double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x;
    double hi_x = -lo_x, hi_y = -lo_x;
    for (const SvgLayer& layer : layers) {
        for (const Path& p : layer.paths) {
            for (Vec2 q : flatten(p, 2.0)) {
                lo_x = std::min(lo_x, q.x);
                lo_y = std::min(lo_y, q.y);
                hi_x = std::max(hi_x, q.x);
                hi_y = std::max(hi_y, q.y);
            }
        }
    }
    if (!(hi_x >= lo_x)) return {0, 0, 100, 100};
    const double margin = 0.05 * std::max({hi_x - lo_x, hi_y - lo_y, 1.0});
    return {lo_x - margin, lo_y - margin, hi_x - lo_x + 2 * margin, hi_y - lo_y + 2 * margin};
}

std::string to_svg(const Drawing& canvas, const std::vector<SvgLayer>& layers) {
    const auto box = canvas_bounds(canvas, layers);
    std::ostringstream out;
    out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
        << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" viewBox=\""
        << format_number(box[0]) << ' ' << format_number(box[1]) << ' ' << format_number(box[2])
        << ' ' << format_number(box[3]) << "\">\n";
    for (const SvgLayer& layer : layers) {
        out << "<g";
        if (!layer.name.empty()) out << " id=\"" << xml_escape(layer.name) << '"';
        out << " fill=\"none\" stroke=\"" << xml_escape(layer.stroke) << "\" stroke-width=\""
            << format_number(layer.stroke_width)
            << "\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";
        if (layer.opacity < 1.0) out << " opacity=\"" << format_number(layer.opacity) << '"';
        out << ">\n";
        for (std::size_t i = 0; i < layer.paths.size(); ++i) {
            if (layer.paths[i].empty()) continue;
            out << "<path";
            if (i < layer.ids.size() && !layer.ids[i].empty()) {
                out << " id=\"" << xml_escape(layer.ids[i]) << '"';
            }
            out << " d=\"" << path_data(layer.paths[i]) << "\"/>\n";
        }
        out << "</g>\n";
    }
    out << "</svg>\n";
    return out.str();
}

Status save_text(const std::string& text, const std::string& path) {
    return write_file_atomically(text, path);
}

Status save_svg(const Drawing& canvas, const std::vector<SvgLayer>& layers,
                const std::string& path) {
    return save_text(to_svg(canvas, layers), path);
}

}  // namespace exemplar::sketch
