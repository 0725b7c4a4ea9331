#pragma once
/// \file
/// The styles of image-space NPR (issue 20, docs/npr.md): one rendered frame in, one stippled,
/// hatched or halftoned frame out, continuing from the previous frame's state.
///
/// A style is the coordinate synthesis of synthesis.hpp plus what turns its screen into a
/// picture (§6 of "Image Space Texture Synthesis for 3D NPR Animation"): the tone taken from a
/// light buffer (luma, sRGB-encoded, clamped to [0, 1]), halftone thresholding with the tone
/// correction of §6.0.1, the orientation buffer for hatching, and the renderer's silhouette and
/// crease lines inked on top (§6.0.2). `exemplar npr` and Python's `exemplar.npr_frame` are this
/// call per frame; they only read and write the buffers.
///
/// Buffers are named as `exemplar render --frames` writes them into each frame folder (and as
/// Python's `exemplar.render(scene, frame=n)` returns them): `needed_buffers` says which a frame
/// reads under given options, `NprFrame` holds them by role.
///
/// Deterministic: a frame is a pure function of (pattern, buffers, previous state, frame
/// number, options), bit-identical for any thread count.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/npr/pattern.hpp"
#include "exemplar/npr/synthesis.hpp"

namespace exemplar::npr {

/// What a frame shows.
enum class Style {
    Stipple,   ///< Isotropic screen thresholded by the tone (stipple patterns).
    Halftone,  ///< The same (halftone dot screens); a separate name for the user's intent.
    Hatch,     ///< Thresholded, and oriented by the `orientation` buffer unless told otherwise.
    Pattern,   ///< The synthesized pattern itself: no tone, no thresholding.
};

/// "stipple", "halftone", "hatch", "pattern".
std::string_view to_string(Style style);
/// Parses the names of to_string; the error names the accepted values
/// (`style: 'crosshatch' is invalid (must be one of stipple, hatch, halftone, pattern)`).
Result<Style> parse_style(std::string_view name);

/// Options of a styled run. Defaults are docs/npr.md's (the paper's where it gives one).
struct NprOptions {
    Style style = Style::Stipple;
    /// Pyramid levels of the coordinate synthesis (the pattern's Gaussian stack). Default 3
    /// (the paper's L = 2); range 1..6.
    int levels = 3;
    /// Initialization patch in coarsest-level pixels (the paper's 10-14). Default 12; range
    /// 3..32. The pattern must be at least patch_size · 2^(levels−1) pixels on a side.
    int patch_size = 12;
    /// β, the weight of the temporal coherence term. Default 1 (the paper's); range 0..100.
    float coherence_weight = 1.0f;
    /// Pyramid levels, from the coarsest, whose correction also tries the previous frame's
    /// coordinate at each pixel's advected position (SynthesisOptions::motion_levels). Default 0
    /// (the pattern keeps its size under a zoom); range 0..6.
    int motion_levels = 0;
    /// Buffer giving the tone (its Rec. 709 luma). Unset = "direct_diffuse". Style::Pattern
    /// shows no tone: setting it there is an error.
    std::optional<std::string> tone;
    /// Buffer giving the pattern's orientation (angles in radians), or "none". Unset = the
    /// style's: "orientation" for Style::Hatch, "none" otherwise.
    std::optional<std::string> orientation;
    /// Ink the renderer's `lines` buffer (silhouettes, creases; > 0.5 = line). Default true.
    bool lines = true;
    /// Tone correction (§6.0.1) of the thresholded styles. Default true.
    bool tone_correction = true;
    /// Seed of the keyed random generator (with the frame number). Default 1.
    std::uint64_t seed = 1;
    /// The paper layer (§6, §6.0.2): a paper texture synthesized the same way as the pattern
    /// (its own coordinates, coherent along the same motion, unoriented), shown as grain
    /// (white × (1 − paper_grain · (1 − paper))) and eroding the shape's boundary: a pixel of
    /// the `alpha` buffer's shape stays where the shape mask blurred by erosion_px exceeds
    /// 0.5 + 0.45 · paper, else it becomes paper. Needs stylize_frame's `paper` and the `alpha`
    /// buffer. Default false.
    bool paper = false;
    /// Grain of the paper layer: how much its dark parts darken the white. Default 0.15; range
    /// 0..1.
    float paper_grain = 0.15f;
    /// Width of the boundary erosion: the blur of the shape mask, in pixels. Default 2; range
    /// 0.5..20.
    float erosion_px = 2.0f;
};

/// Description of one numeric option (name, doc, unit, range): the one table the CLI flags,
/// Python's keywords and docs/npr.md's option table come from.
struct NprOptionSpec {
    std::string_view name;  ///< kebab-case: --name; Python's keyword with '_'.
    std::string_view doc;
    std::string_view unit;
    double min = 0.0;  ///< Inclusive range.
    double max = 0.0;
    std::variant<int NprOptions::*, float NprOptions::*> field;
};

/// The numeric options (levels, patch-size, coherence-weight, motion-levels, ...).
std::span<const NprOptionSpec> npr_option_specs();
/// Reads an option's value as a double.
double get_option(const NprOptions& options, const NprOptionSpec& spec);
/// Sets an option; rejects values outside the range and non-integers for integer options
/// (`levels: 9 is invalid (must be an integer, 1..6)`).
Status set_option(NprOptions& options, const NprOptionSpec& spec, double value);
/// Checks every option, the buffer names, and the tone against the style.
Status validate(const NprOptions& options);

/// Prepares `pattern` (any channel count, as prepare_pattern) for `options`: its levels, and at
/// least patch_size · 2^(levels−1) pixels on a side (`pattern: 16x16 is too small (needs at
/// least 48x48 for the patch size)`). Uses context.threads.
Result<Pattern> prepare_pattern(const Image& pattern, const NprOptions& options,
                                const RunContext& context = {});

/// What a style uses a buffer for.
enum class BufferRole { Tone, Orientation, BackwardFlow, Disocclusion, Lines, Mask };

/// One buffer a frame reads: its role and its name in the frame folder.
struct BufferNeed {
    BufferRole role;
    std::string name;
};

/// The buffers a frame reads under `options`, in this order: the tone (thresholded styles),
/// the orientation (unless "none"), `backward_flow` and `disocclusion` (when `continues`: a
/// previous frame's state is given), `alpha` (the shape mask, with the paper layer), `lines`
/// (when inked, or when no other buffer would give the frame's size: the renderer always
/// writes it). Assumes valid options.
std::vector<BufferNeed> needed_buffers(const NprOptions& options, bool continues);

/// The file of buffer `name` in a frame folder of `exemplar render --frames`: NAME.exr (linear
/// light) if it is there, else NAME.png (sRGB-encoded values); "" when neither is. A tone buffer
/// read from an EXR sets NprFrame::tone_linear.
std::string frame_buffer_file(const std::string& folder, const std::string& name);

/// One frame's buffers, at the output resolution; empty = not given. Channels beyond those
/// used are ignored.
struct NprFrame {
    /// Tone buffer (1+ channels; 3+ → Rec. 709 luma), 1 = white.
    Image tone;
    /// True: `tone` holds linear light (EXR buffers, Python's render()) and is sRGB-encoded
    /// first; false: it is encoded already (8-bit PNG buffers).
    bool tone_linear = false;
    Image orientation;    ///< Channel 0: angle in radians, counter-clockwise on screen.
    Image backward_flow;  ///< Channels 0, 1: pixel x was at x + b(x) in the previous frame.
    Image disocclusion;   ///< Channel 0: > 0.5 where the point was not visible before.
    Image lines;          ///< Channel 0: > 0.5 on a line.
    Image mask;           ///< Channel 0: the shape's coverage (`alpha`), 1 = shape.
    /// The bidirectional loop's backward pass (§5.2.1): where hold > 0.5 the frame keeps the
    /// coordinates of `held` (its forward pass), and the rest is synthesized around them,
    /// coherent with `previous` (then the next frame's state, `backward_flow` and
    /// `disocclusion` its forward flow and occlusion). Empty = none.
    Image hold;
    const FrameState* held = nullptr;  ///< The held coordinates (needed with `hold`).

