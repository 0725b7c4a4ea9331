#pragma once
/// \file
/// Operations on offset fields (NNFs) used by the temporally coherent solver (Bénard et al.
/// 2013 §3.3): advection along a flow field with nearest-sample lookup and extrapolation by the
/// match's rotation, upsampling to a finer pyramid level, and the per-pixel random merge of two
/// candidate fields (with a fresh or a fixed draw per pixel), the dot screen of the fixed draw,
/// and the input time-derivative guide built from a neighbour's offsets.
/// Entries with x = y = -1 are "no match" (the engine draws a random match).

#include <cstdint>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/synth/nnf.hpp"

namespace exemplar::animate {

/// Advects the field `from` (on the grid of frame s) to frame t: for each pixel p of t with
/// visible(p) > 0.5, q = p + flow(p) is p's position in frame s (flow on t's grid, pointing into
/// s, e.g. the backward flow of t for s = t − 1); the nearest sample p̃ = round(q) is looked up
/// and the sub-pixel rest is extrapolated through the match's rotation:
///     M_t(p) = M_s(p̃) + Rot(angle) (q − p̃)   (rounded to the nearest source pixel).
/// Entries are -1 where p is not visible, q falls outside, M_s(p̃) is "no match" or the result
/// leaves the style (`style_width` x `style_height`). No interpolation between offsets (the
/// paper: it produces spurious offsets across discontinuities). `visible` may be empty (all
/// visible). Sizes must agree (checked).
Nnf advect_nnf(const Nnf& from, const Image& flow, const Image& visible, int style_width,
               int style_height);

/// A rectangle of the source (style) image that scales on its own between pyramid levels:
/// the solver's source is an atlas of the style and the painted keyframes side by side.
struct AtlasSlot {
    int x0 = 0;     ///< Left column in the atlas (the top row is 0).
    int width = 0;  ///< Size at this level.
    int height = 0;
};

/// The field of a coarser level on the grid of a finer one (`width` x `height`): the nearest
/// coarse sample, its position mapped from its slot of `coarse_slots` to the same slot of
/// `fine_slots` (same count and order), the sub-pixel rest extrapolated through the match's
/// rotation as in advect_nnf. Matches outside every slot, or leaving their slot, become
/// "no match". One slot covering the style is the plain case.
Nnf upsample_nnf(const Nnf& coarse, const std::vector<AtlasSlot>& coarse_slots, int width,
                 int height, const std::vector<AtlasSlot>& fine_slots);

/// Per-pixel random merge of two candidate fields of the same size: pixel i takes `a` with
/// probability `probability_a` and `b` otherwise, decided by a counter-based random number of
/// (key, i) (deterministic). Where one candidate is "no match" the other is used.
Nnf random_merge(const Nnf& a, const Nnf& b, float probability_a, std::uint64_t key);

/// The merge with a given draw per pixel instead of a fresh one: pixel i takes `a` where
/// draw(i) < `probability_a` and `b` otherwise (`draw`: 1 channel, the fields' size, values in
/// [0, 1)); where one candidate is "no match" the other is used. With one draw for every frame
/// of a shot and a probability that falls over time, the set of pixels that take `b` only
/// grows: a dissolve from a to b, each pixel switching once.
Nnf threshold_merge(const Nnf& a, const Nnf& b, float probability_a, const Image& draw);

/// The fixed draw of a dissolve, a stochastic clustered-dot screen (a halftone screen with
/// jittered dots): two lattices of centres, one at a random place in each `cell_px` x `cell_px`
/// cell and one in each cell shifted by half a cell (keyed by `seed`), and each pixel's value
/// its rank by d_low / (d_low + d_high), the distances to the nearest centre of each, so the
/// values are uniform in [0, 1). The pixels above 1 − s are a round dot around every "high"
/// centre, about s of a cell, that grows with s until the dots meet and the rest shrinks to
/// dots around the "low" centres: every region of a few cells holds about the share s, in
/// blobs at both ends rather than single pixels. 1 channel, `width` x `height`; `cell_px` > 0.
Image dot_screen(int width, int height, float cell_px, std::uint64_t seed);

/// Target guide and per-pixel weight of the input time-derivative term g_∂in (Bénard eq. 10).
struct DerivativeGuide {
    Image target;  ///< G_t, the frame's size and channels.
    Image weight;  ///< 1 channel: 1 where the term applies, 0 elsewhere; empty = 1 everywhere.
};

/// g_∂in of frame t against its solved neighbour n = t ∓ 1 as a guide pair (S, G_t):
///     |(I_t(p) − I_n(q)) − (S(C_t(p)) − S(C_n(q)))|² = |S(C_t(p)) − G_t(p)|²,
///     G_t(p) = I_t(p) + (S(C_n(q)) − I_n(q)),   q = p + V(p),
/// with C_n = `neighbour_offsets` (their centre pixel, into `source_input` = S) and
/// (S(C_n) − I_n) pulled along `flow` (t's grid, pointing into n) bilinearly. Where
/// `visible` (χ) ≤ 0.5, the sample leaves the frame or C_n has no match the weight is 0, as in
/// the paper, and G_t = I_t (keeps the guide in the frames' value range). Sizes must agree.
Result<DerivativeGuide> input_derivative_guide(const Image& frame, const Image& neighbour_frame,
                                               const Nnf& neighbour_offsets,
                                               const Image& source_input, const Image& flow,
                                               const Image& visible);

}  // namespace exemplar::animate
