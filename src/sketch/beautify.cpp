// Stroke-level beautification: corner splitting (§7.4.1), per-segment processing with the
// intermediate-state reduction (§7.4.2) and internal restrictions (§7.4.3), joining (§7.4.4),
// and accepting a suggestion into the resolved drawing.

#include "exemplar/sketch/beautify.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "exemplar/sketch/fit.hpp"

namespace exemplar::sketch {

std::vector<Relation> Suggestion::relations() const {
    std::vector<Relation> all;
    for (const Candidate& c : segments)
        all.insert(all.end(), c.relations.begin(), c.relations.end());
    return all;
}

Status validate(const BeautifyOptions& o) {
    auto range = [](const char* name, double v, double lo, double hi) -> Status {
        if (std::isfinite(v) && v >= lo && v <= hi) return Status::ok();
        char buffer[160];
        std::snprintf(buffer, sizeof buffer, "%s: %g is invalid (must be %g..%g)", name, v, lo, hi);
        return invalid_argument(buffer);
    };
    EXEMPLAR_RETURN_IF_ERROR(range("max-suggestions", o.max_suggestions, 1, 100));
    EXEMPLAR_RETURN_IF_ERROR(range("segment-suggestions", o.segment_suggestions, 1, 100));
    EXEMPLAR_RETURN_IF_ERROR(range("intermediate-states", o.intermediate_states, 1, 1000));
    EXEMPLAR_RETURN_IF_ERROR(range("max-expansions", o.max_expansions, 0, 1000000));
    EXEMPLAR_RETURN_IF_ERROR(range("rdp-epsilon-px", o.rdp_epsilon_px, 0, 1000));
    EXEMPLAR_RETURN_IF_ERROR(range("match-samples", o.match_samples, 4, 4096));
    EXEMPLAR_RETURN_IF_ERROR(range("corner-step-px", o.corner_step_px, 0.1, 100));
    EXEMPLAR_RETURN_IF_ERROR(range("corner-angle-rad", o.corner_angle_rad, 0.01, 10));
    EXEMPLAR_RETURN_IF_ERROR(range("hook-fraction", o.hook_fraction, 0, 1));
    EXEMPLAR_RETURN_IF_ERROR(range("hook-max-px", o.hook_max_px, 0, 1000));
    EXEMPLAR_RETURN_IF_ERROR(range("shape-tolerance-px", o.shape_tolerance_px, 0, 10000));
    EXEMPLAR_RETURN_IF_ERROR(range("center-search-px", o.center_search_px, 0, 10000));
    EXEMPLAR_RETURN_IF_ERROR(range("offset-percentile", o.offset_percentile, 0, 50));
    return Status::ok();
}

RuleContext make_context(const ResolvedDrawing& drawing, const std::vector<ResolvedPath>& extra,
                         const BeautifyOptions& options) {
    RuleContext context;
    context.paths.reserve(drawing.paths.size() + extra.size());
    for (const ResolvedPath& p : drawing.paths) context.paths.push_back(&p);
    for (const ResolvedPath& p : extra) context.paths.push_back(&p);
    context.axes = drawing.axes;
    context.rotation_centers = drawing.rotation_centers;
    context.pixels_per_unit = drawing.pixels_per_unit;
    context.current_stroke = drawing.strokes;
    context.options = &options;
    return context;
}

std::vector<Path> split_at_corners(const Path& stroke, const BeautifyOptions& options,
                                   double pixels_per_unit) {
    const double step = options.corner_step_px / pixels_per_unit;
    const std::vector<Vec2> pts = resample_by_step(flatten(stroke, step / 4), step);
    if (pts.size() < 7) return {stroke};
    // Turn at each inner sample from its two neighbouring tangents (a window of three samples),
    // summed over ±2 samples so that a corner rounded over a few pixels still counts.
    const std::size_t m = pts.size();
    std::vector<double> turn(m, 0.0), windowed(m, 0.0);
    for (std::size_t i = 1; i + 1 < m; ++i)
        turn[i] = angle_between(pts[i] - pts[i - 1], pts[i + 1] - pts[i]);
    for (std::size_t i = 1; i + 1 < m; ++i) {
        for (std::size_t j = i >= 2 ? i - 2 : 0; j <= std::min(m - 1, i + 2); ++j)
            windowed[i] += turn[j];
    }
    std::vector<std::size_t> corners;
    for (std::size_t i = 3; i + 3 < m; ++i) {
        if (windowed[i] < options.corner_angle_rad) continue;
        bool local_max = true;
        for (std::size_t j = i - 2; j <= i + 2; ++j) {
            if (j == i) continue;
            if (windowed[j] > windowed[i] || (j < i && windowed[j] == windowed[i]))
                local_max = false;
        }
        if (local_max) corners.push_back(i);
    }
    if (corners.empty()) return {stroke};

    // Pieces between corners; drop end hooks and merge short inner pieces (§7.4.1).
    std::vector<std::vector<Vec2>> pieces;
    std::size_t first = 0;
    for (std::size_t c : corners) {
        pieces.emplace_back(pts.begin() + static_cast<long>(first),
                            pts.begin() + static_cast<long>(c) + 1);
        first = c;
    }
    pieces.emplace_back(pts.begin() + static_cast<long>(first), pts.end());
    bool changed = true;
    while (changed && pieces.size() > 1) {
        changed = false;
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            const double length = polyline_length(pieces[k]);
            const double left = k > 0 ? polyline_length(pieces[k - 1]) : 0.0;
            const double right = k + 1 < pieces.size() ? polyline_length(pieces[k + 1]) : 0.0;
            const double neighbour =
                k == 0 ? right : (k + 1 == pieces.size() ? left : std::min(left, right));
            if (length >= options.hook_fraction * neighbour) continue;
            const bool end_piece = k == 0 || k + 1 == pieces.size();
            if (end_piece && length * pixels_per_unit <= options.hook_max_px) {
                pieces.erase(pieces.begin() + static_cast<long>(k));  // a hook at an end
            } else {
                // A short piece that is more than a hook: merge it into its shorter neighbour
                // (the corner between them is ignored) so that no stroke part is lost.
                const std::size_t into =
                    k == 0 ? 1 : (k + 1 == pieces.size() ? k - 1 : (left <= right ? k - 1 : k + 1));
                std::vector<Vec2>& target = pieces[into];
                if (into < k) {
                    target.insert(target.end(), pieces[k].begin() + 1, pieces[k].end());
                } else {
                    target.insert(target.begin(), pieces[k].begin(), pieces[k].end() - 1);
                }
                pieces.erase(pieces.begin() + static_cast<long>(k));
            }
            changed = true;
            break;
        }
    }
    FitOptions fit;
    fit.tolerance = 0.75 / pixels_per_unit;
    fit.corner_angle_rad = std::numbers::pi;  // the pieces are smooth by construction
    std::vector<Path> out;
    for (const std::vector<Vec2>& piece : pieces) {
        Path p = fit_path(piece, fit);
        p.closed = false;
        if (!p.empty()) out.push_back(p);
    }
    if (out.empty() || (out.size() == 1 && pieces.front().size() == pts.size())) return {stroke};
    return out;
}

