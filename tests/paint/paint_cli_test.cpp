// `exemplar directions` and `exemplar paint` run in-process: files written, their channels, and
// one-line errors naming the file or parameter.

#include <cmath>
#include <fstream>

#include "cli_fixture.hpp"

namespace exemplar::cli::testing {
namespace {

// An RGBA exemplar: diagonal stripes with grain inside a disc, transparent outside.
Image blob(int size) {
    Image im = texture(size, size, 4, 5);
    const float c = 0.5f * static_cast<float>(size - 1);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float r = std::hypot(static_cast<float>(x) - c, static_cast<float>(y) - c);
            im.at(x, y, 0) = 0.5f + 0.4f * std::sin(0.6f * static_cast<float>(x + y));
            im.at(x, y, 3) = std::clamp((0.45f * size - r) / 2.0f, 0.0f, 1.0f);
        }
    }
    return im;
}

TEST_F(Cli, DirectionsWritesAnAngleFieldAndAPreview) {
    write("blob.png", blob(40));
    const CliRun r = run({"directions", path("blob.png"), "-o", path("d/field.exr"), "--radius",
                          "4", "--preview", path("d/field.png"), "--threads", "2"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("d/field.exr") + "\n" + path("d/field.png") + "\n");
    const Image field = read("d/field.exr");
    ASSERT_EQ(field.channels(), 1);
    EXPECT_EQ(field.channel_names()[0], "angle");
    EXPECT_EQ(field.width(), 40);
    // Stripes along the anti-diagonal (x + y = const): the direction is ±(1, -1)/√2, ±45°.
    EXPECT_NEAR(std::abs(std::sin(2.0f * field.at(20, 20, 0))), 1.0f, 0.05f);
    EXPECT_EQ(read("d/field.png").channels(), 3);
}

TEST_F(Cli, DirectionsRejectsBadInputs) {
    write("blob.png", blob(24));
    const std::string in = path("blob.png");
    expect_failure_as_is({"directions", in, "-o", path("f.exr"), "--radius", "0"}, 1, "--radius");
    expect_failure_as_is({"directions", in, "-o", path("f.png")}, 1, "must be an .exr file");
    expect_failure_as_is({"directions", path("none.png"), "-o", path("f.exr")}, 1, "none.png");
    expect_failure_as_is({"directions", in}, 2, "--output");
}

TEST_F(Cli, PaintFromJsonStrokesWritesRgba) {
    write("blob.png", blob(40));
    std::ofstream(path("strokes.json"))
        << R"([{"points": [[6, 30], [40, 20], [70, 34]], "width": 18},
               {"points": [[40, 10], [40, 50]], "width": 10, "comb": true}])";
    const CliRun r = run({"paint", "--source", path("blob.png"), "--strokes", path("strokes.json"),
                          "--width", "80", "--height", "48", "-o", path("out/painted.png"),
                          "--save-directions", path("out/dirs.png"), "--threads", "2"});
    ASSERT_EQ(r.code, 0) << r.err;
    const Image out = read("out/painted.png");
    ASSERT_EQ(out.channels(), 4);
    EXPECT_EQ(out.width(), 80);
    EXPECT_EQ(out.at(2, 2, 3), 0.0f);    // unpainted: transparent
    EXPECT_GT(out.at(40, 22, 3), 0.9f);  // on the stroke: opaque texture
    EXPECT_EQ(read("out/dirs.png").channels(), 3);
    // Over a background: opaque everywhere, the background where nothing was painted.
    write("bg.png", Image(80, 48, 3, 0.25f));
    const CliRun over =
        run({"paint", "--source", path("blob.png"), "--strokes", path("strokes.json"), "--canvas",
             path("bg.png"), "-o", path("over.png"), "--threads", "1"});
    ASSERT_EQ(over.code, 0) << over.err;
    const Image composed = read("over.png");
    EXPECT_EQ(composed.at(2, 2, 3), 1.0f);
    EXPECT_NEAR(composed.at(2, 2, 0), 0.25f, 0.01f);
}

TEST_F(Cli, PaintFromSvgUsesStrokeWidths) {
    write("blob.png", blob(40));
    std::ofstream(path("strokes.svg"))
        << R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 40 24" width="40" height="24">)"
        << R"(<g stroke-width="4"><path d="M 3 12 L 37 12"/></g></svg>)";
    // The viewBox is scaled onto an 80x48 canvas: the stroke is 8 px wide around y = 24.
    const CliRun r = run({"paint", "--source", path("blob.png"), "--strokes", path("strokes.svg"),
                          "--width", "80", "--height", "48", "-o", path("svg.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const Image out = read("svg.png");
    EXPECT_GT(out.at(40, 24, 3), 0.5f);
    EXPECT_EQ(out.at(40, 30, 3), 0.0f);  // 6.5 px from the centre line: outside the 4 px radius
}

TEST_F(Cli, PaintRejectsBadInputs) {
    write("blob.png", blob(24));
    const std::string src = path("blob.png"), js = path("s.json");
    std::ofstream(js) << R"([{"points": [[2, 2], [20, 20]], "width": 8}])";
    auto args = [&](std::vector<std::string> more) {
        std::vector<std::string> a = {"paint", "--source", src, "--strokes", js};
        a.insert(a.end(), more.begin(), more.end());
        return a;
    };
    expect_failure(args({"--width", "32"}), 1, "--width/--height");
    expect_failure(args({"--width", "32", "--height", "32", "--patch-size", "4"}), 1,
                   "--patch-size: 4");
    expect_failure(args({"--width", "32", "--height", "32", "--vote-histogram", "-1"}), 1,
                   "--vote-histogram: -1.000000 is invalid (must be 0..100)");
    expect_failure(args({"--width", "32", "--height", "32", "--usage", "most"}), 1,
                   "--usage: 'most' is invalid (must be one of none, uniform, error-budget, "
                   "occurrence)");
    std::ofstream(path("bad.json")) << R"([{"points": [[2, 2]], "width": "wide"}])";
    expect_failure({"paint", "--source", src, "--strokes", path("bad.json"), "--width", "32",
                    "--height", "32"},
                   1, "stroke 0: 'width' must be a number");
    std::ofstream(path("zero.json")) << R"([{"points": [[2, 2]], "width": 0}])";
    expect_failure({"paint", "--source", src, "--strokes", path("zero.json"), "--width", "32",
                    "--height", "32"},
                   1, "width: 0");
    std::ofstream(path("broken.json")) << "[{";
    expect_failure({"paint", "--source", src, "--strokes", path("broken.json"), "--width", "32",
                    "--height", "32"},
                   1, "not valid JSON");
    expect_failure(
        {"paint", "--source", src, "--strokes", path("s.txt"), "--width", "32", "--height", "32"},
        1, "must be a .json or .svg file");
    write("grey.png", Image(8, 8, 1, 0.5f));
    expect_failure(
        {"paint", "--source", path("grey.png"), "--strokes", js, "--width", "32", "--height", "32"},
        1, "channels (must be RGB or RGBA)");
    write("mask.png", Image(8, 8, 1, 1.0f));
    expect_failure(args({"--width", "32", "--height", "32", "--source-mask", path("mask.png")}), 1,
                   "--source-mask");
    expect_failure(args({"--width", "32", "--height", "32", "--canvas", path("grey.png")}), 1,
                   "--canvas");
}

}  // namespace
}  // namespace exemplar::cli::testing
