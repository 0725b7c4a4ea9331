// Vector image stylization of Painting by Feature (thesis §3.4): stroked paths take the line
// feature assigned to their colour or class, filled shapes the area feature assigned to their
// fill, the background fills the canvas; a TU-Berlin sketch (tests/data, CC BY 4.0) is painted
// along its strokes; bad drawings and palettes are rejected with one line. Synthetic palettes.

#include "exemplar/paint/vectorize_style.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "exemplar/core/rng.hpp"

namespace exemplar::paint {
namespace {

// In [0, 1), a pure function of the pixel (the core's counter-based hash).
float noise(int x, int y) {
    return static_cast<float>(
               hash_keys(static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y)) >> 40) /
           static_cast<float>(1ull << 24);
}

// 160 x 100: a red band (rows 0-39), a blue band (40-69), then green (left) and yellow (right)
// grain (70-99); each with noise so the synthesis has texture to match.
Image palette_image() {
    Image im(160, 100, 3);
    for (int y = 0; y < 100; ++y) {
        for (int x = 0; x < 160; ++x) {
            const float g = 0.1f * (noise(x, y) - 0.5f);
            float rgb[3];
            if (y < 40) {
                rgb[0] = 0.85f, rgb[1] = 0.1f, rgb[2] = 0.1f;
            } else if (y < 70) {
                rgb[0] = 0.1f, rgb[1] = 0.15f, rgb[2] = 0.85f;
            } else if (x < 80) {
                rgb[0] = 0.1f, rgb[1] = 0.8f, rgb[2] = 0.15f;
            } else {
                rgb[0] = 0.9f, rgb[1] = 0.85f, rgb[2] = 0.1f;
            }
            for (int c = 0; c < 3; ++c) im.at(x, y, c) = rgb[c] + g;
        }
    }
    return im;
}

Image rectangle(int w, int h, int x0, int y0, int x1, int y1) {
    Image im(w, h, 1);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) im.at(x, y, 0) = 1.0f;
    return im;
}

StylePalette style(const std::string& background = "") {
    StylePalette p;
    p.palette = palette_image();
    p.line_features.push_back({"red", Stroke{{{10, 20}, {150, 20}}, 16.0f, false}, false, 0.0f});
    p.line_features.push_back({"blue", Stroke{{{10, 55}, {150, 55}}, 16.0f, false}, false, 0.0f});
    p.area_features.push_back({"green", rectangle(160, 100, 2, 72, 78, 98)});
    p.area_features.push_back({"yellow", rectangle(160, 100, 82, 72, 158, 98)});
    p.strokes = {{"#000000", "red"}, {".sea", "blue"}};
    p.fills = {{"#00ff00", "green"}};
    p.background = background;
    return p;
}

// A filled rectangle without stroke, a black path and a black path of class "sea".
const char* kDrawing = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 120 90">
  <g fill="none" stroke-width="8">
    <rect x="30" y="30" width="60" height="30" style="fill: #0f0; stroke: none"/>
    <path d="M10 10 L110 10" stroke="black"/>
    <path class="ink sea" d="M10 80 C40 75 80 85 110 80" stroke="#000"/>
  </g>
</svg>)";

sketch::Drawing drawing(const char* text = kDrawing) {
    auto d = sketch::parse_svg(text);
    EXPECT_TRUE(d.ok()) << d.status().message();
    return d.ok() ? std::move(d).value() : sketch::Drawing{};
}

VectorizeStyleOptions quick() {
    VectorizeStyleOptions o;
    o.fill.rotations = 1;
    return o;
}

TEST(VectorizeStyle, PaintsStrokesAndShapesWithTheirFeatures) {
    auto out = vectorize_style(drawing(), style(), 120, 90, quick(), RunContext(2));
    ASSERT_TRUE(out.ok()) << out.status().message();
    ASSERT_EQ(out->channels(), 4);
    ASSERT_EQ(out->width(), 120);
    // Mean colour of a box; and its least alpha.
    auto mean = [&](int x0, int y0, int x1, int y1, int c) {
        double s = 0.0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) s += out->at(x, y, c);
        return s / ((x1 - x0) * (y1 - y0));
    };
    // The black path: red; the class "sea" wins over its colour: blue; the shape: green.
    EXPECT_GT(mean(20, 8, 100, 12, 0), 0.7);
    EXPECT_LT(mean(20, 8, 100, 12, 2), 0.25);
    EXPECT_GT(mean(20, 79, 100, 81, 2), 0.7);
    EXPECT_LT(mean(20, 79, 100, 81, 0), 0.25);
    EXPECT_GT(mean(35, 35, 85, 55, 1), 0.7);
    EXPECT_LT(mean(35, 35, 85, 55, 2), 0.25);
    EXPECT_DOUBLE_EQ(mean(35, 35, 85, 55, 3), 1.0);
    // Nothing else is painted: no background.
    EXPECT_EQ(mean(0, 20, 25, 70, 3), 0.0);
    EXPECT_EQ(mean(95, 20, 120, 70, 3), 0.0);
}

