// Every rule of Fig. 7.3 on inputs with a known answer, and cases where it must not fire.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "exemplar/sketch/rule.hpp"
#include "sketch_test_util.hpp"

namespace exemplar::sketch {
namespace {

using testing::Canvas;
using testing::mapped;
using testing::s_curve;
using testing::wobbly;

constexpr double kPi = std::numbers::pi;

std::vector<RuleOutput> run(const char* rule, const Candidate& c, const RuleContext& context) {
    const std::unique_ptr<Rule> r = make_rule(rule);
    EXPECT_NE(r, nullptr) << rule;
    std::vector<RuleOutput> out = r->apply(c, context);
    for (const RuleOutput& o : out) {
        EXPECT_GE(o.likelihood, r->threshold(*context.options)) << rule;
        EXPECT_LE(o.likelihood, 1.0) << rule;
        EXPECT_FALSE(o.candidate.relations.empty()) << rule;
        EXPECT_EQ(o.candidate.relations.back().rule, rule);
    }
    return out;
}

Candidate line_candidate(Vec2 a, Vec2 b) {
    Candidate c = make_candidate(polyline_path({a, b}));
    c.kind = ShapeKind::Line;
    c.fixed.shape = true;
    return c;
}

double direction_angle(const Path& p) {
    const Vec2 d = p.end() - p.start();
    return std::atan2(d.y, d.x);
}

TEST(SketchRules, AllRulesOfFigure73AreRegistered) {
    const char* names[] = {"line",          "arc",          "endpoint",   "tangent",  "parallel",
                           "perpendicular", "equal-length", "arc-center", "identity", "transform",
                           "reflection",    "step",         "offset"};
    EXPECT_EQ(make_rules().size(), std::size(names));
    for (const char* n : names) EXPECT_NE(make_rule(n), nullptr) << n;
}

TEST(SketchRules, LineStraightensANearlyStraightStroke) {
    Canvas canvas;
    const Path stroke = wobbly({{10, 10}, {200, 60}}, 1.0, 1);
    const auto out = run("line", make_candidate(stroke), canvas.context());
    ASSERT_EQ(out.size(), 1u);
    const Candidate& c = out[0].candidate;
    EXPECT_EQ(c.kind, ShapeKind::Line);
    EXPECT_TRUE(c.fixed.shape);
    EXPECT_EQ(c.path.start(), stroke.start());
    EXPECT_EQ(c.path.end(), stroke.end());
    EXPECT_GT(out[0].likelihood, 0.8);
}

TEST(SketchRules, LineDoesNotFireOnACurve) {
    Canvas canvas;
    const Path quarter = arc_path({0, 0}, 50, 0, kPi / 2);
    EXPECT_TRUE(run("line", make_candidate(quarter), canvas.context()).empty());
}

TEST(SketchRules, ArcTurnsAJitteredCircleIntoACircleWithTheRightCentre) {
    Canvas canvas;
    std::vector<Vec2> ring;
    for (int i = 0; i <= 90; ++i) {
        const double a = 2 * kPi * i / 90.0;
        ring.push_back(Vec2{120, 80} + Vec2{std::cos(a), std::sin(a)} * 40.0);
    }
    const Path stroke = wobbly(ring, 1.2, 2);
    const auto out = run("arc", make_candidate(stroke), canvas.context());
    ASSERT_EQ(out.size(), 1u);
    const Candidate& c = out[0].candidate;
    EXPECT_EQ(c.kind, ShapeKind::Circle);
    EXPECT_TRUE(c.path.closed);
    EXPECT_NEAR(c.arc.center.x, 120, 0.5);
    EXPECT_NEAR(c.arc.center.y, 80, 0.5);
    EXPECT_NEAR(c.arc.radius, 40, 0.5);
    for (Vec2 p : flatten(c.path, 1.0)) EXPECT_NEAR(distance(p, c.arc.center), c.arc.radius, 0.02);
}

TEST(SketchRules, ArcFitsAnOpenArcAndKeepsAFixedEndpoint) {
    Canvas canvas;
    std::vector<Vec2> pts;
    for (int i = 0; i <= 40; ++i)
        pts.push_back(Vec2{0, 0} + Vec2{std::cos(2.0 * i / 40), std::sin(2.0 * i / 40)} * 60.0);
    Candidate c = make_candidate(wobbly(pts, 0.8, 3));
    c.fixed.start = true;
    const auto out = run("arc", c, canvas.context());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].candidate.kind, ShapeKind::Arc);
    EXPECT_NEAR(std::abs(out[0].candidate.arc.sweep_rad), 2.0, 0.1);
    EXPECT_EQ(out[0].candidate.path.start(), c.path.start());
}

