#pragma once
// Pre-rotated copies of a level's source features (SynthesisInput::rotated_copies), after the
// pre-rotated exemplars of Brushables (Lukáč et al. 2015) and LazyFluids (Jamriška et al. 2015,
// thesis §5.4.5): with orientation steps, a patch rotated by step k is compared as the plain
// patch of copy k, the source turned by that step, so the distance is the unrotated SIMD kernel
// on contiguous rows instead of a gather of the rotated pixels into a block.
// Deviation from the gathered distance (patch_distance_reference): the copy resamples the whole
// source on one rotated grid, so the patch it holds for source centre s is centred on the grid
// point nearest to s (at most 0.71 px away), not on s itself; matches, their angles, the vote and
// the usage stay in the exemplar's coordinates. Internal to the synth module.

#include "level.hpp"
#include "patch_distance.hpp"

namespace exemplar::synth {

/// Where source centre (sx, sy) lies in `copy`: round(R(−angle) (sx, sy)) + origin.
inline RotatedOffset copy_position(const RotatedCopy& copy, int sx, int sy) {
    const RotatedOffset q = rotate_offset(sx, sy, copy.cos, -copy.sin);
    return {q.dx + copy.origin_x, q.dy + copy.origin_y};
}

/// The source pixel that pixel (qx, qy) of `copy` holds (clamped to the sw x sh source).
RotatedOffset copy_source_pixel(const RotatedCopy& copy, int qx, int qy, int sw, int sh);

/// Fills L.step_copies: one copy of L.source_features per orientation step but step 0 (no
/// rotation). Requires L.orientation_steps > 0.
void build_rotated_copies(Level& L, int threads);

/// The rotated patch distance of target centre (tx, ty), inside the target by the patch radius,
/// and source centre (sx, sy) at orientation step `step` ≥ 1 of a level with copies, without
/// target weight maps or fall-off: the weighted SSD of the target patch and copy `step`'s patch
/// around copy_position. Stops as patch_distance does once the sum exceeds `bound`.
float copy_distance(const Level& L, int tx, int ty, int sx, int sy, int step, float bound);

/// The scalar reference of copy_distance: each patch pixel's source pixel computed from the
/// rotation (copy_source_pixel), no copy read. Test oracle.
float copy_distance_reference(const Level& L, int tx, int ty, int sx, int sy, int step);

}  // namespace exemplar::synth
