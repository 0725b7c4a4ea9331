// `exemplar directions` and `exemplar paint` run in-process: files written, their channels, and
// one-line errors naming the file or parameter.

#include <cmath>
#include <fstream>
#include <utility>

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

// Two textures side by side, opaque: warm horizontal stripes left, cool vertical stripes right;
// and its segmentation, red left and blue right.
Image two_textures(int w, int h) {
    Image im(w, h, 3);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const bool left = x < w / 2;
            const float stripe =
                0.5f + 0.4f * std::sin(0.785398f * static_cast<float>(left ? y : x));
            im.at(x, y, 0) = left ? 0.6f + 0.3f * stripe : 0.1f;
            im.at(x, y, 1) = left ? 0.4f * stripe : 0.3f * stripe;
            im.at(x, y, 2) = left ? 0.1f : 0.5f + 0.4f * stripe;
        }
    }
    return im;
}
Image two_segments(int w, int h) {
    Image im(w, h, 3);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) im.at(x, y, x < w / 2 ? 0 : 2) = 1.0f;
    }
    return im;
}

TEST_F(Cli, PaintWithLabelsUsesEachStrokesSegment) {
    write("two.png", two_textures(48, 32));
    write("segments.png", two_segments(48, 32));
    // JSON labels as colours; an SVG's stroke colours.
    std::ofstream(path("labels.json"))
        << R"([{"points": [[4, 12], [76, 12]], "width": 16, "label": "#0000ff"},
               {"points": [[4, 36], [76, 36]], "width": 16, "label": "#f00"}])";
    std::ofstream(path("labels.svg"))
        << R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 80 48">)"
        << R"(<path d="M 4 12 L 76 12" stroke="#0000ff" stroke-width="16"/>)"
        << R"(<path d="M 4 36 L 76 36" style="stroke:#ff0000;stroke-width:16"/></svg>)";
    // A grey segmentation (levels 3 and 200) named by grey levels.
    Image grey(48, 32, 1);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 48; ++x) grey.at(x, y, 0) = (x < 24 ? 3.0f : 200.0f) / 255.0f;
    }
    write("grey_segments.png", grey);
    std::ofstream(path("grey.json"))
        << R"([{"points": [[4, 12], [76, 12]], "width": 16, "label": 200},
               {"points": [[4, 36], [76, 36]], "width": 16, "label": 3}])";
    for (const auto& [strokes, segments] :
         {std::pair<std::string, std::string>{"labels.json", "segments.png"},
          {"labels.svg", "segments.png"},
          {"grey.json", "grey_segments.png"}}) {
        const CliRun r = run({"paint", "--source", path("two.png"), "--source-labels",
                              path(segments), "--strokes", path(strokes), "--width", "80",
                              "--height", "48", "-o", path("labelled.png"), "--threads", "2"});
        ASSERT_EQ(r.code, 0) << r.err;
        const Image out = read("labelled.png");
        // Top stroke: the blue segment's texture; bottom stroke: the red one's.
        for (int x = 10; x < 70; x += 6) {
            EXPECT_GT(out.at(x, 12, 2), out.at(x, 12, 0)) << strokes << " x " << x;
            EXPECT_GT(out.at(x, 36, 0), out.at(x, 36, 2)) << strokes << " x " << x;
        }
    }
}

