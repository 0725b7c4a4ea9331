#pragma once
/// \file
/// As-rigid-as-possible image deformation by moving least squares (Schaefer, McPhail and Warren
/// 2006, "Image Deformation Using Moving Least Squares", §2.3 rigid deformations), and the
/// random lattice jitter Color Me Noisy (Fišer et al. 2014, thesis §4.3.2) pre-deforms its
/// source drawing medium with before every frame.
///
/// Coordinates are pixel centres in pixels, (0,0) top-left, x right, y down.

#include <cstdint>
#include <span>
#include <vector>

#include "exemplar/core/image.hpp"

namespace exemplar::noisy {

/// A point or offset in pixels.
struct Point {
    double x = 0.0;
    double y = 0.0;
};

/// Control points of a deformation: `from[i]` is moved to `to[i]`. Equal lengths.
struct ControlPoints {
    std::vector<Point> from;
    std::vector<Point> to;
};

/// The rigid MLS deformation f(v) of Schaefer et al. 2006 with weights
/// 1 / (|from_i - v|^2 + smoothing_px^2): the rotation and translation that best map the
/// weighted `from` points onto the `to` points (weighted Procrustes) applied to v. With
/// smoothing 0 (α = 1 of the paper) f(from_i) = to_i exactly. Any smoothing keeps: zero offsets
/// give the identity and a rigid motion of all points is reproduced exactly everywhere.
/// Smoothing > 0 (our deviation) removes the singularity of the weights at the control points,
/// around which the paper's map rotates each ray by its own angle and folds over for large
/// offsets; the points are then approximated, not interpolated. Requires at least one point,
/// equal lengths and smoothing ≥ 0 (checked).
Point mls_rigid(const ControlPoints& points, Point v, double smoothing_px = 0.0);

/// A point of the deformation and its local rotation: f(v) = rotation (v - p*) + q*, the
/// rotation by `angle_rad` (x towards y, in image coordinates).
struct MlsSample {
    Point position;
    double angle_rad = 0.0;
};

/// mls_rigid with its rotation angle.
MlsSample mls_rigid_sample(const ControlPoints& points, Point v, double smoothing_px = 0.0);

/// Smoothing (in pixels) that the random pre-deformation uses for a lattice of spacing
/// `spacing_px`: 0.4 × spacing. At the chapter's values (spacing 50, offsets 15..25 px) the
/// paper's unsmoothed map folds over in nearly every draw while this one stays fold-free
/// (tested); the lattice points then move about half their offset (measured in docs/noisy.md).
inline double lattice_smoothing_px(double spacing_px) {
    return 0.4 * spacing_px;
}

/// Lattice of control points every `spacing_px` pixels covering [0, width-1] x [0, height-1]
/// (one extra row and column past the far border so the whole image lies inside the lattice),
/// each moved by a random offset of length uniform in [min_offset_px, max_offset_px] in a
/// uniformly random direction. A pure function of `key`. The chapter's values: spacing 50 px,
/// offsets 15..25 px. Requires width, height ≥ 1, spacing > 0 and 0 ≤ min ≤ max (checked).
ControlPoints jittered_lattice(int width, int height, double spacing_px, double min_offset_px,
                               double max_offset_px, std::uint64_t key);

/// The deformation sampled at every pixel centre: a 2-channel image (x, y) with
/// mls_rigid(points, (x, y), smoothing_px). Bit-identical for any `threads` (0 = all cores,
/// 1 = inline).
Image mls_rigid_map(const ControlPoints& points, int width, int height, double smoothing_px,
                    int threads = 0);

/// `image` deformed by the rigid MLS map of `points`, by backward mapping: output pixel v takes
/// the bilinear sample of `image` at mls_rigid(inverse points, v, smoothing_px), i.e. with the
/// roles of `from` and `to` swapped, so a feature at from_i ends up near to_i. Positions outside
/// the image are mirrored back into it (the drawing medium continues as its mirror image, with no
/// smeared edge pixels). Same size and channels as `image`; bit-identical for any `threads`.
Image deform_rigid(const Image& image, const ControlPoints& points, double smoothing_px,
                   int threads = 0);

/// An orientation field (1 channel, angles in radians) deformed like deform_rigid deforms the
/// image it belongs to: output pixel v takes the nearest sample at the same position and adds
/// the deformation's local rotation there, so the angles keep following the deformed strokes.
/// Same size; bit-identical for any `threads`.
Image deform_rigid_angles(const Image& angles, const ControlPoints& points, double smoothing_px,
                          int threads = 0);

}  // namespace exemplar::noisy