TEST(SketchRules, ArcDoesNotFireOnALineOrAnSCurve) {
    Canvas canvas;
    EXPECT_TRUE(
        run("arc", make_candidate(wobbly({{0, 0}, {100, 5}}, 0.5, 4)), canvas.context()).empty());
    EXPECT_TRUE(
        run("arc", make_candidate(wobbly(s_curve({0, 0}), 0.5, 5)), canvas.context()).empty());
}

TEST(SketchRules, EndpointSnapsToANearbyEndpointExactly) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    const Candidate c = line_candidate({103, 4}, {150, 80});
    const auto out = run("endpoint", c, canvas.context());
    ASSERT_FALSE(out.empty());
    const Candidate& best = out[0].candidate;
    EXPECT_EQ(best.path.start(), (Vec2{100, 0}));
    EXPECT_TRUE(best.fixed.start);
    EXPECT_NEAR(distance(best.path.end(), {150, 80}), 0.0, 1e-9);  // the other end stays
    ASSERT_TRUE(best.start_attachment.has_value());
    EXPECT_TRUE(best.start_attachment->endpoint);
}

TEST(SketchRules, EndpointSnapsToAnInnerPoint) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    const auto out = run("endpoint", line_candidate({50, 3}, {50, 80}), canvas.context());
    ASSERT_FALSE(out.empty());
    EXPECT_NEAR(out[0].candidate.path.start().y, 0.0, 1e-9);
    EXPECT_NEAR(out[0].candidate.path.start().x, 50.0, 0.5);
    EXPECT_FALSE(out[0].candidate.start_attachment->endpoint);
}

TEST(SketchRules, EndpointDoesNotSnapFarOrFixedEnds) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    EXPECT_TRUE(run("endpoint", line_candidate({130, 40}, {200, 80}), canvas.context()).empty());
    Candidate fixed = line_candidate({103, 4}, {150, 80});
    fixed.fixed.start = true;
    EXPECT_TRUE(run("endpoint", fixed, canvas.context()).empty());
}

TEST(SketchRules, TangentAlignsASnappedCurveWithItsTarget) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    // A curve leaving (100, 0) about 6° off the line's direction.
    std::vector<Vec2> pts;
    for (int i = 0; i <= 30; ++i) {
        const double t = i / 30.0;
        pts.push_back(Vec2{100 + 80 * t, 80 * t * std::tan(0.1) + 30 * t * t});
    }
    Candidate c = make_candidate(fit_path(pts));
    c.fixed.start = true;
    c.start_attachment = Attachment{0, {100, 0}, {1, 0}, true};
    const auto out = run("tangent", c, canvas.context());
    ASSERT_EQ(out.size(), 1u);
    const Vec2 t = start_tangent(out[0].candidate.path);
    EXPECT_NEAR(std::abs(std::atan2(t.y, t.x)), 0.0, 1e-9);
    EXPECT_EQ(out[0].candidate.path.start(), (Vec2{100, 0}));
    EXPECT_TRUE(out[0].candidate.fixed.direction);
}

