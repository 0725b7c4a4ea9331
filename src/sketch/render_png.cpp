// PNG rendering of stroke layers with Cairo (the examples' before/after pictures), through its
// plugin (src/plugin/cairo_canvas.hpp).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "atomic_file.hpp"
#include "cairo_canvas.hpp"
#include "exemplar/sketch/svg.hpp"

namespace exemplar::sketch {

namespace {

// "black", "#rrggbb" and a few names the examples use; anything else draws black.
void set_colour(plugin::cairo::Canvas& canvas, const std::string& colour, double opacity) {
    double r = 0, g = 0, b = 0;
    unsigned value = 0;
    if (colour.size() == 7 && colour[0] == '#' &&
        std::sscanf(colour.c_str() + 1, "%x", &value) == 1) {
        r = ((value >> 16) & 0xff) / 255.0;
        g = ((value >> 8) & 0xff) / 255.0;
        b = (value & 0xff) / 255.0;
    } else if (colour == "red") {
        r = 0.85;
    } else if (colour == "blue") {
        r = 0.1, g = 0.35, b = 0.9;
    } else if (colour == "gray" || colour == "grey") {
        r = g = b = 0.6;
    }
    canvas.set_source_rgba(r, g, b, opacity);
}

}  // namespace

Status save_png(const Drawing& canvas, const std::vector<SvgLayer>& layers, const std::string& path,
                int width_px) {
    if (width_px < 16 || width_px > 8192) {
        return invalid_argument(std::string("png width: ") + std::to_string(width_px) +
                                " is invalid (must be 16..8192)");
    }
    const auto box = canvas_bounds(canvas, layers);
    const double scale = width_px / box[2];
    const int height_px = std::max(1, static_cast<int>(std::lround(box[3] * scale)));
    auto cairo = plugin::cairo::canvases();
    if (!cairo.ok()) return Status(cairo.status().code(), path + ": " + cairo.status().message());
    const std::unique_ptr<plugin::cairo::Canvas> cr = (*cairo)->new_image(width_px, height_px);
    cr->set_source_rgb(1, 1, 1);
    cr->paint();
    cr->scale(scale, scale);
    cr->translate(-box[0], -box[1]);
    cr->set_round_lines();
    for (const SvgLayer& layer : layers) {
        set_colour(*cr, layer.stroke, layer.opacity);
        cr->set_line_width(layer.stroke_width);
        for (const Path& p : layer.paths) {
            if (p.empty()) continue;
            cr->new_path();
            cr->move_to(p.start().x, p.start().y);
            for (const Cubic& c : p.segments) {
                cr->curve_to(c.c1.x, c.c1.y, c.c2.x, c.c2.y, c.p3.x, c.p3.y);
            }
            if (p.closed) cr->close_path();
            cr->stroke();
        }
    }
    io_detail::TempFile temp(path);
    EXEMPLAR_RETURN_IF_ERROR(temp.status());
    if (!cr->write_png(temp.path())) return io_error(path + ": cannot write the PNG");
    return temp.commit();
}

}  // namespace exemplar::sketch
