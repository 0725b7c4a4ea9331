// PNG rendering of stroke layers with Cairo (the examples' before/after pictures).

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "atomic_file.hpp"
#include "exemplar/sketch/svg.hpp"

namespace exemplar::sketch {

namespace {

// "black", "#rrggbb" and a few names the examples use; anything else draws black.
void set_colour(cairo_t* cr, const std::string& colour, double opacity) {
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
    cairo_set_source_rgba(cr, r, g, b, opacity);
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
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px);
    cairo_t* cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_scale(cr, scale, scale);
    cairo_translate(cr, -box[0], -box[1]);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (const SvgLayer& layer : layers) {
        set_colour(cr, layer.stroke, layer.opacity);
        cairo_set_line_width(cr, layer.stroke_width);
        for (const Path& p : layer.paths) {
            if (p.empty()) continue;
            cairo_new_path(cr);
            cairo_move_to(cr, p.start().x, p.start().y);
            for (const Cubic& c : p.segments) {
                cairo_curve_to(cr, c.c1.x, c.c1.y, c.c2.x, c.c2.y, c.p3.x, c.p3.y);
            }
            if (p.closed) cairo_close_path(cr);
            cairo_stroke(cr);
        }
    }
    cairo_destroy(cr);
    io_detail::TempFile temp(path);
    Status status = temp.status();
    if (status.is_ok() &&
        cairo_surface_write_to_png(surface, temp.path().c_str()) != CAIRO_STATUS_SUCCESS) {
        status = io_error(path + ": cannot write the PNG");
    }
    cairo_surface_destroy(surface);
    EXEMPLAR_RETURN_IF_ERROR(status);
    return temp.commit();
}

}  // namespace exemplar::sketch