TEST(SketchRules, TangentDoesNotFireAtACornerOrWithoutASnap) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    Candidate corner = line_candidate({100, 0}, {150, 60});  // ~50°
    corner.fixed.start = true;
    corner.start_attachment = Attachment{0, {100, 0}, {1, 0}, true};
    EXPECT_TRUE(run("tangent", corner, canvas.context()).empty());
    EXPECT_TRUE(run("tangent", line_candidate({100, 0}, {150, 3}), canvas.context()).empty());
}

TEST(SketchRules, ParallelMakesNearlyParallelLinesExactlyParallel) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 10});
    const auto out = run("parallel", line_candidate({0, 50}, {100, 63}), canvas.context());
    ASSERT_EQ(out.size(), 1u);
    const double want = std::atan2(10.0, 100.0);
    EXPECT_NEAR(direction_angle(out[0].candidate.path), want, 1e-6);
    EXPECT_TRUE(out[0].candidate.fixed.direction);
}

TEST(SketchRules, ParallelKeepsAFixedEndpoint) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    Candidate c = line_candidate({0, 50}, {100, 54});
    c.fixed.start = true;
    const auto out = run("parallel", c, canvas.context());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].candidate.path.start(), (Vec2{0, 50}));
    EXPECT_NEAR(out[0].candidate.path.end().y, 50.0, 1e-9);
}

TEST(SketchRules, ParallelDoesNotFireOnSteepOrDirectionFixedLines) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    EXPECT_TRUE(run("parallel", line_candidate({0, 50}, {100, 110}), canvas.context()).empty());
    Candidate fixed = line_candidate({0, 50}, {100, 53});
    fixed.fixed.direction = true;
    EXPECT_TRUE(run("parallel", fixed, canvas.context()).empty());
}

TEST(SketchRules, PerpendicularMakesARightAngle) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    const auto out = run("perpendicular", line_candidate({50, 10}, {54, 90}), canvas.context());
    ASSERT_EQ(out.size(), 1u);
    EXPECT_NEAR(std::abs(direction_angle(out[0].candidate.path)), kPi / 2, 1e-6);
}

TEST(SketchRules, PerpendicularDoesNotFireAt45Degrees) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    EXPECT_TRUE(run("perpendicular", line_candidate({0, 10}, {60, 70}), canvas.context()).empty());
}

TEST(SketchRules, EqualLengthScalesToTheExactLength) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    const auto out = run("equal-length", line_candidate({0, 40}, {60, 123}), canvas.context());
    ASSERT_EQ(out.size(), 1u);  // |(60, 83)| = 102.4
    const Path& p = out[0].candidate.path;
    EXPECT_NEAR(distance(p.start(), p.end()), 100.0, 1e-9);
    EXPECT_NEAR(direction_angle(p), std::atan2(83.0, 60.0), 1e-12);
}

TEST(SketchRules, EqualLengthDoesNotFireOnDifferentLengthsOrCurves) {
    Canvas canvas;
    canvas.add_line({0, 0}, {100, 0});
    EXPECT_TRUE(run("equal-length", line_candidate({0, 40}, {150, 40}), canvas.context()).empty());
    EXPECT_TRUE(
        run("equal-length", make_candidate(wobbly({{0, 40}, {101, 40}}, 1, 6)), canvas.context())
            .empty());
}

TEST(SketchRules, ArcCenterSnapsToAnEndpoint) {
    Canvas canvas;
    canvas.add_line({0, 0}, {-100, 0});
    Candidate c = make_candidate(arc_path({4, 3}, 50, 0.2, 1.5));
    c.kind = ShapeKind::Arc;
    c.arc = {{4, 3}, 50, 0.2, 1.5};
    const auto out = run("arc-center", c, canvas.context());
    ASSERT_FALSE(out.empty());
    const ArcGeometry& arc = out[0].candidate.arc;
    EXPECT_EQ(arc.center, (Vec2{0, 0}));
    // Refitted around the new centre where it was drawn: the mean distance of the old arc.
    EXPECT_NEAR(arc.radius, 50, 5);
    for (Vec2 p : flatten(out[0].candidate.path, 1.0)) EXPECT_NEAR(norm(p), arc.radius, 0.02);
    // Same endpoint directions from the new centre.
    const Vec2 s = c.path.start();
    EXPECT_NEAR(arc.start_angle_rad, std::atan2(s.y, s.x), 1e-9);
}

