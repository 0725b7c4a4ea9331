#pragma once
/// \file
/// LazyFluids: appearance transfer for fluid animations (Jamriška et al. 2015; Fišer's thesis,
/// chapter 5). An RGBA exemplar of a fluid element (a still or a sequence) is transferred onto a
/// target animation given by per-frame alpha masks and motion fields, one frame at a time:
///
/// - the target and the exemplar are split into boundary and interior segments by thresholds on
///   their blurred alpha (§5.4.2), and every exemplar patch of a segment is used K or K+1 times
///   in the same segment of the target (uniform usage, §5.4.1: the engine's
///   UsageStrategy::Uniform with one label per segment);
/// - alpha is a synthesized channel (weight 3 against 1 per colour channel) and the blurred
///   alpha a guide (weight η) (§5.4.2);
/// - the previous output, advected along the motion, is a guide against the exemplar's previous
///   frame with a per-pixel weight λ_q = (1 − max(0, alpha_t − advected alpha_{t−1})) λ, zero
///   where new fluid appears (emitters) and everywhere in the first frame (§5.4.3, eq. 5.6);
/// - optionally the exemplar is enriched with copies rotated by 90°, 180° and 270° and the result
///   blurred along the motion (§5.4.5).
///
/// Colours are premultiplied by alpha inside (so the colour of transparent exemplar pixels does
/// not matter) and returned straight (not premultiplied). Deterministic for a given seed and any
/// thread count (the engine is). Defaults are the paper's (§5.5).

#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/synth/nnf.hpp"
#include "exemplar/synth/options.hpp"

