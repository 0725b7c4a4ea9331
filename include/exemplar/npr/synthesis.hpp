#pragma once
/// \file
/// Per-frame image-space coordinate synthesis of a pattern on a 3D animation (issue 20; §5 of
/// "Image Space Texture Synthesis for 3D NPR Animation"; Lefebvre and Hoppe 2005/2006).
///
/// Each output pixel stores a coordinate into the pattern. Per frame, coarse to fine over
/// `levels` pyramid levels (level l has size ceil(W / 2^l) x ceil(H / 2^l), coordinate
/// spacing h = 2^l):
/// 1. Initialization (coarsest level): overlapping oriented patches in scanline order, each
///    centre skipping already-filled pixels; per patch the candidate minimizing
///    texture_weight·E_texture (over the already-filled overlap) + coherence_weight·E_coherence
///    (over the pixels the advected previous frame covers) among the previous frame's
///    coordinates around the centre's advected position and `init_candidates` pattern
///    positions (on a grid of spacing 2^L, drawn by a keyed generator).
/// 2. Upsampling (finer levels): child (2i + Δ), Δ ∈ {0,1}², gets the parent's coordinate plus
///    the offset Δ h rotated by the orientation at the child.
/// 3. Correction (`correction_passes` passes of 4 interleaved sub-passes): Ashikhmin coherence
///    candidates from the 3x3 neighbours, plus, at the `motion_levels` coarsest levels and where
///    the backward flow is valid (disocclusion = 0), the previous frame's coordinates around the
///    advected position; the candidate minimizing texture_weight·‖N_S − N_P‖² +
///    coherence_weight·‖N_P − N_prev‖² over 3x3 appearance neighbourhoods wins (N_prev: the
///    previous frame's appearance, advected).
/// 4. Output: the screen colour with 3x3 coordinate blending (eq. 5).
///
/// Orientation: an angle θ (radians, counter-clockwise on screen, as the renderer's
/// `orientation` buffer) maps the pattern's +x axis onto the screen direction θ: a screen
/// offset Δ reads the pattern at Rot(−θ)Δ.
///
/// Randomness is keyed by (seed, frame, level, pixel or patch); correction passes read the
/// field of the previous sub-pass only, so results are bit-identical for any thread count.
#include <cstdint>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/npr/pattern.hpp"