TEST(SketchRules, ArcCenterSearchRadiusGrowsForFlatArcs) {
    // Fig. 7.6: a 20° arc of radius 200 may have its fitted centre 60 px off.
    Canvas canvas;
    canvas.add_line({0, 0}, {-100, 0});
    Candidate c = make_candidate(arc_path({60, 0}, 200, -0.17, 0.35));
    c.kind = ShapeKind::Arc;
    c.arc = {{60, 0}, 200, -0.17, 0.35};
    const auto out = run("arc-center", c, canvas.context());
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out[0].candidate.arc.center, (Vec2{0, 0}));
    // A full circle with the same offset is not snapped: D = 30 px.
    Candidate full = make_candidate(arc_path({60, 0}, 200, 0, 2 * kPi));
    full.kind = ShapeKind::Circle;
    full.arc = {{60, 0}, 200, 0, 2 * kPi};
    EXPECT_TRUE(run("arc-center", full, canvas.context()).empty());
}

TEST(SketchRules, IdentityFindsATransformedCopy) {
    Canvas canvas;
    const std::vector<Vec2> shape = s_curve({0, 0});
    canvas.add_curve(fit_path(shape));
    const Affine m = Affine::similarity(0.6, 0.8, {0, 0});
    const Affine placed = compose(Affine::translation({300, 50}), m);
    const Candidate c = make_candidate(wobbly(mapped(shape, placed), 1.0, 8));
    const auto out = run("identity", c, canvas.context());
    ASSERT_FALSE(out.empty());
    const Candidate& best = out[0].candidate;
    ASSERT_TRUE(best.instance.has_value());
    EXPECT_EQ(best.instance->template_path, 0);
    const SimilarityParts parts = decompose_similarity(best.instance->from_template);
    EXPECT_NEAR(parts.rotation_rad, 0.6, 0.02);
    EXPECT_NEAR(parts.scale, 0.8, 0.02);
    EXPECT_FALSE(parts.reflected);
    // The result is exactly the template under that transform.
    EXPECT_LT(max_pointwise_distance(
                  sample_path(best.path, 20),
                  sample_path(
                      transformed(canvas.drawing.paths[0].path, best.instance->from_template), 20)),
              1e-9);
}

TEST(SketchRules, IdentityDoesNotMatchADifferentShape) {
    Canvas canvas;
    canvas.add_curve(fit_path(s_curve({0, 0})));
    // A spiral-like hook is not an S.
    std::vector<Vec2> hook;
    for (int i = 0; i <= 60; ++i) {
        const double a = 4.0 * i / 60;
        hook.push_back(Vec2{200, 200} + Vec2{std::cos(a), std::sin(a)} * (20 + 10 * a));
    }
    EXPECT_TRUE(run("identity", make_candidate(fit_path(hook)), canvas.context()).empty());
}

// A template, then the candidate: a copy of it matched by the identity rule.
Candidate matched_copy(Canvas& canvas, const std::vector<Vec2>& copy_points, int salt) {
    const auto out =
        run("identity", make_candidate(wobbly(copy_points, 0.8, salt)), canvas.context());
    EXPECT_FALSE(out.empty());
    return out.empty() ? Candidate{} : out[0].candidate;
}

