#pragma once
/// \file
/// Incremental drawing beautification (ShipShape, Fišer et al. 2016, thesis chapter 7): a new
/// stroke is beautified against the resolved drawing by a best-first search over rule
/// applications (§7.3) with the chained likelihood L = 1 − Π(1 − L_k) (Eq. 7.1), pruning against
/// the suggestion set and stopping at N unique suggestions. Strokes with corners are split and
/// processed segment by segment (§7.4). The caller accepts one suggestion (the first by default),
/// which becomes part of the resolved drawing:
///
///     ResolvedDrawing drawing;               // empty canvas
///     auto s = suggest(drawing, stroke, {});  // ranked suggestions, last = the input itself
///     accept(drawing, (*s)[0], {});
///
/// Everything is deterministic: the same drawing, stroke and options give the same suggestions.

#include <string>
#include <vector>

#include "exemplar/core/status.hpp"
#include "exemplar/sketch/path.hpp"
#include "exemplar/sketch/rule.hpp"

namespace exemplar::sketch {

/// The resolved drawing: accepted paths with their samples and annotations.
struct ResolvedDrawing {
    std::vector<ResolvedPath> paths;
    std::vector<Axis> axes;              ///< Reflection axes used (with use counts).
    std::vector<Vec2> rotation_centers;  ///< Centres of rotation used.
    int strokes = 0;                     ///< Strokes accepted so far.
    double pixels_per_unit = 1.0;        ///< View pixels per drawing unit (§7.3.2).
};

/// One beautified version of a stroke.
struct Suggestion {
    Path path;                        ///< The whole stroke (segments joined).
    std::vector<Candidate> segments;  ///< Per segment: geometry, relations, fixed properties.
    double likelihood = 0.0;          ///< Eq. 7.1 (mean over segments for multi-segment strokes).
    bool original = false;            ///< The unmodified input (always the last suggestion).

    /// All relations of all segments, in order.
    std::vector<Relation> relations() const;
};

/// Checks option ranges; the message names the option, its value and the valid range.
Status validate(const BeautifyOptions& options);

/// Ranked suggestions for `stroke`, most likely first (at most `options.max_suggestions`); the
/// last one is the input itself, unless max_suggestions is 1 or a suggestion is already within
/// `duplicate_px` of the input. InvalidArgument for a degenerate stroke (empty, or all points
/// equal) or bad options.
Result<std::vector<Suggestion>> suggest(const ResolvedDrawing& drawing, const Path& stroke,
                                        const BeautifyOptions& options = {});

/// Adds a suggestion's paths to the drawing (as the next stroke) with their annotations.
void accept(ResolvedDrawing& drawing, const Suggestion& suggestion,
            const BeautifyOptions& options = {});

/// One stroke of a replayed drawing.
struct StrokeResult {
    Path input;
    Suggestion chosen;         ///< The accepted (first) suggestion.
    double moved = 0.0;        ///< Discrete Fréchet distance input → result, drawing units.
    double size = 0.0;         ///< Bounding-box diagonal of the input, drawing units.
    int suggestion_count = 0;  ///< How many suggestions there were.
};

/// A whole drawing beautified stroke by stroke.
struct ReplayResult {
    std::vector<StrokeResult> strokes;
    std::vector<Suggestion> last_suggestions;  ///< All suggestions for the last stroke.
    ResolvedDrawing resolved;
};

/// Replays `strokes` in order, beautifying each against the ones before and accepting the first
/// suggestion (the first stroke too: it has nothing to relate to, but can become a line or arc).
/// InvalidArgument for no strokes ("the drawing has no strokes") or a degenerate one (the message
/// names its index, counting from 0).
Result<ReplayResult> replay(const std::vector<Path>& strokes, double pixels_per_unit,
                            const BeautifyOptions& options = {});

/// Splits a stroke at its corners (§7.4.1): turn angles of tangents sampled every
/// `corner_step_px`, local maxima above `corner_angle_rad`; end pieces shorter than
/// `hook_fraction` × their neighbour are dropped as hooks if at most `hook_max_px` long, other
/// short pieces merged into a neighbour. A stroke
/// without corners is returned unchanged as the only element.
std::vector<Path> split_at_corners(const Path& stroke, const BeautifyOptions& options,
                                   double pixels_per_unit = 1.0);

/// The single-path search (§7.3) for one candidate against `context`: at most `max_results`
/// unique leaves, best first, each with its chained likelihood.
std::vector<std::pair<Candidate, double>> search(const Candidate& input, const RuleContext& context,
                                                 int max_results);

/// The rule context over the drawing's paths plus `extra` ones (earlier segments of the stroke).
RuleContext make_context(const ResolvedDrawing& drawing, const std::vector<ResolvedPath>& extra,
                         const BeautifyOptions& options);

}  // namespace exemplar::sketch
