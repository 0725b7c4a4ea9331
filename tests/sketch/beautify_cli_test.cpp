// `exemplar beautify`: outputs on a real sketch, and one-line errors for bad inputs.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_fixture.hpp"
#include "exemplar/sketch/svg.hpp"

namespace exemplar::cli::testing {
namespace {

const std::string kSketch =
    std::string(EXEMPLAR_TEST_DATA_DIR) + "/strokes/tu-berlin/alarm_clock/85.svg";

class Beautify : public Cli {
protected:
    void write_text(const std::string& name, const std::string& text) {
        std::ofstream(path(name)) << text;
    }
    // Runs `args -o out.svg`: exit code, one stderr line containing `part`, nothing written.
    void fails(std::vector<std::string> args, int code, const std::string& part) {
        args.push_back("-o");
        args.push_back(path("out.svg"));
        expect_failure_as_is(args, code, part);
        EXPECT_FALSE(fs::exists(path("out.svg")));
    }
};

TEST_F(Beautify, WritesDrawingReportSuggestionsAndPreview) {
    const CliRun r =
        run({"beautify", kSketch, "-o", path("clean.svg"), "--report", path("report.json"),
             "--suggestions", path("last.json"), "--preview", path("before_after.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("clean.svg") + "\n" + path("report.json") + "\n" + path("last.json") +
                         "\n" + path("before_after.png") + "\n");
    auto input = sketch::load_svg(kSketch);
    auto clean = sketch::load_svg(path("clean.svg"));
    ASSERT_TRUE(input.ok() && clean.ok());
    EXPECT_EQ(clean->paths.size(), input->paths.size());
    EXPECT_EQ(clean->ids, input->ids);

    const auto report = nlohmann::json::parse(file_bytes(path("report.json")));
    EXPECT_EQ(report["strokes"].get<std::size_t>(), input->paths.size());
    ASSERT_EQ(report["per_stroke"].size(), input->paths.size());
    int relations = 0;
    for (const auto& stroke : report["per_stroke"]) {
        relations += static_cast<int>(stroke["relations"].size());
        for (const auto& rel : stroke["relations"])
            EXPECT_FALSE(rel["detail"].get<std::string>().empty());
    }
    EXPECT_GT(relations, 0);
    EXPECT_FALSE(report["relation_counts"].empty());

    const auto last = nlohmann::json::parse(file_bytes(path("last.json")));
    ASSERT_FALSE(last["suggestions"].empty());
    EXPECT_LE(last["suggestions"].size(), 10u);
    EXPECT_EQ(last["suggestions"][0]["rank"], 1);
    // Ranked by likelihood.
    for (std::size_t k = 1; k < last["suggestions"].size(); ++k) {
        if (last["suggestions"][k]["original"].get<bool>()) continue;
        EXPECT_LE(last["suggestions"][k]["likelihood"].get<double>(),
                  last["suggestions"][k - 1]["likelihood"].get<double>());
    }
    auto preview = load_image(path("before_after.png"));
    ASSERT_TRUE(preview.ok());
    EXPECT_EQ(preview->width(), 1024);
}

TEST_F(Beautify, SuggestionsAsSvgAndTheSameResultEveryRun) {
    ASSERT_EQ(
        run({"beautify", kSketch, "-o", path("a.svg"), "--suggestions", path("s.svg"), "-q"}).code,
        0);
    ASSERT_EQ(run({"beautify", kSketch, "-o", path("b.svg"), "-q"}).code, 0);
    EXPECT_EQ(file_bytes(path("a.svg")), file_bytes(path("b.svg")));
    auto panels = sketch::load_svg(path("s.svg"));
    ASSERT_TRUE(panels.ok()) << panels.status().message();
    EXPECT_GT(panels->paths.size(), 1u);
}

TEST_F(Beautify, FitRefitsPenPolylinesAsSmoothPaths) {
    const std::string house = std::string(EXEMPLAR_SOURCE_DIR) + "/examples/sketch/house.svg";
    ASSERT_EQ(run({"beautify", house, "-o", path("raw.svg"), "-q"}).code, 0);
    ASSERT_EQ(run({"beautify", house, "-o", path("fit.svg"), "--fit", "1", "-q"}).code, 0);
    auto raw = sketch::load_svg(path("raw.svg"));
    auto fit = sketch::load_svg(path("fit.svg"));
    ASSERT_TRUE(raw.ok() && fit.ok());
    ASSERT_EQ(raw->paths.size(), fit->paths.size());
    // The free-form first bird is kept as drawn (a polyline of many pieces) unless refitted.
    const std::size_t bird = 8;
    ASSERT_EQ(raw->ids[bird], "bird-1");
    EXPECT_GT(raw->paths[bird].segments.size(), 20u);
    EXPECT_LT(fit->paths[bird].segments.size(), 8u);
    EXPECT_LT(sketch::discrete_frechet(sketch::sample_path(raw->paths[bird], 64),
                                       sketch::sample_path(fit->paths[bird], 64)),
              1.5);
}

// Missing folders of every output are created (on the bundled sketch: no shared data needed).
TEST_F(Beautify, OutputFoldersAreCreated) {
    const std::string house = EXEMPLAR_SOURCE_DIR "/examples/sketch/house.svg";
    const CliRun r = run({"beautify", house, "-q", "-o", path("clean/a/clean.svg"), "--report",
                          path("reports/r.json"), "--suggestions", path("s/last.svg"), "--preview",
                          path("p/q/before_after.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* name :
         {"clean/a/clean.svg", "reports/r.json", "s/last.svg", "p/q/before_after.png"}) {
        EXPECT_TRUE(fs::exists(path(name))) << name;
    }
}

TEST_F(Beautify, BadInputsGiveOneLineErrors) {
    write_text("empty.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\"><g/></svg>");
    write_text("dot.svg",
               "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0 L10 0\"/>"
               "<path id=\"dot\" d=\"M5 5\"/></svg>");
    write_text("broken.svg", "<svg><path d=\"M0 0 L\"");
    write_text("bad_path.svg", "<svg><path id=\"p7\" d=\"M0 0 L 5\"/></svg>");
    write_text("one.svg", "<svg><path d=\"M0 0 L10 0\"/></svg>");
    fails({"beautify", path("missing.svg")}, 1, "missing.svg: cannot read");
    fails({"beautify", path("broken.svg")}, 1, "broken.svg: not valid XML");
    fails({"beautify", path("bad_path.svg")}, 1, "id=\"p7\"");
    fails({"beautify", path("empty.svg")}, 1, "empty.svg: the drawing has no strokes");
    fails({"beautify", path("dot.svg")}, 1,
          "dot.svg: stroke 1 (id \"dot\") is degenerate (a single point)");
    fails({"beautify", path("one.svg"), "--fit", "-1"}, 1, "--fit: -1.000000 is invalid");
    fails({"beautify", path("one.svg"), "--max-suggestions", "0"}, 1,
          "--max-suggestions: 0 is invalid (must be 1..100)");
    expect_failure_as_is({"beautify", path("one.svg"), "-o", path("out.png")}, 1,
                         "must be an .svg file");
    fails({"beautify", path("one.svg"), "--suggestions", path("s.txt")}, 1,
          "must be a .json or .svg file");
    fails({"beautify", path("one.svg"), "--preview", path("p.jpg")}, 1, "must be a .png file");
    fails({"beautify", path("one.svg"), "--report", path("one.svg/r.json")}, 1,
          "one.svg is a file, not a folder");
    fails({"beautify"}, 2, "drawing is required");
}

}  // namespace
}  // namespace exemplar::cli::testing
