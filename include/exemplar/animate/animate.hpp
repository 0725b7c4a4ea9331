#pragma once
/// \file
/// Temporally coherent image analogies (TCIA, Bénard et al. 2013, "Stylizing Animation by
/// Example"): stylizes an input animation I_t by the analogy S : Ŝ :: I_t : Î_t, keeping the
/// texture attached to the moving content and re-synthesizing disoccluded regions, optionally
/// interpolating painted keyframes (full or partial) that are reproduced exactly.
///
/// The solver maps the paper's goal function onto the engine's public API
/// (exemplar::synthesize) frame by frame: the output term is the style term (Ŝ), the input term
/// the guide pair (S, I_t), the temporal term the guide pair (Ŝ, Î_{t∓1} warped along the
/// motion) with the per-pixel weight χ∓ (0 at occlusions and disocclusions), the histogram term
/// the engine's occurrence penalty; with keyframes the input time-derivative term g_∂in (guide
/// pair (S, G_t), weight χ∓) replaces the temporal term and ribbons (the keys' pixels followed
/// along the motion) are offered to the engine as candidate matches, tried in every PatchMatch
/// iteration. Frames are solved in a forward then a
/// backward sweep per pyramid level, coarse to fine (one engine level per call); each frame starts
/// from the random merge of the advected offsets of its neighbour and its own previous solution
/// (coarser level or forward sweep). See docs/video.md for the defaults and the deviations from the
/// paper.

#include <functional>
#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/synth/options.hpp"
#include "exemplar/video/occlusion.hpp"
#include "exemplar/video/optical_flow.hpp"

namespace exemplar::animate {

/// A painted keyframe: a hard constraint copied in whenever a sweep reaches its frame.
struct Keyframe {
    int frame = 0;  ///< Index into the animation (0-based).
    /// The painted frame: the style's channels (Ŝ), the animation's size.
    Image image;
    /// Optional coverage, 1 channel in [0, 1] (e.g. the painting's alpha): 1 = painted. The
    /// output is image · mask + synthesized · (1 − mask), so painted pixels (mask = 1) are
    /// reproduced exactly. Empty = a full keyframe.
    Image mask;
};

/// Everything the solver reads. Frames and motion are pulled on demand through callbacks so
/// that sequences, videos and in-memory images all fit.
struct AnimationInput {
    Image style_input;   ///< S (any channels, the frames' channel count).
    Image style_output;  ///< Ŝ (any channels; the output has these).
    int frame_count = 0;
    /// Frame I_t for t in [0, frame_count); all of one size and S's channel count.
    std::function<Result<Image>(int)> frame;
    /// Motion between frames t and t + 1 for t in [0, frame_count − 1): the forward flow of t
    /// (t → t+1, on t's grid) and the backward flow of t + 1 (t+1 → t, on t+1's grid), in the
    /// convention of docs/video.md. Empty = estimate both with DIS (exemplar/video).
    std::function<Result<video::FlowPair>(int)> motion;
    std::vector<Keyframe> keyframes;  ///< Any order; at most one per frame.
    /// Optional line drawings for the line term g_dt (Bénard eq. 9): dark lines (< 0.5) on a
    /// light background, channel 0 used; `style_lines` on S's grid, `lines(t)` on the frames'.
    /// Both or neither.
    Image style_lines;
    std::function<Result<Image>(int)> lines;
};

/// Options of the solver. Weights are the paper's w_out, w_in, w_tc (eq. 2) on the engine's
/// scale (weighted squared differences of values, each term summed over its channels).
struct AnimateOptions {
    float output_weight = 1.0f;  ///< w_out: the style term (Ŝ against the current output).
    float input_weight = 2.0f;   ///< w_in: guide (S, I_t).
    /// w_tc: guide (Ŝ, warped neighbour output) × χ. Used without keyframes, or with keyframes
    /// when input_derivative_weight is 0.
    float temporal_weight = 1.0f;
    /// w_∂in: the input time-derivative term g_∂in (Bénard eq. 10), which replaces g_tc when
    /// there are keyframes (g_tc favours the key visited last): the output's change along the
    /// motion, read through S at the offsets, follows the input's change I_t − I_{t∓1}. A guide
    /// pair (S, G_t) with G_t = I_t + (S(C_{t∓1}) − I_{t∓1}) pulled along the motion, weight 0
    /// where χ = 0 (input_derivative_guide). 0 = keep g_tc with keyframes too. Default 1: the
    /// in-betweens follow the input's shading more closely than with 2 or more, measured in
    /// docs/video.md.
    float input_derivative_weight = 1.0f;
    /// Weight of a keyframe's painted pixels when its offsets are fitted (the keyframe's own
    /// pixels are copied exactly; this only decides how well the advected offsets reproduce it).
    float keyframe_weight = 4.0f;
    /// w_dt: guide pair of the bounded line distances D(S), D(I_t) (when lines are given).
    float line_weight = 2.0f;
    /// d_max of g_dt in full-resolution pixels (the paper: 10); distances are divided by it.
    float line_max_distance_px = 10.0f;
    int levels = 4;  ///< Pyramid levels of the coarse-to-fine loop (the paper: 4).
    int sweeps = 1;  ///< Forward-backward sweep pairs per level (the paper: 1).
    /// EM iterations of a backward-sweep call (every level): it starts from the merge of the
    /// frame's forward solution and its solved successor, so it needs fewer than the forward
    /// sweep (whose calls use the engine's em_iterations / finest_em_iterations).
    int backward_em_iterations = 1;
    /// Occlusion test (χ): squared round-trip tolerance ε in px² (the paper: 2 for rendered
    /// velocities). 0 = automatic: 2 for given motion, 8 for estimated flow.
    float occlusion_tolerance_sq_px = 0.0f;
    /// Rotate patches by the orientation fields O(S), O(I_t) (structure tensors). Off by
    /// default: most styles are used upright.
    bool orientation = false;
    /// Ribbons (Bénard §4.1): with keyframes, every frame's pixels also try the offsets of
    /// their corresponding pixels (followed along the motion, while χ holds) in the last and
    /// the next key, so the search reaches the keys' patches directly.
    bool ribbons = true;
    video::FlowOptions flow;  ///< DIS preset when the motion is estimated.
    /// The engine's options for each call (patch size, iterations, usage, seed). `levels` and
    /// `finest_em_iterations` are set by the solver per call; the final 3x3 pass runs on the
    /// finest level only. Defaults: see animate_default_synthesis_options().
    SynthesisOptions synthesis;
    bool keep_frames = true;  ///< Return every output frame in AnimationResult::frames.
    /// Called with each final output frame as soon as it is final (finest level, last backward
    /// sweep: frames arrive from the last to the first). A non-ok Status stops the run.
    std::function<Status(int, const Image&)> on_frame;

