// `exemplar vectorize-style` runs in-process: a drawing rendered with a style palette file (the
// same pixels as the library's vectorize_style), and one-line errors naming the file and the
// problem with no output written.

#include <cstring>
#include <fstream>

#include "cli_fixture.hpp"
#include "exemplar/paint/vectorize_style.hpp"

namespace exemplar::cli::testing {
namespace {

const char* kDrawing = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 60 40">
  <g fill="none" stroke="black" stroke-width="6">
    <path d="M5 20 C20 10 40 30 55 20"/>
  </g>
</svg>)";

// A palette of its own: style.png (32x28) with a line feature along it and the whole of it as
// area feature; `strokes` and the background are given.
std::string palette_json(const std::string& strokes, const std::string& extra = "") {
    return R"({"palette": "style.png",
        "line_features": {"ink": {"path": [[2, 14], [30, 14]], "width": 8, "snap": false}},
        "area_features": {"paper": {"polygon": [[0, 0], [32, 0], [32, 28], [0, 28]]}},
        "strokes": )" +
           strokes + extra + "}";
}

class VectorizeStyleCli : public Cli {
protected:
    void text(const std::string& name, const std::string& content) {
        std::ofstream(path(name)) << content;
    }
};

TEST_F(VectorizeStyleCli, RendersTheDrawingAsTheLibraryDoes) {
    text("drawing.svg", kDrawing);
    text("style.json", palette_json(R"({"default": "ink"})", R"(, "background": "paper")"));
    const CliRun r =
        run({"vectorize-style", path("drawing.svg"), "--palette", path("style.json"), "-o",
             path("out/styled.png"), "--width", "120", "--threads", "2", "--rotations", "1"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("out/styled.png") + "\n");
    const Image out = read("out/styled.png");
    ASSERT_EQ(out.width(), 120);
    ASSERT_EQ(out.height(), 80);
    ASSERT_EQ(out.channels(), 4);

    auto drawing = sketch::load_svg(path("drawing.svg"));
    auto palette = paint::load_style_palette(path("style.json"));
    ASSERT_TRUE(drawing.ok() && palette.ok());
    paint::VectorizeStyleOptions options;
    options.fill.rotations = 1;
    auto expected = paint::vectorize_style(*drawing, *palette, 120, 80, options, RunContext(1));
    ASSERT_TRUE(expected.ok()) << expected.status().message();
    EXPECT_LE(max_abs_diff(out, *expected), 0.5f / 255.0f);  // PNG's 8 bits
}

// The fjord of examples/feature: filled shapes, a background and two line features.
TEST_F(VectorizeStyleCli, BundledExampleGivesItsPicture) {
    const std::string dir = std::string(EXEMPLAR_SOURCE_DIR) + "/examples/feature/";
    const CliRun r =
        run({"vectorize-style", dir + "fjord.svg", "--palette", dir + "fjord_style.json", "-o",
             path("fjord.png"), "-q", "--threads", "2"});
    ASSERT_EQ(r.code, 0) << r.err;
    const Image out = read("fjord.png");
    const Result<Image> picture = load_image(dir + "fjord.png");
    ASSERT_TRUE(picture.ok()) << picture.status().message();
    ASSERT_TRUE(out.same_size(*picture));
    EXPECT_LE(max_abs_diff(out, *picture), 1.5f / 255.0f);
}

TEST_F(VectorizeStyleCli, RejectsBadInputs) {
    text("drawing.svg", kDrawing);
    text("empty.svg", R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"/>)");
    text("style.json", palette_json(R"({"default": "ink"})"));
    text("unknown_name.json", palette_json(R"({"#000": "rail"})"));
    text("malformed.json", palette_json(R"({"default": "ink")"));
    text("unassigned.json", palette_json(R"({"#ff0000": "ink"})"));
    text("outside.json", R"({"palette": "style.png",
        "line_features": {"ink": {"path": [[2, 14], [90, 14]]}}, "strokes": {"default": "ink"}})");
    text("one_sample.json", R"({"palette": "style.png",
        "line_features": {"ink": {"path": [[2, 14]]}}, "strokes": {"default": "ink"}})");
    const auto args = [&](const std::string& drawing, const std::string& palette) {
        return std::vector<std::string>{"vectorize-style", path(drawing), "--palette",
                                        path(palette)};
    };
    expect_failure(args("empty.svg", "style.json"), 1, path("empty.svg") + ": holds no path");
    expect_failure(args("drawing.svg", "unknown_name.json"), 1,
                   path("unknown_name.json") +
                       ": strokes: \"#000000\" names line feature \"rail\", which is not "
                       "defined (defined: ink)");
    expect_failure(args("drawing.svg", "malformed.json"), 1,
                   path("malformed.json") + ": not valid JSON");
    expect_failure(args("drawing.svg", "unassigned.json"), 1,
                   path("drawing.svg") + ": path 0 (stroke #000000): no line feature is assigned");
    expect_failure(args("drawing.svg", "outside.json"), 1,
                   path("outside.json") +
                       ": line feature \"ink\": feature: point (90, 14) lies outside the palette "
                       "(32x28)");
    expect_failure(args("drawing.svg", "one_sample.json"), 1,
                   path("one_sample.json") + ": line feature \"ink\": feature: ");
    expect_failure(args("missing.svg", "style.json"), 1, path("missing.svg"));
    expect_failure(with(args("drawing.svg", "style.json"), {"--walk", "zigzag"}), 1, "--walk");
    expect_failure(with(args("drawing.svg", "style.json"), {"--rotations", "0"}), 1,
                   "--rotations: 0 is invalid");
}

}  // namespace
}  // namespace exemplar::cli::testing
