// `exemplar brush` runs in-process: the painted layer, SVG paths, the canvas, and one-line
// errors naming the file and the problem with no output written.

#include <cmath>
#include <fstream>

#include "cli_fixture.hpp"

namespace exemplar::cli::testing {
namespace {

// A palette with a dark wavy band along y = 24 (grain on a light ground), 120 × 48.
Image band_palette() {
    Image im = texture(120, 48, 3, 3);
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 120; ++x) {
            const float half = 4.0f + 2.0f * std::sin(0.21f * static_cast<float>(x));
            const float inside =
                std::clamp(half - std::abs(static_cast<float>(y) + 0.5f - 24.0f), 0.0f, 1.0f);
            for (int c = 0; c < 3; ++c)
                im.at(x, y, c) = 0.8f + 0.1f * (im.at(x, y, c) - 0.5f) - 0.6f * inside;
        }
    }
    return im;
}

TEST_F(Cli, BrushPaintsJsonAndSvgPaths) {
    write("palette.png", band_palette());
    std::ofstream(path("feature.json"))
        << R"([{"points": [[6, 26], [60, 22], [114, 25]], "width": 24}])";
    std::ofstream(path("path.json"))
        << R"([{"points": [[10, 30], [150, 50], [190, 20]], "width": 24}])";
    const CliRun r = run({"brush", "--palette", path("palette.png"), "--feature",
                          path("feature.json"), "--path", path("path.json"), "--width", "200",
                          "--height", "64", "-o", path("out/brushed.png"), "--threads", "2"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("out/brushed.png") + "\n");
    const Image out = read("out/brushed.png");
    ASSERT_EQ(out.channels(), 4);
    EXPECT_EQ(out.width(), 200);
    EXPECT_EQ(out.at(2, 60, 3), 0.0f);  // off the path: transparent
    // Across the path at x = 80 the band's dark core shows between lighter ground.
    float darkest = 1.0f, alpha = 0.0f;
    for (int y = 25; y < 55; ++y) {
        if (out.at(80, y, 3) > 0.99f) darkest = std::min(darkest, out.at(80, y, 0));
        alpha = std::max(alpha, out.at(80, y, 3));
    }
    EXPECT_EQ(alpha, 1.0f);
    EXPECT_LT(darkest, 0.45f);

    // SVG path with a --brush-width override, over a canvas, the looping walk, no snapping.
    std::ofstream(path("path.svg"))
        << R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 32" width="100" height="32">)"
        << R"(<path d="M 5 16 C 30 0 70 32 95 16" stroke-width="2"/></svg>)";
    Image red(200, 64, 3);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 200; ++x) red.at(x, y, 0) = 1.0f;
    write("bg.png", red);
    const CliRun svg =
        run({"brush", "--palette", path("palette.png"), "--feature", path("feature.json"), "--path",
             path("path.svg"), "--canvas", path("bg.png"), "--brush-width", "20", "--walk",
             "looping", "--no-snap", "-o", path("svg.png"), "-q"});
    ASSERT_EQ(svg.code, 0) << svg.err;
    EXPECT_TRUE(svg.out.empty());
    const Image over = read("svg.png");
    EXPECT_EQ(over.at(2, 2, 3), 1.0f);
    EXPECT_EQ(over.at(2, 2, 1), 0.0f);
    EXPECT_GT(over.at(100, 32, 1), 0.1f);  // painted (grey) in the middle

    // The feature as SVG, in palette pixels (the palette's size is its canvas).
    std::ofstream(path("feature.svg"))
        << R"(<svg xmlns="http://www.w3.org/2000/svg" width="120" height="48">)"
        << R"(<path d="M 6 26 L 114 25" stroke-width="24"/></svg>)";
    const CliRun from_svg =
        run({"brush", "--palette", path("palette.png"), "--feature", path("feature.svg"), "--path",
             path("path.json"), "--width", "200", "--height", "64", "-o", path("from_svg.png")});
    ASSERT_EQ(from_svg.code, 0) << from_svg.err;
    EXPECT_EQ(read("from_svg.png").at(80, 40, 3), 1.0f);
}

