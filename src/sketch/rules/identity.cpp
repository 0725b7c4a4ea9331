// Path identity (§7.3.4): the template paths of the drawing (one per set of copies) are aligned
// to the candidate by the least-squares similarity of Eq. 7.3–7.4 on equally spaced samples, in
// the four variants plain / reversed / reflected / reflected+reversed, and compared by the
// discrete Fréchet distance divided by the candidate's length. The candidate becomes the
// template under that similarity. Templates with i ≥ 3 copies get the boost 1 − (1 − s)^ln i.
// Deviations: lines and circles are not matched (every line or circle is similar to every other;
// the line and arc rules handle them), and the Fréchet distance is between point samples rather
// than points and the simplified template's segments; the likelihood is also capped by the
// absolute distance (`shape_tolerance_px`).

#include <algorithm>
#include <cmath>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

class IdentityRule final : public Rule {
public:
    const char* name() const override { return "identity"; }
    double threshold(const BeautifyOptions& o) const override { return o.identity.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        std::vector<RuleOutput> out;
        if (input.fixed.shape || input.fixed.start || input.fixed.end || input.instance) {
            return out;
        }
        if (input.kind == ShapeKind::Line || input.kind == ShapeKind::Circle) return out;
        const int n = context.options->match_samples;
        const std::vector<Vec2> mine = samples(input, n);
        const double length = polyline_length(mine);
        if (context.px(length) < 10.0) return out;
        const double own_straightness = distance(mine.front(), mine.back()) / length;
        const Affine flip = Affine::scaling(1.0, -1.0);

        for (std::size_t i = 0; i < context.paths.size(); ++i) {
            const ResolvedPath& t = *context.paths[i];
            if (!t.shape || t.template_path != static_cast<int>(i)) continue;
            if (t.kind == ShapeKind::Line || t.kind == ShapeKind::Circle) continue;
            if (t.match.size() != mine.size() || t.length <= 0.0) continue;
            // Cheap rejection: a similarity keeps the chord/length ratio.
            const double straightness_t = distance(t.match.front(), t.match.back()) / t.length;
            if (std::abs(straightness_t - own_straightness) > 0.25) continue;
            double best_error = 1e300;
            Affine best;
            bool best_reversed = false;
            for (int variant = 0; variant < 4; ++variant) {
                const bool reflect = variant >= 2, reverse = variant % 2 == 1;
                std::vector<Vec2> from = t.match;
                if (reflect) {
                    for (Vec2& p : from) p = flip.apply(p);
                }
                if (reverse) std::reverse(from.begin(), from.end());
                const Affine fit = fit_similarity(from, mine);
                std::vector<Vec2> aligned = from;
                for (Vec2& p : aligned) p = fit.apply(p);
                const double error = discrete_frechet(aligned, mine) / length;
                if (error < best_error) {
                    best_error = error;
                    best = reflect ? compose(fit, flip) : fit;
                    best_reversed = reverse;
                }
            }
            const double raw = std::min(
                falloff(best_error, context.options->identity.tolerance),
                falloff(context.px(best_error * length), context.options->shape_tolerance_px));
            const double likelihood = repeat_boost(raw, t.instances);
            if (likelihood < context.options->identity.threshold) continue;

            Candidate shape = input;  // the template moved onto the candidate
            shape.path = t.path;
            shape.kind = t.kind;
            shape.arc = t.arc;
            Candidate c = moved(shape, best);
            if (best_reversed) c.path = reversed(c.path);
            if (best_reversed && (c.kind == ShapeKind::Arc)) {
                c.arc.start_angle_rad += c.arc.sweep_rad;
                c.arc.sweep_rad = -c.arc.sweep_rad;
            }
            c.fixed.shape = true;
            const int index = static_cast<int>(i);
            c.instance = Instance{index, best, index, best, best_reversed};
            const SimilarityParts parts = decompose_similarity(best);
            Relation r{name(),
                       std::string("identity:") + std::to_string(i),
                       {t.stroke},
                       likelihood,
                       "copy of " + stroke_name(context, static_cast<int>(i)) +
                           (parts.reflected ? " (mirrored)" : "") + " (scale " +
                           fixed1(100 * parts.scale) + "%, rotation " +
                           degrees(parts.rotation_rad) + "°, off by " + fixed1(100 * best_error) +
                           "% of the length)"};
            out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
        }
        keep_best(out, 3);
        return out;
    }
};

}  // namespace

std::unique_ptr<Rule> make_identity_rule() {
    return std::make_unique<IdentityRule>();
}

}  // namespace exemplar::sketch::rules