TEST(SketchRules, ReflectionDetectsAMirroredCopyAndItsAxis) {
    Canvas canvas;
    const std::vector<Vec2> shape = s_curve({40, 0});
    canvas.add_curve(fit_path(shape));
    // Mirror across the vertical line x = 200.
    const Affine mirror = Affine::reflection({200, 0}, {0, 1});
    const Candidate copy = matched_copy(canvas, mapped(shape, mirror), 9);
    const auto out = run("reflection", copy, canvas.context());
    ASSERT_FALSE(out.empty());
    const Candidate& best = out[0].candidate;
    ASSERT_TRUE(best.axis.has_value());
    EXPECT_LT(line_angle_between(best.axis->direction, {0, 1}), 0.01);  // < 0.6°
    EXPECT_NEAR(best.axis->point.x, 200, 0.5);
    // The result is the exact mirror of the template across that axis.
    const Affine exact = Affine::reflection(best.axis->point, best.axis->direction);
    EXPECT_LT(
        max_pointwise_distance(sample_path(best.path, 20),
                               sample_path(transformed(canvas.drawing.paths[0].path, exact), 20)),
        1e-6);
}

TEST(SketchRules, ReflectionSnapsToAnAxisUsedBefore) {
    Canvas canvas;
    const std::vector<Vec2> shape = s_curve({40, 0});
    canvas.add_curve(fit_path(shape));
    canvas.drawing.axes.push_back({{201.5, 0}, {0, 1}, 3});
    const Candidate copy =
        matched_copy(canvas, mapped(shape, Affine::reflection({200, 0}, {0, 1})), 10);
    const auto out = run("reflection", copy, canvas.context());
    bool used_existing = false;
    for (const RuleOutput& o : out)
        used_existing |= o.candidate.axis && o.candidate.axis->point.x == 201.5;
    EXPECT_TRUE(used_existing);
}

TEST(SketchRules, ReflectionDoesNotFireOnARotatedCopy) {
    Canvas canvas;
    const std::vector<Vec2> shape = s_curve({40, 0});
    canvas.add_curve(fit_path(shape));
    const Candidate copy =
        matched_copy(canvas, mapped(shape, Affine::rotation(2.0, {300, 300})), 11);
    EXPECT_TRUE(run("reflection", copy, canvas.context()).empty());
}

TEST(SketchRules, TransformSnapsRotationToAQuarterTurn) {
    Canvas canvas;
    const std::vector<Vec2> shape = s_curve({0, 0});
    canvas.add_curve(fit_path(shape));
    const Affine m = Affine::rotation(kPi / 2 + 0.05, {400, 400});  // 92.9°
    const Candidate copy = matched_copy(canvas, mapped(shape, m), 12);
    const auto out = run("transform", copy, canvas.context());
    ASSERT_FALSE(out.empty());
    const SimilarityParts parts = decompose_similarity(out[0].candidate.instance->from_template);
    EXPECT_NEAR(parts.rotation_rad, kPi / 2, 1e-9);
    EXPECT_TRUE(out[0].candidate.fixed.transform);
}

TEST(SketchRules, TransformAlignsATranslatedCopyHorizontally) {
    Canvas canvas;
    const std::vector<Vec2> shape = s_curve({0, 0});
    canvas.add_curve(fit_path(shape));
    const Candidate copy = matched_copy(canvas, mapped(shape, Affine::translation({250, 4})), 13);
    const auto out = run("transform", copy, canvas.context());
    ASSERT_FALSE(out.empty());
    const Affine& m = out[0].candidate.instance->from_template;
    EXPECT_NEAR(m.ty, 0.0, 1e-9);  // same height as the template
    EXPECT_NEAR(decompose_similarity(m).rotation_rad, 0.0, 1e-9);
}

TEST(SketchRules, TransformDoesNotFireWithoutAnythingToSnap) {
    Canvas canvas;
    const std::vector<Vec2> shape = s_curve({0, 0});
    canvas.add_curve(fit_path(shape));
    // 17° and scale 1.37: no nearby fraction of 2π, no nearby 0.5 or integer scale; the centre of
    // rotation (far away) is near no point.
    const Affine m =
        compose(Affine::translation({900, -700}), Affine::similarity(0.3, 1.37, {0, 0}));
    const Candidate copy = matched_copy(canvas, mapped(shape, m), 14);
    EXPECT_TRUE(run("transform", copy, canvas.context()).empty());
}