// examples/feature (its README): the bundled palette, feature and paths give the picture
// committed there, wherever the strokes are opaque (the picture has a paper colour under them;
// an alpha of 0.999 reads back as 1 from the 8-bit PNG, hence one grey level of tolerance).
TEST_F(Cli, BrushBundledExampleGivesItsPicture) {
    const std::string dir = std::string(EXEMPLAR_SOURCE_DIR) + "/examples/feature/";
    const CliRun r = run({"brush", "--palette", dir + "scream_railing.png", "--feature",
                          dir + "railing.json", "--path", dir + "waves.json", "--width", "800",
                          "--height", "260", "-o", path("waves.png"), "-q", "--threads", "2"});
    ASSERT_EQ(r.code, 0) << r.err;
    const Image out = read("waves.png");
    const Result<Image> picture = load_image(dir + "waves.png");
    ASSERT_TRUE(picture.ok()) << picture.status().message();
    ASSERT_TRUE(out.same_size(*picture));
    int opaque = 0;
    for (int y = 0; y < out.height(); ++y) {
        for (int x = 0; x < out.width(); ++x) {
            if (out.at(x, y, 3) < 1.0f) continue;
            ++opaque;
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(out.at(x, y, c), picture->at(x, y, c), 1.5f / 255.0f) << x << ", " << y;
        }
    }
    EXPECT_GT(opaque, 20000);
}

TEST_F(Cli, BrushRejectsBadInputs) {
    write("palette.png", band_palette());
    const std::string pal = path("palette.png"), feat = path("f.json"), p = path("p.json");
    std::ofstream(feat) << R"([{"points": [[6, 24], [114, 24]], "width": 20}])";
    std::ofstream(p) << R"([{"points": [[10, 10], [90, 10]]}])";
    auto args = [&](const std::string& feature, const std::string& target) {
        return std::vector<std::string>{"brush", "--palette", pal,   "--feature", feature, "--path",
                                        target,  "--width",   "100", "--height",  "40"};
    };
    std::ofstream(path("one.json")) << R"([{"points": [[6, 24]], "width": 20}])";
    expect_failure(args(path("one.json"), p), 1, "one.json: has 1 point(s) (needs at least 2)");
    std::ofstream(path("out.json")) << R"([{"points": [[6, 24], [300, 24]], "width": 20}])";
    expect_failure(args(path("out.json"), p), 1,
                   "out.json: point (300, 24) lies outside the palette (120x48)");
    std::ofstream(path("short.json")) << R"([{"points": [[6, 24], [7, 24]], "width": 20}])";
    expect_failure(args(path("short.json"), p), 1, "short.json");
    std::ofstream(path("two.json"))
        << R"([{"points": [[6, 24], [60, 24]]}, {"points": [[6, 24], [60, 24]]}])";
    expect_failure(args(path("two.json"), p), 1, "two.json: holds 2 strokes");
    std::ofstream(path("broken.json")) << "[{";
    expect_failure(args(feat, path("broken.json")), 1, "broken.json: not valid JSON");
    std::ofstream(path("broken.svg")) << "<svg><path d=\"M 1 1 L\"";
    expect_failure(args(feat, path("broken.svg")), 1, "broken.svg");
    std::ofstream(path("empty.svg")) << R"(<svg xmlns="http://www.w3.org/2000/svg"></svg>)";
    expect_failure(args(feat, path("empty.svg")), 1, "empty.svg: holds no path");
    expect_failure(args(feat, path("p.txt")), 1, "p.txt: must be a .json or .svg file");
    std::vector<std::string> bad_walk = args(feat, p);
    bad_walk.insert(bad_walk.end(), {"--walk", "zigzag"});
    expect_failure(bad_walk, 1, "--walk: 'zigzag' is invalid");
    std::vector<std::string> bad_spacing = args(feat, p);
    bad_spacing.insert(bad_spacing.end(), {"--sample-spacing", "0"});
    expect_failure(bad_spacing, 1, "--sample-spacing: 0 is invalid (must be 0.5..64)");
    expect_failure({"brush", "--palette", pal, "--feature", feat, "--path", p}, 1,
                   "--width/--height");
}

}  // namespace
}  // namespace exemplar::cli::testing
