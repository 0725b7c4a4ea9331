#pragma once
// Helpers shared by the rules: likelihood falloff, moving a candidate by a similarity while
// keeping its annotations consistent, pivots that respect fixed endpoints.

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "exemplar/sketch/rule.hpp"

namespace exemplar::sketch::rules {

/// 1 at x = 0 falling linearly to 0 at x = tolerance.
inline double falloff(double x, double tolerance) {
    return tolerance > 0.0 ? std::clamp(1.0 - x / tolerance, 0.0, 1.0) : 0.0;
}

/// The candidate moved by `m` (a similarity, possibly reflecting): path, arc parameters and the
/// copy's transforms follow; attachments are kept (callers move only free parts).
Candidate moved(const Candidate& c, const Affine& m);

/// The candidate with `relation` appended.
Candidate with_relation(Candidate c, Relation relation);

/// Unit chord direction and its length.
inline Vec2 chord(const Candidate& c) {
    return c.path.end() - c.path.start();
}

/// chord length / arc length in [0, 1] (1 for a straight path).
double straightness(const Path& path);

/// The point a rotation or scaling may turn about without moving a fixed endpoint: the fixed
/// endpoint, else the chord midpoint; nothing if both endpoints are fixed.
std::optional<Vec2> pivot(const Candidate& c);

/// The stroke numbers of resolved paths (for relations).
inline int stroke_of(const RuleContext& context, int path) {
    return path >= 0 && path < static_cast<int>(context.paths.size())
               ? context.paths[static_cast<std::size_t>(path)]->stroke
               : -1;
}

/// "stroke 7", or "segment 2 of this stroke" for an earlier segment of the stroke being processed.
std::string stroke_name(const RuleContext& context, int path);

/// A candidate replaced by the straight line a→b.
Candidate as_line(const Candidate& c, Vec2 a, Vec2 b);
/// A candidate replaced by an arc or circle.
Candidate as_arc(const Candidate& c, const ArcGeometry& arc, bool circle);

/// `count` equally spaced samples of the candidate's path.
inline std::vector<Vec2> samples(const Candidate& c, int count) {
    return sample_path(c.path, count);
}

/// Largest distance between corresponding samples of two candidates' paths (how far a rule
/// moved the path).
double move_distance(const Candidate& a, const Candidate& b, int count);

/// Centroid of points.
Vec2 centroid(const std::vector<Vec2>& points);

/// 1 − (1 − s)^ln(i): the boost for a relation already used by i paths (§7.3.4, §7.3.5);
/// s itself when ln(i) ≤ 1 (i < 3), where the formula would lower the score.
double repeat_boost(double s, int i);

/// Keeps the `keep` most likely outputs (stable for ties).
void keep_best(std::vector<RuleOutput>& outputs, std::size_t keep);

/// "12.3" with one decimal.
std::string fixed1(double v);
/// Degrees from radians, one decimal.
inline std::string degrees(double rad) {
    return fixed1(rad * 180.0 / 3.14159265358979323846);
}

/// Lines and arcs of the copies-rules: the resolved paths that are copies of `template_path`
/// (including the template itself).
std::vector<int> copies_of(const RuleContext& context, int template_path);

/// True if the candidate is a copy whose transformation may still be adjusted (the
/// transformation, reflection and step rules): a copy, transformation and endpoints free.
inline bool adjustable_copy(const Candidate& c) {
    return c.instance && !c.fixed.transform && !c.fixed.start && !c.fixed.end;
}

/// The similarity carrying resolved copy `copy` onto the candidate (both copies of one template).
inline Affine relative_to(const Candidate& c, const ResolvedPath& copy) {
    return compose(c.instance->from_template, copy.from_template.inverse());
}

/// Snaps an angle to the nearest multiple of 2π/k (k = 1..12); returns the snapped angle and
/// its distance.
std::pair<double, double> snap_rotation(double angle_rad);

/// Angle wrapped to (−π, π].
double wrap_angle(double a);

/// Shared body of the parallelism and perpendicularity rules: rotates a line-like candidate so
/// that its chord makes `offset_rad` (0 or π/2) with resolved lines.
std::vector<RuleOutput> snap_line_angle(const Candidate& input, const RuleContext& context,
                                        const RuleParams& params, double offset_rad,
                                        const char* rule_name);

}  // namespace exemplar::sketch::rules