namespace {

struct State {
    std::vector<Candidate> segments;
    std::vector<ResolvedPath> resolved;
    double score_sum = 0.0;
    double mean() const { return segments.empty() ? 0.0 : score_sum / segments.size(); }
};

// Moves one end of a segment onto `target` by a similarity about the other end.
Candidate pinned(Candidate c, bool at_start, Vec2 target) {
    const Vec2 p = at_start ? c.path.start() : c.path.end();
    const Vec2 other = at_start ? c.path.end() : c.path.start();
    const Vec2 u = p - other, v = target - other;
    Affine m = Affine::translation(target - p);
    if (norm(u) > 1e-9 && norm(v) > 1e-9) {
        m = Affine::similarity(std::atan2(cross(u, v), dot(u, v)), norm(v) / norm(u), other);
    }
    c.path = transformed(c.path, m);
    if (at_start) {
        c.path.segments.front().p0 = target;
        c.fixed.start = true;
    } else {
        c.path.segments.back().p3 = target;
        c.fixed.end = true;
    }
    return c;
}

Path joined(const std::vector<Candidate>& segments, bool closed) {
    Path path;
    for (const Candidate& c : segments) {
        for (Cubic cubic : c.path.segments) {
            if (!path.empty()) {
                if (&cubic == &c.path.segments.front()) cubic.p0 = path.end();
            }
            path.segments.push_back(cubic);
        }
    }
    for (std::size_t i = 1; i < path.segments.size(); ++i)
        path.segments[i].p0 = path.segments[i - 1].p3;
    if (closed && !path.empty()) {
        path.segments.back().p3 = path.segments.front().p0;
        path.closed = true;
    }
    return path;
}

std::vector<Vec2> coarse(const Path& p) {
    return sample_path(p, 16);
}

}  // namespace

