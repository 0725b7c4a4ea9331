// SVG import/export: every path command, shapes, transforms, errors, round trip.

#include "exemplar/sketch/svg.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace exemplar::sketch {
namespace {

Drawing parse_ok(const std::string& body,
                 const std::string& root = "<svg xmlns=\"http://www.w3.org/2000/svg\">") {
    auto d = parse_svg(root + body + "</svg>", "test.svg");
    EXPECT_TRUE(d.ok()) << d.status().message();
    return d.ok() ? *d : Drawing{};
}

void expect_near(Vec2 a, Vec2 b, double tol = 1e-9) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
}

TEST(SketchSvg, StrokeWidthsFromAttributesStylesAncestorsAndTransforms) {
    const Drawing d = parse_ok(
        R"svg(<path d="M0 0 L1 1"/>)svg"
        R"svg(<g stroke-width="4"><path d="M0 0 L1 1"/><path style="fill:none;stroke-width:6px" d="M0 0 L1 1"/></g>)svg"
        R"svg(<g transform="scale(3)"><line stroke-width="2" x1="0" y1="0" x2="1" y2="0"/></g>)svg");
    ASSERT_EQ(d.stroke_widths.size(), 4u);
    EXPECT_DOUBLE_EQ(d.stroke_widths[0], 1.0);  // SVG's default
    EXPECT_DOUBLE_EQ(d.stroke_widths[1], 4.0);  // inherited from the group
    EXPECT_DOUBLE_EQ(d.stroke_widths[2], 6.0);  // the style property wins
    EXPECT_DOUBLE_EQ(d.stroke_widths[3], 6.0);  // 2 user units scaled by 3
}