TEST(VectorizeStyle, BackgroundFillsTheCanvasAndShapesGoOverIt) {
    auto out = vectorize_style(drawing(), style("yellow"), 120, 90, quick(), RunContext(2));
    ASSERT_TRUE(out.ok()) << out.status().message();
    double yellow = 0.0, alpha = 1.0;
    for (int y = 0; y < 90; ++y) {
        for (int x = 0; x < 120; ++x) alpha = std::min(alpha, double(out->at(x, y, 3)));
    }
    for (int y = 20; y < 70; ++y) {
        for (int x = 0; x < 20; ++x) yellow += out->at(x, y, 1) - out->at(x, y, 2);
    }
    EXPECT_EQ(alpha, 1.0);
    EXPECT_GT(yellow / (20 * 50), 0.6);                       // green minus blue: yellow
    EXPECT_GT(out->at(60, 45, 1) - out->at(60, 45, 0), 0.4);  // the shape stays green
}

TEST(VectorizeStyle, SameBytesForAnyThreadCount) {
    auto one = vectorize_style(drawing(), style("yellow"), 120, 90, quick(), RunContext(1));
    auto two = vectorize_style(drawing(), style("yellow"), 120, 90, quick(), RunContext(2));
    ASSERT_TRUE(one.ok() && two.ok());
    EXPECT_EQ(std::memcmp(one->data().data(), two->data().data(), one->size() * sizeof(float)), 0);
}

// The TU-Berlin airplane: every stroke is painted (opaque along its centre line), nothing else.
TEST(VectorizeStyle, TuBerlinSketchIsPaintedAlongItsStrokes) {
    const std::string file =
        std::string(EXEMPLAR_TEST_DATA_DIR) + "/strokes/tu-berlin/airplane/2.svg";
    auto d = sketch::load_svg(file);
    ASSERT_TRUE(d.ok()) << d.status().message();
    StylePalette p = style();
    p.strokes = {{"default", "red"}};
    p.line_features[0].brush_width_px = 6.0f;
    const auto [w, h] = drawing_canvas_size(*d, 400);
    EXPECT_EQ(w, 400);
    EXPECT_EQ(h, 400);
    auto out = vectorize_style(*d, p, w, h, quick(), RunContext(2));
    ASSERT_TRUE(out.ok()) << out.status().message();
    const std::vector<Stroke> strokes = drawing_strokes(*d, w, h);
    int on = 0, opaque = 0;
    for (const Stroke& s : strokes) {
        for (std::size_t k = 1; k + 1 < s.points.size(); ++k) {
            const int x = static_cast<int>(s.points[k].x), y = static_cast<int>(s.points[k].y);
            ++on;
            opaque += out->at(x, y, 3) > 0.5f && out->at(x, y, 0) > 0.5f ? 1 : 0;
        }
    }
    EXPECT_GT(on, 1000);
    EXPECT_GT(opaque, on * 95 / 100);
    int painted = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) painted += out->at(x, y, 3) > 0.0f ? 1 : 0;
    EXPECT_LT(painted, w * h / 5);  // strokes of 6 px, not the canvas
}