Result<std::vector<Suggestion>> suggest(const ResolvedDrawing& drawing, const Path& stroke,
                                        const BeautifyOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (stroke.empty() || drawing.pixels_per_unit * arc_length(stroke) < 1e-6) {
        return invalid_argument("stroke is degenerate (a single point)");
    }
    const double ppu = drawing.pixels_per_unit;
    const std::vector<Path> pieces = split_at_corners(stroke, options, ppu);
    const bool closed =
        stroke.closed || (pieces.size() > 1 && ppu * distance(stroke.start(), stroke.end()) < 1.0);
    std::vector<Suggestion> out;
    const int wanted = std::max(1, options.max_suggestions - 1);  // the input itself is last

    if (pieces.size() == 1) {
        const RuleContext context = make_context(drawing, {}, options);
        for (auto& [candidate, score] : search(make_candidate(pieces[0]), context, wanted)) {
            Suggestion s;
            s.path = candidate.path;
            s.likelihood = score;
            s.segments.push_back(std::move(candidate));
            out.push_back(std::move(s));
        }
    } else {
        // Segments one at a time, breadth first over intermediate states (§7.4.2).
        std::vector<State> states(1);
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            std::vector<State> next;
            for (const State& state : states) {
                Candidate input = make_candidate(pieces[k]);
                if (k > 0) {  // §7.4.3: starts where the previous segment ends
                    const ResolvedPath& previous = state.resolved.back();
                    input = pinned(input, true, previous.path.end());
                    input.start_attachment = Attachment{
                        static_cast<int>(drawing.paths.size() + state.resolved.size() - 1),
                        previous.path.end(), end_tangent(previous.path), true};
                }
                if (closed && k + 1 == pieces.size()) {
                    input = pinned(input, false, state.segments.front().path.start());
                }
                const RuleContext context = make_context(drawing, state.resolved, options);
                for (auto& [candidate, score] :
                     search(input, context, options.segment_suggestions)) {
                    State grown = state;
                    grown.resolved.push_back(resolve_path(candidate, drawing.strokes,
                                                          static_cast<int>(k), ppu, options));
                    grown.segments.push_back(std::move(candidate));
                    grown.score_sum += score;
                    next.push_back(std::move(grown));
                }
            }
            std::stable_sort(next.begin(), next.end(),
                             [](const State& a, const State& b) { return a.mean() > b.mean(); });
            if (next.size() > static_cast<std::size_t>(options.intermediate_states)) {
                next.resize(static_cast<std::size_t>(options.intermediate_states));
            }
            states = std::move(next);
        }
        std::vector<std::vector<Vec2>> seen;
        for (State& state : states) {
            if (static_cast<int>(out.size()) >= wanted) break;
            Suggestion s;
            s.path = joined(state.segments, closed);
            const std::vector<Vec2> mine = coarse(s.path);
            bool duplicate = false;
            for (const auto& other : seen) {
                duplicate |= ppu * max_pointwise_distance(mine, other) < options.duplicate_px;
            }
            if (duplicate) continue;
            seen.push_back(mine);
            s.likelihood = state.mean();
            s.segments = std::move(state.segments);
            out.push_back(std::move(s));
        }
    }

    // Most likely first (Eq. 7.1); the search's discovery order breaks ties.
    std::stable_sort(out.begin(), out.end(), [](const Suggestion& a, const Suggestion& b) {
        return a.likelihood > b.likelihood;
    });
    // The input itself, last (§7.5), unless a suggestion is already (nearly) the input: then
    // that one stands for it, and a suggestion with no relation at all is the input.
    const std::vector<Vec2> mine = coarse(stroke);
    bool input_present = false;
    for (Suggestion& s : out) {
        if (ppu * max_pointwise_distance(coarse(s.path), mine) >= options.duplicate_px) continue;
        input_present = true;
        if (s.relations().empty()) s.original = true;
    }
    // With room for one suggestion only, that is the best one (the input if nothing applies).
    if (input_present || (options.max_suggestions == 1 && !out.empty())) return out;
    Suggestion original;
    original.path = stroke;
    original.original = true;
    original.segments.push_back(make_candidate(stroke));
    out.push_back(std::move(original));
    return out;
}