TEST(SketchSvg, StrokePaintsFromAttributesStylesAndAncestors) {
    const Drawing d = parse_ok(
        R"svg(<path d="M0 0 L1 1"/>)svg"
        R"svg(<g stroke="#ff0000"><path d="M0 0 L1 1"/><path style="stroke-width:2; stroke : blue" d="M0 0 L1 1"/></g>)svg");
    ASSERT_EQ(d.strokes.size(), 3u);
    EXPECT_EQ(d.strokes[0], "none");     // none given: SVG's default
    EXPECT_EQ(d.strokes[1], "#ff0000");  // inherited from the group
    EXPECT_EQ(d.strokes[2], "#0000ff");  // the style property wins, not confused with stroke-width
    EXPECT_DOUBLE_EQ(d.stroke_widths[2], 2.0);
}

TEST(SketchSvg, StrokeAndFillColoursClassesAndElements) {
    const Drawing d = parse_ok(
        R"svg(<path d="M0 0 L1 1"/>)svg"
        R"svg(<g fill="none" stroke="Black" class="g"><path class="a b" d="M0 0 L1 1 M2 2 L3 3"/>)svg"
        R"svg(<rect style="fill: rgb(255, 0, 0); stroke:#0F0" width="2" height="2"/></g>)svg"
        R"svg(<circle fill="transparent" stroke="url(#g)" fill-rule="evenodd" r="1"/>)svg");
    ASSERT_EQ(d.paths.size(), 5u);
    EXPECT_EQ(d.strokes,
              (std::vector<std::string>{"none", "#000000", "#000000", "#00ff00", "url(#g)"}));
    EXPECT_EQ(d.fills, (std::vector<std::string>{"#000000", "none", "none", "#ff0000", "none"}));
    EXPECT_EQ(d.classes[1], "g a b");  // the group's class, then the path's
    EXPECT_EQ(d.classes[4], "");
    EXPECT_EQ(d.elements, (std::vector<int>{0, 1, 1, 2, 3}));  // two subpaths, one element
    EXPECT_EQ(d.element_count, 4);
    EXPECT_EQ(d.even_odd[4], 1);
    EXPECT_EQ(d.even_odd[0], 0);
    EXPECT_EQ(normalize_colour(" #AbC "), "#aabbcc");
    EXPECT_EQ(normalize_colour("grey"), "#808080");
}

TEST(SketchSvg, AbsoluteAndRelativeCommands) {
    const Drawing d = parse_ok(
        R"svg(<path id="p" d="M10 10 L20 10 h5 v5 H40 V0 l-5-5 c1 1 2 2 3 3 S10 10 12 12 Q20 20 30 20 t10 0 Z"/>)svg");
    ASSERT_EQ(d.paths.size(), 1u);
    const Path& p = d.paths[0];
    EXPECT_TRUE(p.closed);
    expect_near(p.start(), {10, 10});
    expect_near(p.segments[0].p3, {20, 10});
    expect_near(p.segments[1].p3, {25, 10});
    expect_near(p.segments[2].p3, {25, 15});
    expect_near(p.segments[3].p3, {40, 15});
    expect_near(p.segments[4].p3, {40, 0});
    expect_near(p.segments[5].p3, {35, -5});
    expect_near(p.segments[6].p3, {38, -2});
    // S reflects the previous control point (37, -3) about (38, -2).
    expect_near(p.segments[7].c1, {39, -1});
    expect_near(p.segments[7].p3, {12, 12});
    // Q as a cubic: controls at 2/3 towards the quadratic control.
    expect_near(p.segments[8].c1, Vec2{12, 12} + (Vec2{20, 20} - Vec2{12, 12}) * (2.0 / 3.0));
    // T reflects (20, 20) about (30, 20) to (40, 20).
    expect_near(p.segments[9].c1, Vec2{30, 20} + (Vec2{40, 20} - Vec2{30, 20}) * (2.0 / 3.0));
    expect_near(p.end(), {10, 10});
    EXPECT_EQ(d.ids[0], "p");
}

TEST(SketchSvg, ArcsBecomeCubicsOnTheEllipse) {
    // Half circle of radius 10 from (0,0) to (20,0); sweep flag 1 turns through (10, -10).
    const Drawing d = parse_ok(R"svg(<path d="M0 0 A10 10 0 0 1 20 0"/>)svg");
    ASSERT_EQ(d.paths.size(), 1u);
    for (Vec2 q : flatten(d.paths[0], 0.5)) EXPECT_NEAR(distance(q, {10, 0}), 10.0, 0.01);
    expect_near(d.paths[0].end(), {20, 0});
    EXPECT_NEAR(sample_path(d.paths[0], 3)[1].y, -10.0, 0.05);
    // Flags written without separators ("a10 10 0 0110 0").
    const Drawing e = parse_ok(R"svg(<path d="M0 0a10 10 0 0110 0"/>)svg");
    ASSERT_EQ(e.paths.size(), 1u);
    expect_near(e.paths[0].end(), {10, 0});
}

TEST(SketchSvg, ShapesAndTransforms) {
    const Drawing d = parse_ok(R"svg(
      <g transform="translate(100,0) scale(2)">
        <line x1="0" y1="0" x2="10" y2="0"/>
        <g transform="rotate(90)"><polyline points="0,0 10,0 10,10"/></g>
      </g>
      <polygon points="0 0 4 0 4 4"/>
      <circle cx="5" cy="5" r="3"/>
      <ellipse cx="0" cy="0" rx="4" ry="2"/>
      <rect x="1" y="2" width="10" height="5"/>
      <rect x="0" y="0" width="10" height="10" rx="2"/>
      <defs><path d="M0 0 L1 1"/></defs>
      <path d="M0 0 L1 0 M5 5 L6 6"/>)svg");
    ASSERT_EQ(d.paths.size(), 9u);
    expect_near(d.paths[0].start(), {100, 0});
    expect_near(d.paths[0].end(), {120, 0});
    // rotate(90) maps (10, 0) to (0, 10), then scale 2 and translate.
    expect_near(d.paths[1].segments[0].p3, {100, 20});
    EXPECT_TRUE(d.paths[2].closed);
    EXPECT_EQ(d.paths[2].segments.size(), 3u);
    EXPECT_TRUE(d.paths[3].closed);
    EXPECT_NEAR(arc_length(d.paths[3]), 2 * std::numbers::pi * 3, 0.01);
    for (Vec2 q : flatten(d.paths[4], 0.5)) EXPECT_NEAR(q.x * q.x / 16 + q.y * q.y / 4, 1.0, 0.01);
    EXPECT_NEAR(arc_length(d.paths[5]), 30.0, 1e-9);
    EXPECT_NEAR(arc_length(d.paths[6]), 40 - 16 + 2 * std::numbers::pi * 2, 0.02);
    // Two subpaths of one element: two strokes, ids suffixed.
    EXPECT_EQ(d.ids[8], "#1");
}

TEST(SketchSvg, ErrorsNameTheProblem) {
    auto bad_xml = parse_svg("<svg><path d=", "x.svg");
    ASSERT_FALSE(bad_xml.ok());
    EXPECT_NE(bad_xml.status().message().find("x.svg: not valid XML"), std::string::npos);
    auto not_svg = parse_svg("<html/>", "x.svg");
    ASSERT_FALSE(not_svg.ok());
    EXPECT_NE(not_svg.status().message().find("not an SVG"), std::string::npos);
    auto bad_path = parse_svg("<svg><path id=\"q\" d=\"M0 0 L1\"/></svg>", "x.svg");
    ASSERT_FALSE(bad_path.ok());
    EXPECT_NE(bad_path.status().message().find("id=\"q\""), std::string::npos);
    auto bad_transform = parse_svg("<svg><g transform=\"wobble(3)\"/></svg>", "x.svg");
    ASSERT_FALSE(bad_transform.ok());
    EXPECT_NE(bad_transform.status().message().find("wobble"), std::string::npos);
    auto missing = load_svg("/nonexistent/folder/x.svg");
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.status().code(), ErrorCode::IoError);
}

TEST(SketchSvg, WriteThenReadRoundTrips) {
    Drawing canvas;
    canvas.view_width = canvas.view_height = 100;
    SvgLayer layer;
    layer.paths = {arc_path({50, 50}, 20, 0.3, 2.0), polyline_path({{1, 2}, {3.25, 4.5}})};
    layer.ids = {"a", "b"};
    const std::string text = to_svg(canvas, {layer});
    auto back = parse_svg(text, "round.svg");
    ASSERT_TRUE(back.ok()) << back.status().message();
    ASSERT_EQ(back->paths.size(), 2u);
    EXPECT_EQ(back->ids[1], "b");
    EXPECT_EQ(back->view_width, 100);
    EXPECT_LT(
        max_pointwise_distance(sample_path(back->paths[0], 20), sample_path(layer.paths[0], 20)),
        1e-3);
}

TEST(SketchSvg, ViewBoxAndPixelScale) {
    const Drawing d = parse_ok("", R"svg(<svg viewBox="0 0 400 200" width="800" height="400">)svg");
    EXPECT_EQ(d.view_width, 400);
    EXPECT_DOUBLE_EQ(d.pixels_per_unit, 2.0);
}

}  // namespace
}  // namespace exemplar::sketch
