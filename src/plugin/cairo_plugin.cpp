// Cairo behind cairo_canvas.hpp, built as the plugin libexemplar_cairo.so (the header says why).
// It links no exemplar library.

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cstring>

#include "cairo_canvas.hpp"

namespace exemplar::plugin::cairo {
namespace {

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

class CairoCanvas final : public Canvas {
public:
    CairoCanvas(cairo_surface_t* surface, bool pdf)
        : surface_(surface), cr_(cairo_create(surface)), pdf_(pdf) {}
    ~CairoCanvas() override {
        cairo_destroy(cr_);
        cairo_surface_destroy(surface_);
    }
    CairoCanvas(const CairoCanvas&) = delete;
    CairoCanvas& operator=(const CairoCanvas&) = delete;

    void translate(double x, double y) override { cairo_translate(cr_, x, y); }
    void scale(double sx, double sy) override { cairo_scale(cr_, sx, sy); }
    void set_source_rgb(double r, double g, double b) override {
        cairo_set_source_rgb(cr_, r, g, b);
    }
    void set_source_rgba(double r, double g, double b, double a) override {
        cairo_set_source_rgba(cr_, r, g, b, a);
    }
    void paint() override { cairo_paint(cr_); }
    void set_round_lines() override {
        cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
        cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
    }
    void set_line_width(double width) override { cairo_set_line_width(cr_, width); }
    void set_even_odd_fill() override { cairo_set_fill_rule(cr_, CAIRO_FILL_RULE_EVEN_ODD); }
    void new_path() override { cairo_new_path(cr_); }
    void new_sub_path() override { cairo_new_sub_path(cr_); }
    void move_to(double x, double y) override { cairo_move_to(cr_, x, y); }
    void curve_to(double x1, double y1, double x2, double y2, double x3, double y3) override {
        cairo_curve_to(cr_, x1, y1, x2, y2, x3, y3);
    }
    void arc(double cx, double cy, double radius, double from_rad, double to_rad) override {
        cairo_arc(cr_, cx, cy, radius, from_rad, to_rad);
    }
    void close_path() override { cairo_close_path(cr_); }
    void stroke() override { cairo_stroke(cr_); }
    void fill() override { cairo_fill(cr_); }

    bool paint_image(const std::uint32_t* pixels, int width, int height, double x,
                     double y) override {
        cairo_surface_t* image = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
        if (cairo_surface_status(image) != CAIRO_STATUS_SUCCESS) {
            cairo_surface_destroy(image);
            return false;
        }
        cairo_surface_flush(image);
        unsigned char* bytes = cairo_image_surface_get_data(image);
        const int stride = cairo_image_surface_get_stride(image);
        for (int row = 0; row < height; ++row) {
            std::memcpy(bytes + static_cast<std::size_t>(row) * stride,
                        pixels + static_cast<std::size_t>(row) * width,
                        static_cast<std::size_t>(width) * sizeof(std::uint32_t));
        }
        cairo_surface_mark_dirty(image);
        cairo_set_source_surface(cr_, image, x, y);
        cairo_pattern_set_filter(cairo_get_source(cr_), CAIRO_FILTER_NEAREST);
        cairo_paint(cr_);
        cairo_surface_destroy(image);  // the context's source keeps its own reference
        return true;
    }

    std::string finish() override {
        if (pdf_) cairo_show_page(cr_);
        cairo_status_t status = cairo_status(cr_);
        cairo_surface_finish(surface_);
        if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface_);
        return status == CAIRO_STATUS_SUCCESS ? std::string() : cairo_status_to_string(status);
    }

    bool write_png(const std::string& path) override {
        return cairo_surface_write_to_png(surface_, path.c_str()) == CAIRO_STATUS_SUCCESS;
    }

private:
    cairo_surface_t* surface_;
    cairo_t* cr_;
    bool pdf_;
};

std::unique_ptr<Canvas> new_image(int width, int height) {
    return std::make_unique<CairoCanvas>(
        cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height), false);
}

std::unique_ptr<Canvas> new_pdf(double width_pt, double height_pt, std::string* pdf) {
    return std::make_unique<CairoCanvas>(
        cairo_pdf_surface_create_for_stream(&append, pdf, width_pt, height_pt), true);
}

constexpr Entry kEntry{kPlugin.abi_version, &new_image, &new_pdf};

}  // namespace
}  // namespace exemplar::plugin::cairo

// The plugin's one exported symbol (cairo::kPlugin); also linked into libexemplar.so and
// the Python module, where cairo::canvases() calls it directly.
extern "C" __attribute__((visibility("default"))) const exemplar::plugin::cairo::Entry*
exemplar_cairo_entry() {
    return &exemplar::plugin::cairo::kEntry;
}
