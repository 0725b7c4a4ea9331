#pragma once
/// \file
/// Aligning a scan or photo of a painted sheet to the render it was printed from (§8.3.1): find
/// the four alignment marks of sheet.hpp, estimate the projective transform (homography) from
/// render coordinates to scan coordinates, and resample the scan on the render's pixel grid.
///
/// Mark detection (OpenCV): the scan is converted to grey and binarized with a local (adaptive)
/// threshold at a few window sizes, so brightness, contrast, gamma and uneven lighting do not
/// matter; a mark is a chain of nested contours with nearly the same centre (a bull's-eye), and
/// the top-left mark is the one with the deeper chain. Rotation, scale, mild perspective and
/// noise are tolerated; a mirrored scan is not.

#include <array>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/stylit/sheet.hpp"

namespace exemplar {

/// Row-major 3x3 homography mapping homogeneous render coordinates to scan coordinates.
using Homography = std::array<double, 9>;

/// Applies a homography to a point.
Point2 apply_homography(const Homography& h, Point2 p);

/// Finds the mark centres in a scan (any channel count; colour is averaged to grey), in the
/// order of SheetLayout::mark_centres (top-left, top-right, bottom-right, bottom-left of the
/// sheet). Fails (InvalidArgument) with what was found when there are not one distinguished
/// and three plain marks.
Result<std::array<Point2, 4>> find_marks(const Image& scan);

/// Result of aligning a scan.
struct AlignedScan {
    Image image;                    ///< The scan on the render grid (render size).
    Homography render_to_scan{};    ///< Render coordinates -> scan coordinates.
    std::array<Point2, 4> marks{};  ///< Mark centres found in the scan.
};

/// Finds the marks, fits the homography mapping layout.mark_centres() onto them, and resamples
/// the scan (bilinear, borders clamped) at every render pixel. Keeps the scan's channels.
Result<AlignedScan> align_scan(const Image& scan, const SheetLayout& layout);

}  // namespace exemplar