namespace exemplar::fluid {

/// Segment labels (values of segment()).
/// Blurred alpha ≤ boundary_low: transparent, not synthesized.
inline constexpr int kOutside = 0;
/// boundary_low < blurred alpha < boundary_high (B in the paper).
inline constexpr int kBoundary = 1;
/// Blurred alpha ≥ boundary_high (I in the paper).
inline constexpr int kInterior = 2;

/// Options of a LazyFluids run. Defaults: Jamriška et al. 2015 §5.5.
struct FluidOptions {
    /// Patch width, pixels (odd, 3..15). Paper: 5.
    int patch_size = 5;
    /// λ: weight of the temporal term (previous output advected along the motion), 0..10.
    /// Paper: 0.2. 0 = every frame on its own.
    float temporal_weight = 0.2f;
    /// η: weight of the blurred alpha guide ("richness of boundary effects": lower = more
    /// varied boundaries), 0..100. Paper: 3.
    float boundary_weight = 3.0f;
    /// Weight of the synthesized alpha channel against 1 per colour channel, 0..100. Paper: 3.
    float alpha_weight = 3.0f;
    /// r: Gaussian blur of the alpha masks before segmentation, pixels (used as the Gaussian's
    /// σ), 0..50. Paper: 3 ("might change according to the resolution").
    float blur_radius_px = 3.0f;
    /// l: blurred alpha above this is fluid (boundary or interior), 0..1. Paper: 0.1.
    float boundary_low = 0.1f;
    /// u: blurred alpha at or above this is interior, boundary_low..1. Paper: 0.9.
    float boundary_high = 0.9f;
    /// Uniform patch usage per segment (§5.4.1). false = plain nearest neighbours (Kwatra et al.
    /// 2005, which washes out over the frames; for comparisons only).
    bool uniform_usage = true;
    /// Enrich the exemplar with copies rotated by 90°, 180° and 270° (§5.4.5; Lukáč et al. 2013),
    /// so that boundaries of every orientation are available. Default off (4× the source).
    bool rotations = false;
    /// Motion blur (§5.4.5): line convolution of the output along the motion with a Gaussian
    /// whose σ is this fraction of the motion's length (0 = off, default; 0..2).
    float motion_blur = 0.0f;
    /// Strength of the vote's colour-histogram weight (SynthesisOptions::vote_histogram; Kopf
    /// et al. 2007), 0..100: values the frame holds more of than the exemplar weigh less in the
    /// vote, which otherwise averages the scattered uniform matches into flat, faint smoke.
    /// Ours, not the paper's; default 2 (docs/fluid.md, "Wash-out"); 0 = the paper's vote.
    float vote_histogram = 2.0f;
    /// Coherence weight of the vote (SynthesisOptions::vote_coherence; Lukáč et al. 2015,
    /// Brushables' w_c), the variance of the mapping discrepancy in px², 0..100: a patch whose
    /// neighbours map where it does outweighs the scattered matches of the uniform assignment
    /// between them, so coherent runs of the exemplar's fine grain survive the final vote.
    /// Ours, not the paper's; default 2 (Brushables' value; docs/fluid.md, "Wash-out");
    /// 0 = the paper's vote.
    float vote_coherence = 2.0f;
    /// Sweeps in which stray matches of the uniform assignment take a neighbour's shifted exemplar
    /// patch, moving or swapping so that every count stays K or K + 1
    /// (SynthesisOptions::uniform_coherence_sweeps), 0..100: the assignment places larger
    /// coherent pieces of the exemplar instead of scattered patches, which the vote would average
    /// flat. Ours, not the paper's; default 2 (docs/fluid.md, "Wash-out"); 0 = the paper's.
    int coherence_sweeps = 2;
    /// Engine options (levels, EM and PatchMatch iterations, seed). patch_size and usage are
    /// set from the fields above.
    SynthesisOptions synthesis;
};

/// Description of one numeric LazyFluids option: the one source of the CLI flags, the job-file
/// keys, validation and docs/fluid.md's table.
struct FluidOptionSpec {
    std::string_view name;  ///< kebab-case: --name and the JSON key ('_' accepted too).
    std::string_view doc;   ///< Meaning, the paper's symbol and default.
    std::string_view unit;  ///< "px", "" ...
    double min = 0.0;       ///< Inclusive range.
    double max = 0.0;
    std::variant<int FluidOptions::*, float FluidOptions::*> field;
};

/// The numeric options (patch-size, temporal-weight, boundary-weight, alpha-weight,
/// blur-radius, boundary-low, boundary-high, motion-blur, vote-histogram, vote-coherence,
/// coherence-sweeps).
std::span<const FluidOptionSpec> fluid_option_specs();

/// Sets an option, rejecting values outside its range or non-integral values of integer options
/// (`temporal-weight: -1 is invalid (must be 0..10)`).
Status set_option(FluidOptions& options, const FluidOptionSpec& spec, double value);

/// Current value of an option.
double get_option(const FluidOptions& options, const FluidOptionSpec& spec);

/// Checks every option's range and the cross rules (odd patch size, boundary-high above
/// boundary-low), then the engine options; the message names the option
/// (`boundary-high: 0.05 is invalid (must be above boundary-low 0.1)`).
Status validate(const FluidOptions& options);

/// One target frame. Images are borrowed; optional ones are nullptr when absent.
struct FluidFrameInput {
    /// Z^t: the exemplar frame for this output frame (RGBA, 4 channels, straight alpha).
    const Image* exemplar = nullptr;
    /// Z^{t−1}: the exemplar frame for the previous output frame (RGBA); nullptr = `exemplar`
    /// (a still exemplar).
    const Image* previous_exemplar = nullptr;
    /// X^t_a: the target alpha mask (channel 0 is used, values in [0, 1]).
    const Image* target_alpha = nullptr;
    /// X^{t−1}: the previous output (RGBA, straight alpha, target size); nullptr = none (first
    /// frame: λ = 0 everywhere).
    const Image* previous_output = nullptr;
    /// F^{t−1}: forward motion of the previous frame to this one (2 channels, px, target size);
    /// required with previous_output. Frame t's own motion (for motion blur); may be nullptr.
    const Image* previous_motion = nullptr;
    const Image* motion = nullptr;
};

/// One synthesized frame and what went into it (for tests, debugging and the CLI's --debug).
struct FluidFrameResult {
    Image rgba;                 ///< X^t: RGBA, straight alpha, target size.
    Nnf nnf;                    ///< Final NNF into the (possibly rotation-enriched) exemplar.
    Image source_segments;      ///< Segment labels of the (enriched) exemplar.
    Image target_segments;      ///< Segment labels of the target.
    Image advected_previous;    ///< X̂^{t−1}: previous output advected (RGBA, premultiplied);
                                ///< empty in the first frame.
    Image temporal_weight_map;  ///< λ_q / λ (1 channel); empty when the term is off.
};

/// Gaussian-blurred alpha (σ = `blur_radius_px`) thresholded into Segment labels (1 channel).
Image segment(const Image& alpha, const FluidOptions& options, int threads = 0);

/// X̂(x) = image(x − motion(x)): `image` (frame t−1) carried along its forward motion to frame t
/// (semi-Lagrangian, bilinear, 0 outside the frame — the simulator's advection).
Image advect_along_motion(const Image& image, const Image& motion, int threads = 0);

/// Eq. 5.6 without λ: 1 − max(0, alpha(q) − advected_previous_alpha(q)) (1 channel).
Image temporal_weight_map(const Image& alpha, const Image& advected_previous_alpha);

/// The exemplar and its copies rotated by 90°, 180° and 270° side by side, separated by
/// transparent gaps of `gap` pixels (§5.4.5).
Image rotation_atlas(const Image& exemplar, int gap);

/// Line convolution of `image` along `motion` (per pixel, a Gaussian of σ = strength × |motion|
/// over the segment x + s·motion(x), s in [−1, 1]); strength 0 returns the image.
Image motion_blur(const Image& image, const Image& motion, float strength, int threads = 0);

/// Synthesizes one frame. Errors (InvalidArgument): missing or wrong-channel images, sizes that
/// differ (messages name the input and both sizes), an exemplar without any fluid pixels, bad
/// options; engine errors; Cancelled.
Result<FluidFrameResult> synthesize_fluid_frame(const FluidFrameInput& input,
                                                const FluidOptions& options,
                                                const RunContext& context = {});

}  // namespace exemplar::fluid
