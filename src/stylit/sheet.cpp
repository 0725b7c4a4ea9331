// The painting sheet of the StyLit workflow (Fišer et al. 2016, §8.3.1): the exemplar render in
// low contrast with alignment marks. The paper does not describe its marks; ours are
// bull's-eyes (concentric rings), which keep their nesting under rotation, scale, perspective
// and relighting, and whose centre is the centroid of a symmetric shape.

#include "exemplar/stylit/sheet.hpp"

#include <algorithm>
#include <cmath>

#include "exemplar/core/check.hpp"
#include "marks.hpp"

namespace exemplar {

namespace {

bool is_black(double r, bool corner) {
    const auto in = [r](const marks::Band& band) { return r <= band.outer && r >= band.inner; };
    const auto bands = marks::bands(corner);
    return std::any_of(bands.begin(), bands.end(), in);
}

// Ink coverage of the pixel centred at (x, y) by a mark at `centre` (4x4 supersampling).
double coverage(double x, double y, Point2 centre, double radius, bool corner) {
    constexpr int kSamples = 4;
    int black = 0;
    for (int j = 0; j < kSamples; ++j) {
        for (int i = 0; i < kSamples; ++i) {
            const double sx = x - 0.5 + (i + 0.5) / kSamples - centre.x;
            const double sy = y - 0.5 + (j + 0.5) / kSamples - centre.y;
            if (is_black(std::sqrt(sx * sx + sy * sy) / radius, corner)) ++black;
        }
    }
    return static_cast<double>(black) / (kSamples * kSamples);
}

}  // namespace

std::array<Point2, 4> SheetLayout::mark_centres() const {
    const double left = -0.5 - mark_offset_px;
    const double top = -0.5 - mark_offset_px;
    const double right = render_width - 0.5 + mark_offset_px;
    const double bottom = render_height - 0.5 + mark_offset_px;
    return {Point2{left, top}, Point2{right, top}, Point2{right, bottom}, Point2{left, bottom}};
}

SheetLayout sheet_layout(int render_width, int render_height) {
    EXEMPLAR_CHECK(render_width >= 1 && render_height >= 1);
    SheetLayout layout;
    layout.render_width = render_width;
    layout.render_height = render_height;
    layout.mark_radius_px =
        std::max(20.0, std::round(0.045 * std::min(render_width, render_height)));
    layout.mark_offset_px = 2.0 * layout.mark_radius_px;
    layout.margin_px = static_cast<int>(std::ceil(3.5 * layout.mark_radius_px));
    return layout;
}

Image low_contrast(const Image& render, float low, float high) {
    Image out(render.width(), render.height(), 1);
    out.set_channel_names({"Y"});
    const int channels = render.channels();
    for (std::size_t p = 0; p < render.pixel_count(); ++p) {
        const float* px = render.data().data() + p * static_cast<std::size_t>(channels);
        float y = channels >= 3 ? 0.2126f * px[0] + 0.7152f * px[1] + 0.0722f * px[2] : px[0];
        if (!(y >= 0.0f)) y = 0.0f;  // NaN too
        y = std::min(y, 1.0f);
        out.data()[p] = low + (high - low) * y;
    }
    return out;
}

Result<Image> make_sheet(const Image& content, const SheetLayout& layout) {
    if (content.width() != layout.render_width || content.height() != layout.render_height) {
        return invalid_argument("sheet: the content is " + std::to_string(content.width()) + "x" +
                                std::to_string(content.height()) + " but the layout is for " +
                                std::to_string(layout.render_width) + "x" +
                                std::to_string(layout.render_height));
    }
    if (content.channels() < 1 || content.channels() > 4) {
        return invalid_argument("sheet: the content has " + std::to_string(content.channels()) +
                                " channels (must be 1..4)");
    }
    const int channels = content.channels();
    Image sheet(layout.sheet_width(), layout.sheet_height(), channels, 1.0f);
    sheet.set_channel_names(content.channel_names());
    for (int y = 0; y < content.height(); ++y) {
        std::copy_n(content.pixel(0, y), static_cast<std::size_t>(content.width() * channels),
                    sheet.pixel(layout.margin_px, y + layout.margin_px));
    }

    // The marks: ink darkens the colour channels (not alpha).
    const int colour_channels = channels == 2 || channels == 4 ? channels - 1 : channels;
    const std::array<Point2, 4> centres = layout.mark_centres();
    const double radius = layout.mark_radius_px;
    for (std::size_t m = 0; m < centres.size(); ++m) {
        const Point2 c{centres[m].x + layout.margin_px, centres[m].y + layout.margin_px};
        const int x0 = std::max(0, static_cast<int>(std::floor(c.x - radius - 1)));
        const int x1 = std::min(sheet.width() - 1, static_cast<int>(std::ceil(c.x + radius + 1)));
        const int y0 = std::max(0, static_cast<int>(std::floor(c.y - radius - 1)));
        const int y1 = std::min(sheet.height() - 1, static_cast<int>(std::ceil(c.y + radius + 1)));
        for (int y = y0; y <= y1; ++y) {
            for (int x = x0; x <= x1; ++x) {
                const double ink = coverage(x, y, c, radius, m == 0);
                if (ink <= 0.0) continue;
                float* px = sheet.pixel(x, y);
                for (int k = 0; k < colour_channels; ++k) {
                    px[k] = static_cast<float>(px[k] * (1.0 - ink));
                }
            }
        }
    }
    return sheet;
}

}  // namespace exemplar
