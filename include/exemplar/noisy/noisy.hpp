#pragma once
/// \file
/// Color Me Noisy (Fišer, Lukáč, Jamriška, Čadík, Gingold, Asente, Sýkora: "Color Me Noisy:
/// Example-based rendering of hand-colored animations with temporal noise control", EGSR 2014;
/// J. Fišer's thesis, chapter 4). Re-synthesizes each frame of a coherent reference animation
/// (flat-coloured cels, a render, a filtered video) from a scan of a drawing medium, so that
/// the frame's low frequencies follow the reference (low-pass strength f) while its details
/// come from the medium and change randomly from frame to frame: the larger f, the stronger
/// the perceived temporal noise. See docs/noisy.md.
///
/// Frames are independent: each is a pure function of (source, reference frame, options,
/// frame index), identical for any thread count, so a range can run in parallel, be resumed or
/// split across machines.

#include <cstdint>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::noisy {

/// The low-pass filter h_f. Its strength f is the width of the box in pixels (thesis §4.4).
enum class LowPassFilter {
    /// Box of width f followed by subsampling by f: an exact area average (the chapter's
    /// default).
    Box,
    /// Lanczos-3 prefilter scaled by f: sharper, for media with sharp details (§4.4).
    Lanczos3,
};

/// "box", "lanczos3".
std::string_view to_string(LowPassFilter filter);
/// Parses the names of to_string; the error names the accepted values.
Result<LowPassFilter> parse_low_pass_filter(std::string_view name);

/// Options of a run. Defaults are the chapter's (thesis §4.3.2 and §4.4) unless noted.
struct NoisyOptions {
    /// Low-pass strength f: width in pixels of the box that separates the reference's low
    /// frequencies (kept) from the details (re-synthesized at random in every frame). Larger =
    /// more perceived temporal noise. Values ≤ 1 synthesize on the finest level only, starting
    /// from the reference itself (the least noise). The chapter gives no single default; 4 is a
    /// moderate level. Range 0..256, and at most min(frame side, source side) / patch-size, so
    /// that the coarsest level holds a patch.
    float noise = 4.0f;
    /// Ratio of the sampling rates of consecutive pyramid levels (the chapter's 0.85, after
    /// Simakov et al. 2008): the strengths go geometrically from f down to 1 in the fewest
    /// steps whose ratio is at least this. Range 0.5..0.95.
    float level_ratio = 0.85f;
    int patch_size = 7;         ///< Patch width in pixels, odd, 3..31 (chapter: 7).
    int em_iterations = 4;      ///< Search+vote iterations per level, 1..100 (chapter: 4).
    int search_iterations = 8;  ///< PatchMatch iterations per search, 1..100 (chapter: 8).
    /// PatchMatch iterations per search on a level whose pixels all continue from the level
    /// before: its nearest-neighbour field starts as the level before's, upsampled, which is
    /// already close. 0 = every level starts from a random field and runs em_iterations x
    /// search_iterations (the chapter's schedule). Range 0..100. Our deviation (default 2):
    /// about 5x faster, measurements in docs/noisy.md.
    int warm_search_iterations = 2;
    /// EM iterations on such a level (ignored when warm_search_iterations is 0). Range 1..100
    /// (default 1).
    int warm_em_iterations = 1;
    /// Spacing in pixels of the control lattice of the random rigid-MLS pre-deformation of the
    /// source, on the source's full resolution (chapter: 50). Range 4..10000.
    float lattice_spacing_px = 50.0f;
    /// Each lattice point moves by a length uniform in [min, max] pixels in a uniformly random
    /// direction (chapter: 15..25). 0 and 0 turn the pre-deformation off. Range 0..1000,
    /// min ≤ max.
    float min_offset_px = 15.0f;
    float max_offset_px = 25.0f;  ///< See min_offset_px (chapter: 25).
    /// Weight of the coarse-consistency guide (eq. 4.2 as a term of the patch distance): on
    /// every level, the low-passed reference h_f * R_i and the low-passed deformed source
    /// h_f * S are a guide pair, so the re-synthesized details stay where the reference's low
    /// frequencies put them. 0 = the chapter's algorithm, which enforces eq. 4.2 only through
    /// the coarsest level's start. Range 0..100.
    float coarse_weight = 0.5f;
    /// Random seed: frame i uses randomness keyed by (seed, i) only, so any frame can be
    /// re-made alone.
    std::uint64_t seed = 1;
    LowPassFilter filter = LowPassFilter::Box;  ///< h_f (chapter: box).
};

/// Description of one numeric option (name, doc, unit, range), the one table that validation,
/// CLI flags, JSON job keys and docs/noisy.md use.
struct NoisyOptionSpec {
    std::string_view name;  ///< kebab-case: --name and the JSON key (with '_' too).
    std::string_view doc;
    std::string_view unit;
    double min = 0.0;  ///< Inclusive range.
    double max = 0.0;
    std::variant<int NoisyOptions::*, float NoisyOptions::*, std::uint64_t NoisyOptions::*> field;
};

/// The table of numeric options.
std::span<const NoisyOptionSpec> noisy_option_specs();
/// Finds an option by name ('-' and '_' interchangeable); nullptr if unknown.
const NoisyOptionSpec* find_noisy_option(std::string_view name);
/// Reads an option's value as a double.
double get_option(const NoisyOptions& options, const NoisyOptionSpec& spec);
/// Sets an option; rejects values outside the range, non-integers for integer options and
/// even patch sizes (`noise: -1 is invalid (must be 0..256)`).
Status set_option(NoisyOptions& options, const NoisyOptionSpec& spec, double value);
/// Checks every option and the cross-option rules (min-offset ≤ max-offset).
Status validate(const NoisyOptions& options);

