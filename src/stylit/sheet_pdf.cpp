// The painting sheet as a one-page PDF (Cairo's PDF surface), centred on the paper at a chosen
// or the largest fitting resolution: the render as an image, the alignment marks as vector
// paths (filled rings), so they print sharp whatever the printer's resolution. Cairo is called
// through its plugin (src/plugin/cairo_canvas.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>
#include <vector>

#include "cairo_canvas.hpp"
#include "exemplar/io/atomic_write.hpp"
#include "exemplar/stylit/sheet.hpp"
#include "marks.hpp"

namespace exemplar {

namespace {

constexpr double kPointsPerInch = 72.0;
constexpr double kBorderPt = 10.0 / 25.4 * kPointsPerInch;  // 10 mm unprinted border

struct Paper {
    const char* name;
    double width_pt;  // portrait
    double height_pt;
};
constexpr Paper kPapers[] = {
    {"a4", 595.276, 841.890}, {"a3", 841.890, 1190.551}, {"letter", 612.0, 792.0}};

// The marks as filled paths, in sheet pixel coordinates: each black band is a disc with the
// inner disc cut out (even-odd rule).
void draw_marks(plugin::cairo::Canvas& canvas, const SheetLayout& layout) {
    const std::array<Point2, 4> centres = layout.mark_centres();
    const double radius = layout.mark_radius_px;
    // Pixel centres are at integers: pixel (0, 0) covers [0, 1] in Cairo's coordinates.
    const double shift = layout.margin_px + 0.5;
    canvas.set_source_rgb(0.0, 0.0, 0.0);
    canvas.set_even_odd_fill();
    for (std::size_t m = 0; m < centres.size(); ++m) {
        const double cx = centres[m].x + shift, cy = centres[m].y + shift;
        for (const marks::Band& band : marks::bands(m == 0)) {
            canvas.new_path();
            canvas.arc(cx, cy, band.outer * radius, 0.0, 2.0 * std::numbers::pi);
            canvas.close_path();
            if (band.inner > 0.0) {
                canvas.new_sub_path();
                canvas.arc(cx, cy, band.inner * radius, 0.0, 2.0 * std::numbers::pi);
                canvas.close_path();
            }
            canvas.fill();
        }
    }
}

}  // namespace

Status save_sheet_pdf(const Image& content, const SheetLayout& layout, const std::string& path,
                      const PdfOptions& options) {
    const Paper* paper = nullptr;
    for (const Paper& p : kPapers) {
        if (options.paper == p.name) paper = &p;
    }
    if (paper == nullptr) {
        return invalid_argument("--paper " + options.paper + ": unknown (use a4, a3 or letter)");
    }
    if (!(options.dpi >= 0.0 && options.dpi <= 4800.0)) {
        return invalid_argument("--dpi " + std::to_string(options.dpi) +
                                ": is invalid (must be 0..4800; 0 = fit the paper)");
    }
    if (content.empty() || (content.channels() != 1 && content.channels() != 3)) {
        return invalid_argument(path + ": the sheet's render must have 1 or 3 channels");
    }
    if (content.width() != layout.render_width || content.height() != layout.render_height) {
        return invalid_argument(path + ": the render is " + std::to_string(content.width()) + "x" +
                                std::to_string(content.height()) + " but the layout is for " +
                                std::to_string(layout.render_width) + "x" +
                                std::to_string(layout.render_height));
    }
    const int sheet_width = layout.sheet_width(), sheet_height = layout.sheet_height();

    // Orientation and scale: the sheet as large as fits, unless a resolution is given.
    const bool landscape = sheet_width > sheet_height;
    const double page_w = landscape ? paper->height_pt : paper->width_pt;
    const double page_h = landscape ? paper->width_pt : paper->height_pt;
    const double fit_pt_per_px =
        std::min((page_w - 2 * kBorderPt) / sheet_width, (page_h - 2 * kBorderPt) / sheet_height);
    double pt_per_px = fit_pt_per_px;
    if (options.dpi > 0.0) {
        pt_per_px = kPointsPerInch / options.dpi;
        if (pt_per_px > fit_pt_per_px * (1.0 + 1e-9)) {
            const double min_dpi = std::ceil(kPointsPerInch / fit_pt_per_px);
            return invalid_argument("--dpi " + std::to_string(static_cast<int>(options.dpi)) +
                                    ": the " + std::to_string(sheet_width) + "x" +
                                    std::to_string(sheet_height) + " px sheet does not fit " +
                                    options.paper + " paper (use at least " +
                                    std::to_string(static_cast<int>(min_dpi)) + " dpi)");
        }
    }

    auto cairo = plugin::cairo::canvases();
    if (!cairo.ok()) return Status(cairo.status().code(), path + ": " + cairo.status().message());

    // The render as 0x00RRGGBB pixels (Cairo's RGB24).
    std::vector<std::uint32_t> pixels(static_cast<std::size_t>(content.width()) * content.height());
    const auto to_byte = [](float v) {
        return static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    };
    for (int y = 0; y < content.height(); ++y) {
        std::uint32_t* row = pixels.data() + static_cast<std::size_t>(y) * content.width();
        for (int x = 0; x < content.width(); ++x) {
            const float* px = content.pixel(x, y);
            const std::uint32_t r = to_byte(px[0]);
            const std::uint32_t g = content.channels() == 3 ? to_byte(px[1]) : r;
            const std::uint32_t b = content.channels() == 3 ? to_byte(px[2]) : r;
            row[x] = (r << 16) | (g << 8) | b;
        }
    }

    // One page, the sheet centred: white paper, the render at the margin, the marks.
    std::string pdf;
    {
        const std::unique_ptr<plugin::cairo::Canvas> cr = (*cairo)->new_pdf(page_w, page_h, &pdf);
        const double w = sheet_width * pt_per_px;
        const double h = sheet_height * pt_per_px;
        cr->translate((page_w - w) / 2.0, (page_h - h) / 2.0);
        cr->scale(pt_per_px, pt_per_px);
        if (!cr->paint_image(pixels.data(), content.width(), content.height(), layout.margin_px,
                             layout.margin_px)) {
            return io_error(path + ": cannot create the render image (Cairo)");
        }
        draw_marks(*cr, layout);
        const std::string error = cr->finish();
        if (!error.empty())
            return io_error(path + ": Cairo could not draw the PDF (" + error + ")");
    }
    return write_file_atomically(pdf, path);
}

}  // namespace exemplar