namespace exemplar::npr {

/// Synthesis options. Defaults follow the paper where it gives values.
struct SynthesisOptions {
    /// Patch size of the coarse initialization, in coarse-level pixels. Default 12 (the paper
    /// uses 10-14); range 3..32.
    int init_patch_size = 12;
    /// Pattern positions tried per initialization patch. Default 128; range 1..100000.
    int init_candidates = 128;
    /// Correction passes per level. Default 2; range 0..8.
    int correction_passes = 2;
    /// α, the weight of the texture term. Default 1 (the paper's); range [0, 100].
    float texture_weight = 1.0f;
    /// β, the weight of the temporal coherence term. Default 1 (the paper's); range [0, 100].
    float coherence_weight = 1.0f;
    /// Pyramid levels, counted from the coarsest, whose correction also tries the previous
    /// frame's coordinates around each pixel's advected position (§5.2.4). Default 0: the
    /// previous frame enters through the initialization (each coarsest-level patch may be the
    /// previous frame's content at its centre's advected position, chosen by the same
    /// objective) and the coherence term, so the pattern keeps its size in the image under a
    /// camera zoom. Each level more follows the exact motion more closely (steadier on
    /// rotations), but those per-pixel candidates carry the motion's scaling: with all levels
    /// a 2x zoom grows the pattern 2x, as texture mapping does. Range 0..6 (more than the
    /// levels = all).
    int motion_levels = 0;
    /// Blend coordinates over 3x3 (eq. 5) when producing the screen. Default true.
    bool blend_coordinates = true;
    /// Seed of the keyed random generator. Default 1.
    std::uint64_t seed = 1;
    /// Run the correction with its plain scalar reference kernel instead of the optimized one
    /// (the tests' oracle: both give the same coordinates, bit for bit). Default false.
    bool reference_kernels = false;
};

/// Checks every option; InvalidArgument naming the first bad one and its range.
Status validate(const SynthesisOptions& options);

struct FrameState;

/// The per-frame inputs, all at the output resolution.
struct FrameInput {
    int width = 0, height = 0;
    /// Orientation angle (1 channel, radians); empty = 0 everywhere.
    Image orientation;
    /// Backward flow (2 channels u, v in px: pixel x was at x + b(x) in the previous frame);
    /// empty = no previous frame (first frame or independent synthesis).
    Image backward_flow;
    /// 1 where the point was hidden or off-screen in the previous frame (1 channel); empty =
    /// valid everywhere the flow is given.
    Image disocclusion;
    /// Pixels to hold (1 channel, > 0.5; the bidirectional loop's backward pass): they keep the
    /// coordinates of `held` at every level (a level's pixel where all its full-resolution
    /// pixels are held), and the rest is synthesized around them. Empty = none.
    Image hold;
    /// The held coordinates (FrameState::coords; needed with `hold`).
    const FrameState* held = nullptr;
};

/// The state of one synthesized frame.
struct FrameState {
    /// Coordinates per level (0 = finest): 2 channels x, y into the pattern (integers stored as
    /// floats, wrapped into the pattern).
    std::vector<Image> coords;
    /// Appearance (stack level l sampled at coords) per level, for the next frame's coherence.
    std::vector<Image> appearance;
    /// The synthesized screen (1 channel, [0, 1]): the pattern's equalized grey at the
    /// (blended) coordinates.
    Image screen;
};

/// Synthesizes one frame. `previous` (may be null) is the previous frame's state, used where
/// `input.backward_flow` is given. InvalidArgument if the options are invalid, the buffers do
/// not match width x height, or the frame is smaller than 2^(levels-1) on a side. Threads:
/// context.threads (0 = all cores, 1 = inline; results do not depend on it); progress events
/// ("synthesis") after each level, with `fraction` the share of the pixels done; Cancelled when
/// context.cancel is set (checked before each correction sub-pass).
Result<FrameState> synthesize_frame(const Pattern& pattern, const FrameInput& input,
                                    const FrameState* previous, int frame_index,
                                    const SynthesisOptions& options,
                                    const RunContext& context = {});

/// The coordinates of every level packed into one image of the finest level's size (channels
/// x0, y0, x1, y1, ...; level l in the top-left ceil(W / 2^l) x ceil(H / 2^l) pixels), to store
/// a frame's state in a file (a resumed run continues from it exactly).
Image pack_state(const FrameState& state);

/// The state stored by `pack_state` (channels found by name, in any order), with the
/// appearance recomputed from `pattern` (screen left empty). InvalidArgument if the channel
/// count does not match the pattern's levels, a channel is missing or a coordinate lies
/// outside the pattern.
Result<FrameState> unpack_state(const Pattern& pattern, const Image& packed);

/// Halftone options (§6).
struct HalftoneOptions {
    /// Tone correction (§6.0.1): blur the first thresholded result, subtract the error from the
    /// tone, threshold again. Default true.
    bool tone_correction = true;
    /// Blur of the tone correction in pixels (the visual system's spatial integration; the
    /// paper gives no value). About half the pattern's element spacing works best: smaller
    /// blurs feed the dots' own noise back. Default 3.0; range (0, 50].
    float blur_sigma_px = 3.0f;
};

/// Checks every option; InvalidArgument naming the first bad one and its range.
Status validate(const HalftoneOptions& options);

/// Thresholds `screen` against `tone` (both 1 channel, same size; tone 1 = white): a pixel is
/// ink (0) where screen < 1 − tone, paper (1) otherwise; with tone correction the tone is first
/// replaced by clamp(2·tone − blur(first result)). Returns 1 channel in {0, 1}.
Image halftone(const Image& screen, const Image& tone, const HalftoneOptions& options,
               int threads = 0);

}  // namespace exemplar::npr
