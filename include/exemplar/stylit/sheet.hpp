#pragma once
/// \file
/// The printable painting sheet of the StyLit workflow (§8.3.1): the exemplar render in low
/// contrast, so that paint covers it, framed by four alignment marks that `align_scan` finds in
/// a scan or photo of the painted sheet.
///
/// Coordinates are render pixels with pixel centres at integers: the render covers
/// [-0.5, W - 0.5] x [-0.5, H - 0.5]. The marks sit outside the render's corners, on the
/// diagonal, so paint on the render does not cover them. Each mark is a bull's-eye (black ring,
/// white ring, black dot); the top-left one has two black rings, which tells the sheet's
/// orientation in a rotated scan.

#include <array>
#include <string>
#include <string_view>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar {

/// A point in pixel coordinates (pixel centres at integers).
struct Point2 {
    double x = 0.0;
    double y = 0.0;
};

/// Geometry of a sheet, in render pixels. A function of the render size only (sheet_layout), so
/// that `align` can rebuild it from the render alone.
struct SheetLayout {
    int render_width = 0;
    int render_height = 0;
    double mark_radius_px = 0.0;  ///< Outer radius of a mark.
    double mark_offset_px = 0.0;  ///< Distance of a mark centre from the render corner, per axis.
    int margin_px = 0;            ///< White border around the render on the sheet.

    int sheet_width() const { return render_width + 2 * margin_px; }
    int sheet_height() const { return render_height + 2 * margin_px; }
    /// Mark centres in render coordinates: top-left (the distinguished one), top-right,
    /// bottom-right, bottom-left.
    std::array<Point2, 4> mark_centres() const;
};

/// The layout for a render: mark radius max(20, 4.5% of the shorter side), offset 2 radii,
/// margin 3.5 radii. Width and height must be ≥ 1 (checked).
SheetLayout sheet_layout(int render_width, int render_height);

/// Maps a render to a light grey range: luminance (Rec. 709 weights, 1 channel input as is)
/// scaled from [0, 1] to [low, high] (e.g. 0.72..0.95), one channel. Float renders are clamped
/// to [0, 1] first.
Image low_contrast(const Image& render, float low, float high);

/// The sheet: white paper of layout.sheet_width() x sheet_height() with `content` (the render's
/// size, any channel count ≤ 4) placed at the margin and the four marks drawn (anti-aliased)
/// in black. The result has content's channels (alpha, if any, is 1 on the paper).
/// `content` must have the layout's render size (InvalidArgument otherwise).
Result<Image> make_sheet(const Image& content, const SheetLayout& layout);

/// Paper for the PDF.
struct PdfOptions {
    std::string paper = "a4";  ///< "a4", "a3", "letter" (portrait or landscape, as fits best).
    /// Print resolution of the sheet image in dots per inch; 0 = as large as fits the paper
    /// inside a 10 mm border (default). A resolution at which the sheet does not fit is
    /// rejected with the smallest that fits.
    double dpi = 0.0;
};

/// Writes the sheet of `layout` as a one-page PDF (Cairo), atomically (temporary file +
/// rename): white paper, `content` (the render's size, 1 or 3 channels in [0, 1], e.g. the
/// output of low_contrast) as an image at the margin, and the four marks as vector paths
/// (filled rings), so they print sharp at any resolution. The page looks like make_sheet's
/// image. Errors name the file or the option.
Status save_sheet_pdf(const Image& content, const SheetLayout& layout, const std::string& path,
                      const PdfOptions& options);

}  // namespace exemplar
