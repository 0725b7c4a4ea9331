// Offset path detection (§7.3.6, Fig. 7.11): from each sample of the candidate a line is cast
// along the normal; where it meets a resolved path, the distance from the sample to the closest
// point of that path is recorded with its side. The (50 ± n)-th percentiles (n = 25) of the
// signed distances must agree in side and be close relative to the median; then the candidate is
// replaced by the reference offset by the median distance, over the stretch of the reference the
// candidate spans. Deviations: a normal "hits" the reference when the direction to the closest
// reference point is within 30° of the normal (instead of an exact ray intersection); lines and
// arcs as references are left to parallelism and centre snapping; references farther than 40 view
// px are ignored; and the likelihood is capped by how far the stroke moves (`shape_tolerance_px`).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "exemplar/sketch/fit.hpp"
#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

constexpr double kHitCone = 0.52;        // 30°
constexpr double kMinHitFraction = 0.6;  // of the samples
constexpr double kMinOffsetPx = 3.0;
constexpr double kMaxOffsetPx = 40.0;  // farther references are not offsets of this stroke

class OffsetRule final : public Rule {
public:
    const char* name() const override { return "offset"; }
    double threshold(const BeautifyOptions& o) const override { return o.offset.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        std::vector<RuleOutput> out;
        if (input.kind != ShapeKind::Curve || input.fixed.shape || input.fixed.start ||
            input.fixed.end || input.path.closed) {
            return out;
        }
        const BeautifyOptions& o = *context.options;
        const int n = o.match_samples;
        const std::vector<Vec2> pts = samples(input, n);
        const double length = polyline_length(pts);
        if (context.px(length) < 10.0) return out;
        const double max_offset = context.units(kMaxOffsetPx);
        const Box box = bounding_box(pts);
        for (std::size_t i = 0; i < context.paths.size(); ++i) {
            const ResolvedPath& ref = *context.paths[i];
            if (!ref.geometric || ref.kind != ShapeKind::Curve || ref.dense.size() < 2) continue;
            if (!ref.box.near(box, max_offset)) continue;
            std::vector<double> signed_distances;
            for (std::size_t k = 0; k < pts.size(); ++k) {
                const Vec2 tangent =
                    normalized(pts[std::min(k + 1, pts.size() - 1)] - pts[k == 0 ? 0 : k - 1]);
                const Vec2 normal = perpendicular(tangent);
                if (ref.box.distance_to(pts[k]) > max_offset) continue;
                const ClosestPoint cp = closest_point(ref.dense, pts[k]);
                if (cp.distance > max_offset || cp.distance <= 0.0) continue;
                const Vec2 towards = (cp.point - pts[k]) / cp.distance;
                if (line_angle_between(towards, normal) > kHitCone) continue;
                signed_distances.push_back(dot(towards, normal) > 0 ? cp.distance : -cp.distance);
            }
            if (signed_distances.size() < kMinHitFraction * pts.size()) continue;
            std::sort(signed_distances.begin(), signed_distances.end());
            auto percentile = [&](double q) {
                const double at = q / 100.0 * static_cast<double>(signed_distances.size() - 1);
                return signed_distances[static_cast<std::size_t>(std::lround(at))];
            };
            const double lo = percentile(50 - o.offset_percentile);
            const double hi = percentile(50 + o.offset_percentile);
            const double median = percentile(50);
            if (lo * hi <= 0.0 || context.px(std::abs(median)) < kMinOffsetPx) continue;
            const double spread = std::abs(hi - lo) / std::abs(median);
            double likelihood = falloff(spread, o.offset.tolerance);
            if (likelihood < o.offset.threshold) continue;
            std::optional<Path> path = offset_stretch(ref, input, std::abs(median), context);
            if (!path) continue;
            Candidate c = input;
            c.path = *path;
            // The offset must replace the stroke where it was drawn.
            const double moved_px = context.px(discrete_frechet(pts, samples(c, n)));
            likelihood = std::min(likelihood, falloff(moved_px, o.shape_tolerance_px));
            if (likelihood < o.offset.threshold) continue;
            c.fixed.shape = true;
            Relation r{name(),
                       std::string("offset:") + std::to_string(i),
                       {ref.stroke},
                       likelihood,
                       "offset of " + stroke_name(context, static_cast<int>(i)) + " by " +
                           fixed1(context.px(std::abs(median))) + " px"};
            out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
        }
        keep_best(out, 3);
        return out;
    }

private:
    // The stretch of `ref` between the projections of the candidate's endpoints, offset by
    // `amount` towards the candidate's side, refitted as a smooth path in the candidate's
    // direction.
    static std::optional<Path> offset_stretch(const ResolvedPath& ref, const Candidate& input,
                                              double amount, const RuleContext& context) {
        const ClosestPoint a = closest_point(ref.dense, input.path.start());
        const ClosestPoint b = closest_point(ref.dense, input.path.end());
        const double from = std::min(a.arc_position, b.arc_position);
        const double to = std::max(a.arc_position, b.arc_position);
        if (context.px(to - from) < 6.0) return std::nullopt;
        // Side: the candidate's middle relative to the reference's normal there.
        const Vec2 middle = sample_path(input.path, 3)[1];
        const ClosestPoint m = closest_point(ref.dense, middle);
        const double side = dot(middle - m.point, perpendicular(m.tangent)) >= 0 ? 1.0 : -1.0;
        std::vector<Vec2> offset;
        double position = 0.0;
        for (std::size_t k = 0; k < ref.dense.size(); ++k) {
            if (k > 0) position += distance(ref.dense[k - 1], ref.dense[k]);
            if (position < from - 1e-9 || position > to + 1e-9) continue;
            const Vec2 before = ref.dense[k == 0 ? 0 : k - 1];
            const Vec2 after = ref.dense[std::min(k + 1, ref.dense.size() - 1)];
            const Vec2 normal = perpendicular(normalized(after - before));
            offset.push_back(ref.dense[k] + normal * (side * amount));
        }
        if (offset.size() < 2) return std::nullopt;
        if (a.arc_position > b.arc_position) std::reverse(offset.begin(), offset.end());
        FitOptions fit;
        fit.tolerance = context.units(0.5);
        Path path = fit_path(offset, fit);
        if (path.empty()) return std::nullopt;
        return path;
    }
};

}  // namespace

std::unique_ptr<Rule> make_offset_rule() {
    return std::make_unique<OffsetRule>();
}

}  // namespace exemplar::sketch::rules