void accept(ResolvedDrawing& drawing, const Suggestion& suggestion,
            const BeautifyOptions& options) {
    const int stroke = drawing.strokes++;
    const bool single = suggestion.segments.size() == 1;
    for (std::size_t k = 0; k < suggestion.segments.size(); ++k) {
        const Candidate& c = suggestion.segments[k];
        ResolvedPath r =
            resolve_path(c, stroke, static_cast<int>(k), drawing.pixels_per_unit, options);
        const int index = static_cast<int>(drawing.paths.size());
        r.shape = single;
        r.template_path = index;
        if (c.instance && c.instance->template_path >= 0 && c.instance->template_path < index) {
            r.template_path = c.instance->template_path;
            r.from_template = c.instance->from_template;
            if (c.instance->relative_to >= 0) r.step = c.instance->relative;
            drawing.paths[static_cast<std::size_t>(r.template_path)].instances += 1;
        }
        if (c.axis) {
            bool found = false;
            for (Axis& a : drawing.axes) {
                if (line_angle_between(a.direction, c.axis->direction) < 1e-9 &&
                    std::abs(cross(normalized(a.direction), c.axis->point - a.point)) < 1e-6) {
                    a.uses += 1;
                    found = true;
                }
            }
            if (!found) drawing.axes.push_back({c.axis->point, c.axis->direction, 1});
        }
        if (c.rotation_center) drawing.rotation_centers.push_back(*c.rotation_center);
        drawing.paths.push_back(std::move(r));
    }
    if (!single) {  // the whole stroke, for the rules on copies (§7.4.4)
        ResolvedPath whole = resolve_path(make_candidate(suggestion.path), stroke, -1,
                                          drawing.pixels_per_unit, options);
        whole.geometric = false;
        whole.shape = true;
        whole.template_path = static_cast<int>(drawing.paths.size());
        drawing.paths.push_back(std::move(whole));
    }
}

}  // namespace exemplar::sketch

namespace exemplar::sketch {

Result<ReplayResult> replay(const std::vector<Path>& strokes, double pixels_per_unit,
                            const BeautifyOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (strokes.empty()) return invalid_argument("the drawing has no strokes");
    if (!(std::isfinite(pixels_per_unit) && pixels_per_unit > 0.0)) {
        return invalid_argument("pixels per unit: must be > 0");
    }
    ReplayResult result;
    result.resolved.pixels_per_unit = pixels_per_unit;
    for (std::size_t i = 0; i < strokes.size(); ++i) {
        auto suggestions = suggest(result.resolved, strokes[i], options);
        if (!suggestions.ok()) {
            return invalid_argument("stroke " + std::to_string(i) + ": " +
                                    suggestions.status().message());
        }
        StrokeResult stroke;
        stroke.input = strokes[i];
        stroke.chosen = suggestions->front();
        stroke.suggestion_count = static_cast<int>(suggestions->size());
        const std::vector<Vec2> before = resample_by_step(flatten(strokes[i], 0.5), 1.0);
        const std::vector<Vec2> after = resample_by_step(flatten(stroke.chosen.path, 0.5), 1.0);
        stroke.moved = discrete_frechet(before, after);
        stroke.size = bounding_diagonal(before);
        accept(result.resolved, stroke.chosen, options);
        result.strokes.push_back(std::move(stroke));
        if (i + 1 == strokes.size()) result.last_suggestions = std::move(suggestions).value();
    }
    return result;
}

}  // namespace exemplar::sketch
