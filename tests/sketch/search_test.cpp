// The search (§7.3) and multi-segment processing (§7.4): ranking, the input as the last
// suggestion, N, determinism, corner splitting and joined segments.

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "exemplar/sketch/beautify.hpp"
#include "sketch_test_util.hpp"

namespace exemplar::sketch {
namespace {

using testing::Canvas;
using testing::wobbly;

bool has_rule(const Suggestion& s, const std::string& rule) {
    for (const Relation& r : s.relations()) {
        if (r.rule == rule) return true;
    }
    return false;
}

std::string path_signature(const Suggestion& s) {
    std::string out;
    for (Vec2 p : sample_path(s.path, 8))
        out += std::to_string(p.x) + "," + std::to_string(p.y) + ";";
    return out;
}

TEST(SketchSearch, FirstSuggestionEnforcesTheObviousRelations) {
    Canvas canvas;
    canvas.add_line({0, 0}, {200, 0});
    // Nearly parallel, starting near nothing: a line parallel to the first.
    const Path stroke = wobbly({{10, 60}, {190, 66}}, 0.8, 21);
    auto s = suggest(canvas.drawing, stroke, canvas.options);
    ASSERT_TRUE(s.ok()) << s.status().message();
    ASSERT_GE(s->size(), 2u);
    const Suggestion& best = s->front();
    EXPECT_TRUE(has_rule(best, "line"));
    EXPECT_TRUE(has_rule(best, "parallel"));
    const Vec2 d = best.path.end() - best.path.start();
    EXPECT_NEAR(std::atan2(d.y, d.x), 0.0, 1e-6);
    // The last suggestion is the input itself.
    EXPECT_TRUE(s->back().original);
    EXPECT_EQ(s->back().path.segments.size(), stroke.segments.size());
    EXPECT_LE(s->size(), 10u);
    for (const Suggestion& x : *s) {
        EXPECT_GE(x.likelihood, 0.0);
        EXPECT_LE(x.likelihood, 1.0);
    }
}

TEST(SketchSearch, SuggestionsAreUniqueBoundedAndDeterministic) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    canvas.add_line({100, 0}, {100, 100});
    canvas.add_line({0, 100}, {100, 100});
    const Path stroke = wobbly({{2, 97}, {1, 4}}, 0.8, 22);
    for (int n : {1, 3, 10}) {
        canvas.options.max_suggestions = n;
        auto a = suggest(canvas.drawing, stroke, canvas.options);
        auto b = suggest(canvas.drawing, stroke, canvas.options);
        ASSERT_TRUE(a.ok() && b.ok());
        ASSERT_LE(a->size(), static_cast<std::size_t>(n));
        ASSERT_EQ(a->size(), b->size());
        for (std::size_t i = 0; i < a->size(); ++i) {
            EXPECT_EQ(path_signature((*a)[i]), path_signature((*b)[i]));
            for (std::size_t j = 0; j < i; ++j) {
                EXPECT_GT(max_pointwise_distance(sample_path((*a)[i].path, 16),
                                                 sample_path((*a)[j].path, 16)),
                          0.49);
            }
        }
    }
    // With room for several, the first is a vertical line from the corner (0, 100), and one of
    // the first three closes the square exactly at both corners (Eq. 7.1 ranks declining the
    // weaker second snap, 6.6 px off, just above applying it).
    canvas.options.max_suggestions = 10;
    auto s = suggest(canvas.drawing, stroke, canvas.options);
    ASSERT_TRUE(s.ok());
    ASSERT_GE(s->size(), 3u);
    EXPECT_NEAR(distance(s->front().path.start(), {0, 100}), 0.0, 1e-9);
    EXPECT_NEAR(s->front().path.end().x, 0.0, 1e-9);
    bool closed_square = false;
    for (std::size_t k = 0; k < 3; ++k) {
        closed_square |= distance((*s)[k].path.start(), {0, 100}) < 1e-9 &&
                         distance((*s)[k].path.end(), {0, 0}) < 1e-9;
    }
    EXPECT_TRUE(closed_square);
}

TEST(SketchSearch, LikelihoodChainsTheRuleLikelihoods) {
    // Eq. 7.1: L = 1 − Π(1 − L_k) over the applications on the branch; declined rules add
    // factors (1 − max) too, so L is at least the product over the applied relations alone.
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    canvas.add_line({100, 0}, {100, 100});
    canvas.add_line({100, 100}, {0, 100});
    const RuleContext context = canvas.context();
    const auto found = search(make_candidate(wobbly({{3, 97}, {1, 3}}, 0.8, 27)), context, 10);
    ASSERT_GE(found.size(), 2u);
    // Endpoint snapping applies once per endpoint: some suggestion snaps both.
    bool both = false;
    for (const auto& [candidate, score] : found) {
        int snaps = 0;
        for (const Relation& r : candidate.relations) snaps += r.rule == "endpoint";
        EXPECT_LE(snaps, 2);
        both |= snaps == 2 && candidate.fixed.start && candidate.fixed.end;
    }
    EXPECT_TRUE(both);
    for (std::size_t i = 0; i < found.size(); ++i) {
        const auto& [candidate, score] = found[i];
        double keep = 1.0;
        for (const Relation& r : candidate.relations) keep *= 1.0 - r.likelihood;
        EXPECT_GE(score, 1.0 - keep - 1e-12);
        EXPECT_LE(score, 1.0);
        // Applied and declined rules on one branch are distinct (no rule twice).
        std::set<std::string> rules;
        for (const Relation& r : candidate.relations) {
            if (r.rule != "endpoint") {  // once per endpoint
                EXPECT_TRUE(rules.insert(r.rule).second) << r.rule;
            }
        }
        for (const std::string& d : candidate.declined) {
            EXPECT_TRUE(rules.insert("!" + d).second) << d;
        }
    }
}

TEST(SketchSearch, NothingToDoGivesOnlyTheInput) {
    Canvas canvas;
    const Path stroke = wobbly(testing::s_curve({0, 0}), 0.3, 23);
    auto s = suggest(canvas.drawing, stroke, canvas.options);
    ASSERT_TRUE(s.ok());
    ASSERT_EQ(s->size(), 1u);
    EXPECT_TRUE(s->front().original);
}

TEST(SketchSearch, DegenerateStrokeAndBadOptionsAreErrors) {
    Canvas canvas;
    Path dot;
    dot.segments.push_back(line_cubic({5, 5}, {5, 5}));
    auto s = suggest(canvas.drawing, dot, canvas.options);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.status().message().find("degenerate"), std::string::npos);
    EXPECT_FALSE(suggest(canvas.drawing, Path{}, canvas.options).ok());
    canvas.options.max_suggestions = 0;
    auto bad = suggest(canvas.drawing, polyline_path({{0, 0}, {10, 0}}), canvas.options);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.status().message(), "max-suggestions: 0 is invalid (must be 1..100)");
}

