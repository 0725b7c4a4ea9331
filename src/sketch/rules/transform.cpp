// Path transformation adjustment (§7.3.5): for a candidate that is a copy of a template, the
// similarity from every copy C of that template to the candidate is split into rotation, scale
// and translation (Eq. 7.5) and snapped: the rotation to a multiple of 2π/k (k = 2..12), the scale
// to 0.5 or an integer, and the translation so that the centre of rotation lands on an existing
// point (endpoints, arc centres, centres of rotation used), or — without rotation — so that the
// x or y offset from C becomes 0. All snaps that apply to one copy are combined into one
// suggestion whose likelihood is the geometric mean of theirs; snaps that would move the copy
// more than `shape_tolerance_px` are not proposed (ours). Reflected copies are left to the
// reflection rule. Fixes the transformation.

#include <cmath>
#include <numbers>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

class TransformRule final : public Rule {
public:
    const char* name() const override { return "transform"; }
    double threshold(const BeautifyOptions& o) const override { return o.transform.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        std::vector<RuleOutput> out;
        if (!adjustable_copy(input)) return out;
        const BeautifyOptions& o = *context.options;
        const double slack = o.transform.tolerance;
        for (int j : copies_of(context, input.instance->template_path)) {
            const ResolvedPath& copy = *context.paths[static_cast<std::size_t>(j)];
            const Affine rel = relative_to(input, copy);
            const SimilarityParts parts = decompose_similarity(rel);
            if (parts.reflected) continue;
            std::vector<double> scores;
            std::string detail;

            double rotation = parts.rotation_rad;
            const auto [snapped_rotation, rotation_error] = snap_rotation(rotation);
            if (rotation_error > 1e-12 && rotation_error < o.rotation_snap_rad * slack) {
                rotation = snapped_rotation;
                scores.push_back(falloff(rotation_error, o.rotation_snap_rad * slack));
                detail += std::string(" rotation ") + degrees(rotation) + "°";
            }
            double scale = parts.scale;
            const double scale_target = scale < 0.75 ? 0.5 : std::round(scale);
            const double scale_error = std::abs(scale / scale_target - 1.0);
            if (scale_error > 1e-12 && scale_error < o.scale_snap * slack) {
                scale = scale_target;
                scores.push_back(falloff(scale_error, o.scale_snap * slack));
                detail += std::string(" scale ") + fixed1(scale);
            }
            // The adjusted map keeps the copy's centroid where the candidate has it.
            const Vec2 anchor = centroid(copy.match);
            Affine adjusted = Affine::similarity(rotation, scale, {});
            const Vec2 target = rel.apply(anchor);
            const Vec2 moved_anchor = adjusted.apply(anchor);
            adjusted.tx = target.x - moved_anchor.x;
            adjusted.ty = target.y - moved_anchor.y;

            std::optional<Vec2> rotation_center;
            if (std::abs(wrap_angle(rotation)) > 1e-9) {
                if (auto snap = snap_center(adjusted, context, j)) {
                    const Vec2 q = snap->first;
                    const Vec2 aq = adjusted.apply_vector(q);
                    adjusted.tx = q.x - aq.x;
                    adjusted.ty = q.y - aq.y;
                    rotation_center = q;
                    scores.push_back(snap->second);
                    detail += " centre of rotation on a point";
                }
            } else {
                const Vec2 offset = adjusted.apply(anchor) - anchor;
                const double tol = context.units(o.translation_snap_px * slack);
                for (int axis = 0; axis < 2; ++axis) {
                    const double v = axis == 0 ? offset.x : offset.y;
                    if (std::abs(v) < 1e-12 || std::abs(v) >= tol) continue;
                    (axis == 0 ? adjusted.tx : adjusted.ty) -= v;
                    scores.push_back(falloff(std::abs(v), tol));
                    detail += axis == 0 ? " aligned vertically" : " aligned horizontally";
                }
            }
            if (scores.empty()) continue;
            double log_sum = 0.0;
            for (double s : scores) log_sum += std::log(std::max(s, 1e-12));
            const double likelihood = std::exp(log_sum / static_cast<double>(scores.size()));
            if (likelihood < o.transform.threshold) continue;
            const Affine correction = compose(adjusted, rel.inverse());
            Candidate c = moved(input, correction);
            // Snapping must not carry the copy far from where it was drawn.
            const double moved_px = context.px(move_distance(c, input, o.match_samples));
            if (falloff(moved_px, o.shape_tolerance_px) < o.transform.threshold) continue;
            c.instance->relative_to = j;
            c.instance->relative = adjusted;
            c.fixed.transform = true;
            if (rotation_center) c.rotation_center = rotation_center;
            Relation r{name(),
                       std::string("transform:") + std::to_string(j),
                       {copy.stroke},
                       likelihood,
                       "transformation from " + stroke_name(context, j) + " snapped:" + detail};
            out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
        }
        keep_best(out, 3);
        return out;
    }

private:
    // The existing point nearest to the map's centre of rotation, with its likelihood.
    static std::optional<std::pair<Vec2, double>> snap_center(const Affine& m,
                                                              const RuleContext& context,
                                                              int copy) {
        // Fixed point: (I − A)·c = t.
        const double a = 1 - m.a, b = -m.c, c = -m.b, d = 1 - m.d;
        const double det = a * d - b * c;
        if (std::abs(det) < 1e-12) return std::nullopt;
        const Vec2 center{(d * m.tx - b * m.ty) / det, (a * m.ty - c * m.tx) / det};
        const double tol = context.options->center_search_px * context.options->transform.tolerance;
        std::optional<std::pair<Vec2, double>> best;
        auto consider = [&](Vec2 q) {
            const double s = falloff(context.px(distance(q, center)), tol);
            if (s > 0.0 && (!best || s > best->second)) best = std::make_pair(q, s);
        };
        for (std::size_t i = 0; i < context.paths.size(); ++i) {
            const ResolvedPath& p = *context.paths[i];
            if (!p.geometric || static_cast<int>(i) == copy) continue;
            if (p.kind == ShapeKind::Arc || p.kind == ShapeKind::Circle) consider(p.arc.center);
            if (!p.path.closed) {
                consider(p.path.start());
                consider(p.path.end());
            }
        }
        for (Vec2 q : context.rotation_centers) consider(q);
        return best;
    }
};

}  // namespace

std::unique_ptr<Rule> make_transform_rule() {
    return std::make_unique<TransformRule>();
}

}  // namespace exemplar::sketch::rules