TEST_F(Cli, PaintRejectsBadLabels) {
    write("two.png", two_textures(48, 32));
    write("segments.png", two_segments(48, 32));
    write("small.png", two_segments(40, 32));
    std::ofstream(path("green.json"))
        << R"([{"points": [[4, 12], [76, 12]], "width": 16, "label": "#ff0000"},
               {"points": [[4, 36], [76, 36]], "width": 16, "label": "#00ff00"}])";
    const std::vector<std::string> base = {"paint",    "--source", path("two.png"), "--width", "80",
                                           "--height", "48"};
    auto args = [&](std::vector<std::string> more) {
        std::vector<std::string> a = base;
        a.insert(a.end(), more.begin(), more.end());
        return a;
    };
    expect_failure(args({"--source-labels", path("segments.png"), "--strokes", path("green.json")}),
                   1,
                   "green.json: stroke 1: label #00ff00 has no segment in --source-labels " +
                       path("segments.png") + " (its colours: #0000ff, #ff0000)");
    expect_failure(args({"--source-labels", path("small.png"), "--strokes", path("green.json")}), 1,
                   "--source-labels " + path("small.png") + ": is 40x32 but --source is 48x32");
    // A label without --source-labels, and labels that name no colour.
    expect_failure(args({"--strokes", path("green.json")}), 1,
                   "stroke 0: 'label' is read only with --source-labels");
    std::ofstream(path("bad_label.json")) << R"([{"points": [[4, 12]], "label": 300}])";
    expect_failure(
        args({"--source-labels", path("segments.png"), "--strokes", path("bad_label.json")}), 1,
        "stroke 0: 'label': '300' is invalid (must be 0..255, a grey level, or #rrggbb)");
    std::ofstream(path("bad_colour.svg"))
        << R"svg(<svg xmlns="http://www.w3.org/2000/svg"><path d="M 4 12 L 40 12" stroke="url(#g)"/></svg>)svg";
    expect_failure(
        args({"--source-labels", path("segments.png"), "--strokes", path("bad_colour.svg")}), 1,
        "path 0: stroke colour: 'url(#g)' is invalid");
    expect_failure(args({"--source-labels", path("none.png"), "--strokes", path("green.json")}), 1,
                   "none.png");
}

// Issue 18's bad-input list: a stroke partly outside the canvas is clipped; an empty stroke list,
// an RGB source with nothing giving its shape, malformed JSON or SVG are one line naming the file,
// exit 1, nothing written. An all-white mask paints with the whole RGB source.
TEST_F(Cli, PaintClipsStrokesAndRejectsEmptyListsAndShapelessSources) {
    write("two.png", two_textures(48, 32));
    write("white.png", Image(48, 32, 1, 1.0f));
    std::ofstream(path("outside.json")) << R"([{"points": [[-30, 10], [50, 10]], "width": 12},
               {"points": [[200, 200], [300, 260]], "width": 12}])";
    CliRun r =
        run({"paint", "--source", path("two.png"), "--source-mask", path("white.png"), "--strokes",
             path("outside.json"), "--width", "40", "--height", "24", "-o", path("clipped.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    Image out = read("clipped.png");
    EXPECT_EQ(out.width(), 40);
    EXPECT_EQ(out.at(0, 10, 3), 1.0f);   // the clipped stroke, up to the canvas' left edge
    EXPECT_EQ(out.at(20, 20, 3), 0.0f);  // the stroke far outside painted nothing
    expect_failure({"paint", "--source", path("two.png"), "--strokes", path("outside.json"),
                    "--width", "40", "--height", "24"},
                   1,
                   "--source " + path("two.png") +
                       ": has no alpha channel and no --source-mask or --source-labels gives its "
                       "shape (an all-white mask paints with the whole image)");
    std::ofstream(path("empty.json")) << "[]";
    expect_failure({"paint", "--source", path("two.png"), "--source-mask", path("white.png"),
                    "--strokes", path("empty.json"), "--width", "40", "--height", "24"},
                   1, "--strokes " + path("empty.json") + ": has no strokes");
    std::ofstream(path("broken.svg")) << "<svg><path d=";
    expect_failure({"paint", "--source", path("two.png"), "--strokes", path("broken.svg"),
                    "--width", "40", "--height", "24"},
                   1, "broken.svg");
    std::ofstream(path("notobject.json")) << "[3]";
    expect_failure({"paint", "--source", path("two.png"), "--strokes", path("notobject.json"),
                    "--width", "40", "--height", "24"},
                   1, "stroke 0: must be an object");
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
