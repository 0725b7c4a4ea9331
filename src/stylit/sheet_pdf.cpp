// The painting sheet as a one-page PDF (Cairo's PDF surface), centred on the paper at a chosen
// or the largest fitting resolution: the render as an image, the alignment marks as vector
// paths (filled rings), so they print sharp whatever the printer's resolution.

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>

#include "atomic_file.hpp"
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

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
}

// Writes `bytes` to `path` through a temporary file in the same folder (created if missing) and
// a rename.
Status write_atomically(const std::string& bytes, const std::string& path) {
    io_detail::TempFile temp(path);
    EXEMPLAR_RETURN_IF_ERROR(temp.status());
    {
        std::ofstream out(temp.path(), std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        out.close();
        if (!out) return io_error(path + ": cannot write (disk full or not writable)");
    }
    return temp.commit();
}

// The marks as filled paths, in sheet pixel coordinates: each black band is a disc with the
// inner disc cut out (even-odd rule).
void draw_marks(cairo_t* cr, const SheetLayout& layout) {
    const std::array<Point2, 4> centres = layout.mark_centres();
    const double radius = layout.mark_radius_px;
    // Pixel centres are at integers: pixel (0, 0) covers [0, 1] in Cairo's coordinates.
    const double shift = layout.margin_px + 0.5;
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
    for (std::size_t m = 0; m < centres.size(); ++m) {
        const double cx = centres[m].x + shift, cy = centres[m].y + shift;
        for (const marks::Band& band : marks::bands(m == 0)) {
            cairo_new_path(cr);
            cairo_arc(cr, cx, cy, band.outer * radius, 0.0, 2.0 * std::numbers::pi);
            cairo_close_path(cr);
            if (band.inner > 0.0) {
                cairo_new_sub_path(cr);
                cairo_arc(cr, cx, cy, band.inner * radius, 0.0, 2.0 * std::numbers::pi);
                cairo_close_path(cr);
            }
            cairo_fill(cr);
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

    // The render as an RGB24 Cairo image.
    using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
    SurfacePtr image(
        cairo_image_surface_create(CAIRO_FORMAT_RGB24, content.width(), content.height()),
        &cairo_surface_destroy);
    if (cairo_surface_status(image.get()) != CAIRO_STATUS_SUCCESS) {
        return io_error(path + ": cannot create the render image (Cairo)");
    }
    cairo_surface_flush(image.get());
    unsigned char* bytes = cairo_image_surface_get_data(image.get());
    const int stride = cairo_image_surface_get_stride(image.get());
    const auto to_byte = [](float v) {
        return static_cast<std::uint32_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    };
    for (int y = 0; y < content.height(); ++y) {
        auto* row = reinterpret_cast<std::uint32_t*>(bytes + static_cast<std::size_t>(y) * stride);
        for (int x = 0; x < content.width(); ++x) {
            const float* px = content.pixel(x, y);
            const std::uint32_t r = to_byte(px[0]);
            const std::uint32_t g = content.channels() == 3 ? to_byte(px[1]) : r;
            const std::uint32_t b = content.channels() == 3 ? to_byte(px[2]) : r;
            row[x] = (r << 16) | (g << 8) | b;
        }
    }
    cairo_surface_mark_dirty(image.get());

    // One page, the sheet centred: white paper, the render at the margin, the marks.
    std::string pdf;
    {
        SurfacePtr surface(cairo_pdf_surface_create_for_stream(&append, &pdf, page_w, page_h),
                           &cairo_surface_destroy);
        cairo_t* cr = cairo_create(surface.get());
        const double w = sheet_width * pt_per_px;
        const double h = sheet_height * pt_per_px;
        cairo_translate(cr, (page_w - w) / 2.0, (page_h - h) / 2.0);
        cairo_scale(cr, pt_per_px, pt_per_px);
        cairo_set_source_surface(cr, image.get(), layout.margin_px, layout.margin_px);
        cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
        cairo_paint(cr);
        draw_marks(cr, layout);
        cairo_show_page(cr);
        const cairo_status_t status = cairo_status(cr);
        cairo_destroy(cr);
        cairo_surface_finish(surface.get());
        if (status != CAIRO_STATUS_SUCCESS ||
            cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS) {
            return io_error(path + ": Cairo could not draw the PDF (" +
                            cairo_status_to_string(status) + ")");
        }
    }
    return write_atomically(pdf, path);
}

}  // namespace exemplar
