#pragma once
/// \file
/// Painting and combing strokes and the direction diffusion of Brushables (Lukáč et al. 2015
/// §3.2, eq. 1-3): the target region and its direction field, built stroke by stroke.
///
/// Coordinates are in pixels of the canvas with (0, 0) the top-left corner of the top-left pixel,
/// so pixel (x, y) has its centre at (x + 0.5, y + 0.5) (the SVG convention).
///
/// A stroke's direction at a pixel p is the kernel-weighted average of the stroke's unit tangents
/// (eq. 1), normalized by the integrated kernel weight (eq. 2). The kernel is a Gaussian of
/// σ = width / 2 (the paper) cut off at the support radius 2σ = width and shifted down by its
/// value there, so that it falls continuously to zero: a stroke changes nothing farther than
/// `width` from its centre line (strictly local), and its edge blends without a seam. Along a
/// polyline the tangent is constant per segment and the integral of the kernel over a segment is
/// closed-form (erf), so the diffusion is exact for polylines. The new direction is blended with
/// the existing field (eq. 3) by w_s = w_k(p) / w_line, the integrated weight relative to that
/// of an infinite straight line through p, clamped to [0, 1]: 1 on the centre line of a long
/// stroke, falling to 0 at the support radius.

#include <span>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::paint {

/// A point of a stroke's centre line, in canvas pixels.
struct StrokePoint {
    float x = 0.0f;
    float y = 0.0f;
};

/// One brush stroke: a polyline centre line drawn with a round brush.
struct Stroke {
    std::vector<StrokePoint> points;  ///< Centre line, in drawing order (≥ 1 point).
    /// Brush diameter in pixels (> 0; default 40). A painting stroke covers the swept disc of
    /// radius width / 2; the direction kernel has σ = width / 2 and support radius width.
    float width_px = 40.0f;
    /// A combing stroke changes only the directions of pixels already painted and paints no new
    /// ones; a painting stroke (false, the default) adds its swept disc and gives it direction.
    bool comb = false;
    /// Segment label of a painting stroke (several segmented textures, Brushables §4): its pixels
    /// take only exemplar patches of this segment (`PaintSource::labels`). 0..2^24 − 1 (exact as
    /// a float); default 0. A combing stroke paints no segment: its label must stay 0.
    int label = 0;
};

/// Largest stroke label (2^24 − 1: labels travel as floats, exact up to 2^24; a 24-bit colour).
inline constexpr int max_stroke_label = (1 << 24) - 1;

/// Checks a stroke: at least one point, finite coordinates, 0 < width ≤ 4096 px, label in
/// 0..max_stroke_label (0 for a combing stroke). The message names the field (`points`,
/// `width`, `label`).
Status validate(const Stroke& stroke);

/// A rectangle of pixels [x0, x1) × [y0, y1) (empty when x0 ≥ x1 or y0 ≥ y1).
struct PixelRect {
    int x0 = 0;
    int y0 = 0;
    int x1 = 0;
    int y1 = 0;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
};

/// The diffused direction of several strokes applied together (eq. 1-2 summed over the strokes)
/// before blending: 3 channels "x", "y", "weight" — the normalized direction (zero where no
/// stroke reaches) and w_s (eq. 3's blending weight, in [0, 1]).
/// Nearly collinear points of a stroke are merged into one chord first (each dropped point within
/// min(0.25, width / 400) px of its chord; the integral is exact for straight runs) and erf and
/// exp come from interpolated tables (errors < 1e-7); a chord is cut off at the support less its
/// largest deviation, so nothing farther than `width` from the drawn centre line changes (the
/// weights and weighted directions differ from the reference's by < 3e-3, at the support's fringe).
/// `threads`: 0 = all cores, 1 = inline (the default); the result is the same for any count.
Image diffuse_strokes(std::span<const Stroke> strokes, int width, int height, int threads = 1);

/// diffuse_strokes evaluated segment by segment with libm's erf and exp (no merging, no tables):
/// the reference the fast path is tested against (about 20 times slower for a wide stroke).
Image diffuse_strokes_reference(std::span<const Stroke> strokes, int width, int height);

/// The painted region and its direction field, changed stroke by stroke. Meant for interactive
/// front ends: each call returns the rectangle of pixels it may have changed, so that only that
/// region (grown by the synthesis' patch reach) needs to be synthesized again.
class PaintCanvas {
public:
    /// An empty canvas of `width` × `height` pixels (both ≥ 0).
    PaintCanvas(int width, int height);

    int width() const { return coverage_.width(); }
    int height() const { return coverage_.height(); }

    /// Applies one stroke (painting or combing): a painting stroke adds its swept disc to the
    /// region (and paints its label there, over earlier strokes), and both kinds blend their
    /// diffused direction into the field (eq. 3) — a combing stroke only inside the painted region,
    /// a painting stroke wherever its kernel reaches. Returns the pixels that may have changed (the
    /// stroke's bounding box grown by its support, clipped to the canvas), or the validation error
    /// (the canvas is then unchanged). `threads` for the direction diffusion (0 = all cores, 1 =
    /// inline, the default); the canvas is the same for any count.
    Result<PixelRect> add_stroke(const Stroke& stroke, int threads = 1);

    /// Applies several strokes at once: their kernels are summed before the blend (Brushables
    /// Fig. 4a) rather than blended one after the other. All must be valid (checked first) and of
    /// one kind, painting or combing.
    Result<PixelRect> add_strokes(std::span<const Stroke> strokes, int threads = 1);

    /// The painted region: 1 channel "mask", 1 inside, 0 outside.
    const Image& coverage() const { return coverage_; }
    /// The direction field: 2 channels "x", "y", unit vectors, zero where no stroke has reached.
    const Image& directions() const { return directions_; }
    /// The painted segmentation: 1 channel "label", the label of the last painting stroke that
    /// covered each pixel (0 where none did).
    const Image& labels() const { return labels_; }

private:
    Image coverage_;
    Image directions_;
    Image labels_;
};

}  // namespace exemplar::paint