    AnimateOptions();
};

/// Engine options the solver starts from: occurrence penalty (Bénard's histogram term g_h),
/// 3 EM iterations on coarse levels and 2 on the finest, 3 cold / 2 warm PatchMatch iterations
/// (the frames start from advected offsets), one final 3x3 iteration.
SynthesisOptions animate_default_synthesis_options();

/// The engine options of a quality preset for animation: Default is
/// animate_default_synthesis_options(); Fast (previews) runs 2 EM and 2/1 PatchMatch iterations
/// and no final 3x3 pass; Best 4 EM and 4/3 PatchMatch iterations. Explicit options are applied
/// after it by callers.
SynthesisOptions animate_synthesis_options(Quality quality);

/// Wall time of each stage, seconds.
struct StageTimes {
    double flow = 0.0;       ///< Loading or estimating motion.
    double occlusion = 0.0;  ///< χ± masks.
    double forward = 0.0;    ///< Forward sweeps (synthesis).
    double backward = 0.0;   ///< Backward sweeps (synthesis).
    double merge = 0.0;      ///< Advection, warps, random merges, upsampling, pyramids.
};

/// Output of a run.
struct AnimationResult {
    std::vector<Image> frames;  ///< Î_t (empty if keep_frames is false).
    StageTimes times;
};

/// Checks inputs and options (sizes, channels, keyframes, weights); one-line messages.
Status validate(const AnimationInput& input, const AnimateOptions& options);

/// Runs TCIA. Deterministic for options.synthesis.seed, independent of context.threads.
/// Progress: ProgressEvent::stage is "motion", "forward" or "backward"; `level`/`levels` the
/// pyramid level; `iteration`/`iterations` the frame being solved and the frame count;
/// `fraction` the overall completion (proportional to synthesized pixels).
Result<AnimationResult> animate(const AnimationInput& input, const AnimateOptions& options,
                                const RunContext& context = {});

/// One layer of a layered animation (Bénard §4): its own frames, style pair, keyframes and
/// lines (an AnimationInput), and its coverage per frame.
struct Layer {
    /// The layer's inputs. `motion` is the motion of the layer's content (e.g. a renderer's
    /// per-layer motion vectors); empty = estimated from the layer's frames. Either way it is
    /// extrapolated into the layer's background (extrapolate_flow) before the solve.
    AnimationInput input;
    /// Coverage (alpha) of the layer in frame t: 1 channel in [0, 1], the frames' size.
    std::function<Result<Image>(int)> coverage;
};

/// Output of animate_layers.
struct LayeredResult {
    std::vector<Image> frames;               ///< Composite Î_t (layers over each other).
    std::vector<std::vector<Image>> layers;  ///< Each layer's own output, every frame.
    StageTimes times;                        ///< Summed over the layers.
};

/// The flow of a layer extrapolated into its background: every pixel with coverage ≤ 0.5
/// takes the flow of the nearest covered pixel (exact Euclidean distance transform), so that
/// texture painted or synthesized beyond the layer's outline moves with the layer (Bénard
/// Fig. 10). Without any covered pixel the flow is returned unchanged. Sizes must agree.
Result<Image> extrapolate_flow(const Image& flow, const Image& coverage);

/// Layered TCIA: solves each layer on its own (its motion extrapolated into its background, so
/// a layer's texture persists behind the layers in front of it instead of being re-synthesized
/// when they move away) and composites them back to front with their coverage:
/// C = A·L + (1 − A)·C, starting from the first (backmost) layer as it is. All layers need the
/// same frame count and size and the same style output channel count. options.on_frame and
/// keep_frames are ignored (every frame is kept).
Result<LayeredResult> animate_layers(const std::vector<Layer>& layers,
                                     const AnimateOptions& options, const RunContext& context = {});

}  // namespace exemplar::animate