    Image& operator[](BufferRole role);
    const Image& operator[](BufferRole role) const;
};

/// The delayed visibility of the bidirectional loop (§5.2.1, "delayed dis-occlusions"): 1 where
/// the point seen at a pixel was visible in every frame since the last update frame, else 0.
/// `previous`: the previous frame's delayed visibility (empty: the previous frame is the update
/// frame, all visible there); `disocclusion` (channel 0 > 0.5 = hidden before) and
/// `backward_flow` (channels 0, 1) of this frame; nearest pixel along the flow. InvalidArgument
/// if the sizes differ.
Result<Image> delayed_visibility(const Image& previous, const Image& disocclusion,
                                 const Image& backward_flow);

/// A styled frame.
struct NprFrameResult {
    /// 1 channel in [0, 1]: {0 = ink, 1 = paper} for the thresholded styles.
    Image image;
    /// The synthesis state: the next frame's `previous` (pack_state stores it in a file).
    FrameState state;
    /// The paper layer's synthesis state (NprOptions::paper), the next frame's
    /// `NprPaper::previous`; empty without the paper layer.
    FrameState paper_state;
};

/// The paper layer's inputs (NprOptions::paper).
struct NprPaper {
    /// The prepared paper texture (prepare_pattern with the same options); null = none.
    const Pattern* pattern = nullptr;
    /// The previous frame's paper state (NprFrameResult::paper_state), or null.
    const FrameState* previous = nullptr;
    /// The paper's held coordinates where NprFrame::hold is given (its forward pass; needed
    /// then).
    const FrameState* held = nullptr;
};

/// Styles frame `frame_index` (it keys the randomness with the seed) from its buffers,
/// continuing from `previous` (the previous frame's state, or null for the first frame or an
/// independent one). Errors (InvalidArgument, one line): invalid options; a buffer that
/// needed_buffers(options, previous != null) names missing (`missing buffer 'backward_flow'`);
/// a buffer of another size than the first given one (`buffer 'lines' is 64x48 but the frames
/// are 96x64`) or with too few channels; a frame size other than the previous frame's; a pattern
/// prepared with other levels. Cancelled through context.cancel (checked before each
/// correction sub-pass); progress events after each level ("synthesis", the last with fraction
/// 1). Uses context.threads. With NprOptions::paper, `paper.pattern` is required (and rejected
/// without it); the paper is synthesized after the pattern (the pattern's progress events then
/// cover fractions 0..0.5 and the paper's 0.5..1).
Result<NprFrameResult> stylize_frame(const Pattern& pattern, const NprFrame& frame,
                                     const FrameState* previous, int frame_index,
                                     const NprOptions& options, const RunContext& context = {},
                                     const NprPaper& paper = {});

}  // namespace exemplar::npr