TEST(VectorizeStyle, RejectsBadDrawingsAndPalettes) {
    const auto message = [](const Result<Image>& r) {
        return r.ok() ? std::string("ok") : r.status().message();
    };
    // A drawing without paths.
    EXPECT_EQ(
        message(vectorize_style(drawing(R"(<svg xmlns="http://www.w3.org/2000/svg"><g/></svg>)"),
                                style(), 50, 50)),
        "drawing: holds no path");
    // A stroke colour nothing is assigned to.
    StylePalette p = style();
    p.strokes = {{".sea", "blue"}};
    EXPECT_EQ(message(vectorize_style(drawing(), p, 120, 90, quick())),
              "drawing: path 1 (stroke #000000): no line feature is assigned (strokes has no key "
              "for it and no \"default\")");
    // Unknown feature names.
    p = style();
    p.strokes.push_back({"default", "rail"});
    EXPECT_EQ(validate(p).message(),
              "strokes: \"default\" names line feature \"rail\", which is not defined (defined: "
              "red, blue)");
    p = style("sky");
    EXPECT_EQ(message(vectorize_style(drawing(), p, 120, 90)),
              "background: names area feature \"sky\", which is not defined (defined: green, "
              "yellow)");
    // A line feature's path outside the palette, and one too short for two samples.
    p = style();
    p.line_features[0].selection.points = {{10, 20}, {300, 20}};
    EXPECT_EQ(message(vectorize_style(drawing(), p, 120, 90, quick())),
              "line feature \"red\": feature: point (300, 20) lies outside the palette (160x100)");
    p.line_features[0].selection.points = {{10, 20}, {11, 20}};
    EXPECT_EQ(message(vectorize_style(drawing(), p, 120, 90, quick())),
              "line feature \"red\": feature: gives 1 sample(s) (needs at least 2: the path is "
              "shorter than the sample spacing)");
}

TEST(PolygonMask, NonzeroKeepsOppositelyWoundHolesAndEvenOddAnyHole) {
    const std::vector<std::vector<StrokePoint>> square_with_hole = {
        {{2, 2}, {18, 2}, {18, 18}, {2, 18}},   // clockwise on screen
        {{6, 6}, {6, 14}, {14, 14}, {14, 6}}};  // the other way
    const Image nonzero = polygon_mask(square_with_hole, 20, 20);
    EXPECT_EQ(nonzero.at(3, 3, 0), 1.0f);
    EXPECT_EQ(nonzero.at(10, 10, 0), 0.0f);
    EXPECT_EQ(nonzero.at(19, 10, 0), 0.0f);
    int inside = 0;
    for (float v : nonzero.data()) inside += v > 0.5f ? 1 : 0;
    EXPECT_EQ(inside, 16 * 16 - 8 * 8);
    const std::vector<std::vector<StrokePoint>> same_way = {{{2, 2}, {18, 2}, {18, 18}, {2, 18}},
                                                            {{6, 6}, {14, 6}, {14, 14}, {6, 14}}};
    EXPECT_EQ(polygon_mask(same_way, 20, 20).at(10, 10, 0), 1.0f);
    EXPECT_EQ(polygon_mask(same_way, 20, 20, /*even_odd=*/true).at(10, 10, 0), 0.0f);
}

TEST(StylePaletteFile, ReadsFeaturesAssignmentsAndRelativeImages) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "exemplar_style_palette_test";
    fs::remove_all(dir);
    fs::create_directories(dir / "img");
    // A 4x4 palette written as PGM (no image library needed to write it).
    {
        std::ofstream pgm(dir / "img" / "p.pgm", std::ios::binary);
        pgm << "P5 4 4 255\n";
        for (int i = 0; i < 16; ++i) pgm.put(static_cast<char>(i * 16));
    }
    {
        std::ofstream json(dir / "style.json");
        json << R"({"palette": "img/p.pgm",
            "line_features": {"ink": {"path": [[0, 1], [3, 1]], "width": 2, "brush_width": 5,
                                      "snap": false}},
            "area_features": {"paper": {"polygon": [[0, 0], [4, 0], [4, 4], [0, 4]]}},
            "strokes": {"Black": "ink", ".hair": "ink"}, "fills": {"default": "paper"},
            "background": "paper"})";
    }
    auto p = load_style_palette((dir / "style.json").string());
    ASSERT_TRUE(p.ok()) << p.status().message();
    EXPECT_EQ(p->palette.width(), 4);
    ASSERT_EQ(p->line_features.size(), 1u);
    EXPECT_EQ(p->line_features[0].brush_width_px, 5.0f);
    EXPECT_FALSE(p->line_features[0].snap);
    EXPECT_EQ(p->line_features[0].selection.width_px, 2.0f);
    ASSERT_EQ(p->area_features.size(), 1u);
    EXPECT_EQ(p->area_features[0].region.at(3, 3, 0), 1.0f);
    ASSERT_EQ(p->strokes.size(), 2u);
    // Colours are normalized, classes kept (JSON objects are read in key order).
    EXPECT_EQ(p->strokes[0].first, ".hair");
    EXPECT_EQ(p->strokes[1].first, "#000000");
    EXPECT_EQ(p->background, "paper");

    const auto fails = [&](const std::string& text) {
        std::ofstream(dir / "bad.json") << text;
        auto r = load_style_palette((dir / "bad.json").string());
        return r.ok() ? std::string("ok") : r.status().message();
    };
    const std::string bad = (dir / "bad.json").string() + ": ";
    EXPECT_EQ(fails("{\"palette\": "), bad + "not valid JSON");
    EXPECT_EQ(fails(R"({"palette": "img/p.pgm", "colours": {}})"),
              bad +
                  "unknown key 'colours' (known: palette, line_features, area_features, strokes, "
                  "fills, background)");
    EXPECT_EQ(fails(R"({"palette": "img/p.pgm", "fills": {"#fff": "sky"}})"),
              bad +
                  "fills: \"#ffffff\" names area feature \"sky\", which is not defined "
                  "(defined: none)");
    EXPECT_NE(fails(R"({"palette": "missing.png"})").find(bad + "palette: "), std::string::npos);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace exemplar::paint