/// The low-pass strengths of the pyramid levels, coarsest first: f̄(1) = max(f, 1), ...,
/// f̄(M) = 1, geometric with the fewest levels whose ratio is ≥ level_ratio (eq. 4.4). A
/// single level {1} for f ≤ 1.
std::vector<double> level_strengths(double noise, double level_ratio);

/// h_f * image ↓f (eq. 4.4): `image` low-pass filtered with strength f ≥ 1 and subsampled by
/// f, to max(1, round(side / f)) pixels per side. f = 1 returns the image.
Image low_pass(const Image& image, double strength, LowPassFilter filter, int threads = 0);

/// One frame's inputs.
struct NoisyFrame {
    /// The reference frame R_i: any size; 1, 3 or 4 channels. Converted to the source's
    /// channels (grey is replicated, an alpha channel the source lacks is dropped, a missing
    /// one is 1).
    Image reference;
    /// Optional per-pixel noise strength (thesis §4.3.3): 1 channel on the reference's grid,
    /// values in [0, 1] scale `noise` (f_p = noise · map). A pixel starts being synthesized on
    /// the coarsest level whose strength is ≤ f_p (the finest level when f_p ≤ 1); before
    /// that it holds the reference low-passed at that level's strength.
    Image noise_map;
    /// Optional orientation field of the frame (§4.3.3, O_R): 1 channel on the reference's
    /// grid, angles in radians (e.g. filters::orientation_field of the frame, or painted).
    /// Needs the source's orientation too; patches are then rotated by the difference.
    Image orientation;
    /// Optional local choice of source (§4.3.3): 1 channel on the reference's grid, integer
    /// values k = 0 .. sources - 1 (compared after rounding); a pixel takes patches of
    /// sources[k] only, on every level (the engine's label groups), so each region of the frame
    /// is drawn with its own medium and the boundaries between regions stay where the map puts
    /// them; the reference's low frequencies (the levels' starts, the coarse guide) are taken
    /// within each region. Required with several sources; with one source it must be all 0.
    Image source_map;
};

/// One drawing medium of a frame: a scan S (1..4 channels) and, optionally, its orientation
/// field (§4.3.3, O_S: 1 channel on the scan's grid, angles in radians).
struct NoisySource {
    Image image;
    Image orientation;
};

/// Checks a source map against the number of sources: 1 channel, finite, every value rounds to
/// 0 .. sources - 1. The message has no prefix (callers name the map): `value 2 at (5, 3) has
/// no source (2 given: 0..1)`.
Status check_source_map(const Image& map, std::size_t sources);

/// Synthesizes frame `frame_index` from `source` (the scanned drawing medium S, 1..4
/// channels) and the frame's inputs: the source randomly pre-deformed by rigid MLS, a source
/// pyramid low-pass filtered with strengths level_strengths(noise), the target's coarsest level
/// set to the reference low-passed with strength f, then plain nearest neighbours coarse to
/// fine: 4 EM iterations of 8 PatchMatch iterations from a random field on the coarsest level,
/// and warm_em_iterations x warm_search_iterations from the level before's field on the levels
/// whose pixels all continue from it (options; 0 warm iterations = the chapter's 4 x 8 from a
/// random field everywhere). Patches reaching the source's border are not used. Returns the
/// frame in the source's channels at the reference's size. Errors (one line, naming the
/// input): empty or non-finite images, unsupported channel counts, a noise map of the wrong
/// size or outside [0, 1], a noise strength too large for the sizes, invalid options,
/// cancellation.
/// Deterministic for (source, frame, options, frame_index) for any context.threads.
Result<Image> synthesize_frame(const Image& source, const NoisyFrame& frame,
                               const NoisyOptions& options, std::int64_t frame_index,
                               const RunContext& context = {});

/// The same with the source's orientation field (§4.3.3, O_S: 1 channel on the source's grid,
/// angles in radians), deformed along with the source. Give both it and the frame's
/// orientation, or neither (InvalidArgument otherwise). With orientations every patch is
/// rotated to compensate the difference, which needs sides of 2·ceil(r·√2)+1 pixels on the
/// coarsest level (r = patch-size / 2) instead of patch-size.
Result<Image> synthesize_frame(const Image& source, const Image& source_orientation,
                               const NoisyFrame& frame, const NoisyOptions& options,
                               std::int64_t frame_index, const RunContext& context = {});

/// The same with several sources chosen per pixel by NoisyFrame::source_map (§4.3.3, "local
/// choice of source"). Every source needs the same channel count and each is pre-deformed with
/// its own random lattice (keyed by seed, frame index and its position in `sources`; source 0's
/// is the single-source call's, so one source gives that call's frame bit for bit). Give
/// orientation fields for every source and the frame, or for none. With several sources the
/// coarsest level must hold a patch of every source inside its border: sides of patch-size + 2
/// (rotated: the rotated footprint + 2) instead of patch-size. Errors as above, plus: no
/// sources, differing channel counts, a map of the wrong size, a map value without a source, a
/// missing map with several sources.
Result<Image> synthesize_frame(std::span<const NoisySource> sources, const NoisyFrame& frame,
                               const NoisyOptions& options, std::int64_t frame_index,
                               const RunContext& context = {});

}  // namespace exemplar::noisy