TEST(SketchSearch, CornersSplitAStrokeIntoSegments) {
    const BeautifyOptions options;
    const Path l_shape = wobbly({{0, 0}, {100, 0}, {100, 80}}, 0.5, 24);
    const std::vector<Path> pieces = split_at_corners(l_shape, options);
    ASSERT_EQ(pieces.size(), 2u);
    EXPECT_NEAR(distance(pieces[0].end(), {100, 0}), 0.0, 3.0);
    // A smooth curve has no corners.
    EXPECT_EQ(split_at_corners(arc_path({0, 0}, 50, 0, 3), options).size(), 1u);
    // A short hook at the end is dropped.
    const Path hooked = polyline_path({{0, 0}, {100, 0}, {100, 5}});
    EXPECT_EQ(split_at_corners(hooked, options).size(), 1u);
}

TEST(SketchSearch, MultiSegmentStrokeBecomesJoinedLines) {
    Canvas canvas;
    // A triangle drawn in one closed stroke.
    const Path triangle = wobbly({{0, 0}, {120, 2}, {58, 100}, {0, 0}}, 0.6, 25);
    auto s = suggest(canvas.drawing, triangle, canvas.options);
    ASSERT_TRUE(s.ok()) << s.status().message();
    const Suggestion& best = s->front();
    ASSERT_EQ(best.segments.size(), 3u);
    for (const Candidate& c : best.segments) EXPECT_EQ(c.kind, ShapeKind::Line);
    // Joined end to end and closed.
    EXPECT_EQ(best.segments[1].path.start(), best.segments[0].path.end());
    EXPECT_EQ(best.segments[2].path.start(), best.segments[1].path.end());
    EXPECT_EQ(best.segments[2].path.end(), best.segments[0].path.start());
    EXPECT_TRUE(best.path.closed);
    // Accepting adds the three segments and the whole stroke (for the identity rules).
    accept(canvas.drawing, best, canvas.options);
    EXPECT_EQ(canvas.drawing.paths.size(), 4u);
    EXPECT_EQ(canvas.drawing.strokes, 1);
}

TEST(SketchSearch, MirroredStrokeIsBeautifiedAsAReflection) {
    Canvas canvas;
    const std::vector<Vec2> shape = testing::s_curve({40, 0});
    canvas.add_curve(fit_path(shape));
    const Path copy = wobbly(testing::mapped(shape, Affine::reflection({200, 0}, {0, 1})), 0.8, 26);
    auto s = suggest(canvas.drawing, copy, canvas.options);
    ASSERT_TRUE(s.ok());
    EXPECT_TRUE(has_rule(s->front(), "identity"));
    EXPECT_TRUE(has_rule(s->front(), "reflection"));
    accept(canvas.drawing, s->front(), canvas.options);
    ASSERT_EQ(canvas.drawing.axes.size(), 1u);
    EXPECT_NEAR(canvas.drawing.axes[0].point.x, 200, 0.5);
}

}  // namespace
}  // namespace exemplar::sketch