TEST(SketchRules, StepRepeatsTheStepTransform) {
    Canvas canvas;
    const std::vector<Vec2> shape = s_curve({0, 0});
    canvas.add_curve(fit_path(shape));
    // A copy one step of (130, 0) further, already accepted with that step.
    Candidate first =
        make_candidate(transformed(canvas.drawing.paths[0].path, Affine::translation({130, 0})));
    first.instance =
        Instance{0, Affine::translation({130, 0}), 0, Affine::translation({130, 0}), false};
    canvas.add(first);
    ASSERT_TRUE(canvas.drawing.paths[1].step.has_value());
    const Candidate copy = matched_copy(canvas, mapped(shape, Affine::translation({264, 5})), 15);
    const auto out = run("step", copy, canvas.context());
    ASSERT_FALSE(out.empty());
    const Affine& m = out[0].candidate.instance->from_template;
    EXPECT_NEAR(m.tx, 260.0, 1e-9);
    EXPECT_NEAR(m.ty, 0.0, 1e-9);
}

TEST(SketchRules, StepDoesNotFireOffTheStep) {
    Canvas canvas;
    const std::vector<Vec2> shape = s_curve({0, 0});
    canvas.add_curve(fit_path(shape));
    Candidate first =
        make_candidate(transformed(canvas.drawing.paths[0].path, Affine::translation({130, 0})));
    first.instance =
        Instance{0, Affine::translation({130, 0}), 0, Affine::translation({130, 0}), false};
    canvas.add(first);
    const Candidate copy = matched_copy(canvas, mapped(shape, Affine::translation({190, 90})), 16);
    EXPECT_TRUE(run("step", copy, canvas.context()).empty());
}

TEST(SketchRules, OffsetReplacesAStrokeByAnOffsetOfItsNeighbour) {
    Canvas canvas;
    std::vector<Vec2> wave;
    for (int i = 0; i <= 100; ++i) wave.push_back({3.0 * i, 30 * std::sin(i / 16.0)});
    canvas.add_curve(fit_path(wave));
    // The same wave drawn 15 units to its side (along the normals), with jitter, over a part.
    std::vector<Vec2> side;
    for (int i = 10; i <= 90; ++i) {
        const Vec2 tangent = normalized(Vec2{3.0, 30 * std::cos(i / 16.0) / 16.0});
        side.push_back(Vec2{3.0 * i, 30 * std::sin(i / 16.0)} + perpendicular(tangent) * 15.0);
    }
    const auto out = run("offset", make_candidate(wobbly(side, 1.0, 17)), canvas.context());
    ASSERT_FALSE(out.empty());
    const std::vector<Vec2> reference = canvas.drawing.paths[0].dense;
    for (Vec2 p : sample_path(out[0].candidate.path, 40)) {
        EXPECT_NEAR(closest_point(reference, p).distance, 15.0, 0.8);
    }
}

TEST(SketchRules, OffsetDoesNotFireOnACrossingStroke) {
    Canvas canvas;
    std::vector<Vec2> wave;
    for (int i = 0; i <= 100; ++i) wave.push_back({3.0 * i, 30 * std::sin(i / 16.0)});
    canvas.add_curve(fit_path(wave));
    // A gently curved stroke that crosses the wave diagonally: the distance varies.
    std::vector<Vec2> crossing;
    for (int i = 0; i <= 40; ++i) crossing.push_back({50.0 + 5 * i, -60.0 + 3 * i + 0.02 * i * i});
    EXPECT_TRUE(run("offset", make_candidate(fit_path(crossing)), canvas.context()).empty());
}

}  // namespace
}  // namespace exemplar::sketch
