// `exemplar stylit`, `stylit sheet` and `stylit align` in-process: outputs written, and one-line
// errors with exit code != 0 for missing buffers, buffers of different sizes and an EXR without
// the named layer.

#include "cli_fixture.hpp"
#include "stylit_test_data.hpp"

namespace exemplar::cli::testing {
namespace {

class StylitCli : public Cli {
protected:
    // Tiny renders: painting and 2 source buffers 32x28, 2 target buffers 36x30.
    void SetUp() override {
        Cli::SetUp();
        write("s_full.png", texture(32, 28, 3, 4));
        write("s_spec.png", texture(32, 28, 3, 5));
        write("t_full.png", texture(36, 30, 3, 6));
        write("t_spec.png", texture(36, 30, 3, 7));
    }
    std::vector<std::string> args() const {
        return {"stylit",   "--exemplar",       path("style.png"),
                "--source", path("s_full.png"), path("s_spec.png"),
                "--target", path("t_full.png"), path("t_spec.png")};
    }
};

TEST_F(StylitCli, StylizesAndPreviews) {
    CliRun r = run(with(args(), {"-o", path("out.png"), "--seed", "3", "-j", "1"}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("out.png") + "\n");
    EXPECT_EQ(read("out.png").width(), 36);
    r = run(with(args(), {"-o", path("preview.png"), "--preview"}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(read("preview.png").width(), 18);
    EXPECT_NE(r.err.find("preview at 18x15"), std::string::npos) << r.err;
}

TEST_F(StylitCli, MissingBufferFile) {
    expect_failure({"stylit", "--exemplar", path("style.png"), "--source", path("s_full.png"),
                    path("nope.png"), "--target", path("t_full.png"), path("t_spec.png")},
                   kExitFailure, "nope.png");
}

TEST_F(StylitCli, MissingFlagsAndUnpairedBuffers) {
    expect_failure({"stylit", "--exemplar", path("style.png"), "--source", path("s_full.png")},
                   kExitUsage, "--target");
    expect_failure({"stylit", "--exemplar", path("style.png"), "--source", path("s_full.png"),
                    path("s_spec.png"), "--target", path("t_full.png")},
                   kExitFailure, "--target has 1");
}

TEST_F(StylitCli, BuffersOfDifferentSizes) {
    write("t_small.png", texture(30, 30, 3, 8));
    expect_failure({"stylit", "--exemplar", path("style.png"), "--source", path("s_full.png"),
                    path("s_spec.png"), "--target", path("t_full.png"), path("t_small.png")},
                   kExitFailure, "30x30");
    // The painting must have the exemplar render's size.
    expect_failure({"stylit", "--exemplar", path("b.png"), "--source", path("s_full.png"),
                    "--target", path("t_full.png")},
                   kExitFailure, "exemplar painting is 36x30");
}

TEST_F(StylitCli, ExrWithoutTheNamedLayerListsItsLayers) {
    const Image s = texture(32, 28, 3, 4), t = texture(36, 30, 3, 5);
    ASSERT_TRUE(
        save_exr_layers({{"ViewLayer.Combined", &s}, {"ViewLayer.DiffDir", &s}}, path("source.exr"))
            .is_ok());
    ASSERT_TRUE(
        save_exr_layers({{"ViewLayer.Combined", &t}, {"ViewLayer.DiffDir", &t}}, path("target.exr"))
            .is_ok());
    expect_failure({"stylit", "--exemplar", path("style.png"), "--source", path("source.exr"),
                    "--target", path("target.exr"), "--preset", "cycles"},
                   kExitFailure, "the file has layers: ViewLayer.Combined, ViewLayer.DiffDir");
    // Naming the layers it has works.
    const CliRun r =
        run({"stylit", "--exemplar", path("style.png"), "--source", path("source.exr"), "--target",
             path("target.exr"), "--layers", "Combined,DiffDir", "-q", "-o", path("ok.png")});
    EXPECT_EQ(r.code, 0) << r.err;
    expect_failure({"stylit", "--exemplar", path("style.png"), "--source", path("source.exr"),
                    "--target", path("target.exr"), "--preset", "vray"},
                   kExitFailure, "preset 'vray' is unknown");
}

TEST_F(StylitCli, SheetThenAlign) {
    const std::string render = exemplar::testing::example_path("source_fullgi.png");
    CliRun r = run({"stylit", "sheet", "--render", render, "-o", path("sheet.png"), "--pdf",
                    path("sheet.pdf")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("sheet.png") + "\n" + path("sheet.pdf") + "\n");
    // The unpainted sheet as its own "scan": aligned, it is the low-contrast render.
    r = run({"stylit", "align", "--scan", path("sheet.png"), "--render", render, "-o",
             path("aligned.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const Image aligned = read("aligned.png");
    EXPECT_EQ(aligned.width(), 600);
    EXPECT_EQ(aligned.height(), 456);
    EXPECT_NEAR(aligned.at(300, 10, 0), read("sheet.png").at(300 + 95, 10 + 95, 0), 0.02f);
    // A scan without marks: one line, nothing written.
    expect_failure_as_is(
        {"stylit", "align", "--scan", path("style.png"), "--render", render, "-o", path("bad.png")},
        kExitFailure, "alignment marks");
    expect_failure_as_is({"stylit", "sheet", "--render", render}, kExitUsage, "--pdf");
    expect_failure_as_is(
        {"stylit", "--preview", "sheet", "--render", render, "--pdf", path("x.pdf")}, kExitUsage,
        "not to its sub-command sheet");
}

TEST_F(StylitCli, HelpOfEachLevel) {
    CliRun r = run({"stylit", "--help"});
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.out.find("--exemplar"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("sheet"), std::string::npos);
    r = run({"stylit", "sheet", "--help"});
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.out.find("--pdf"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("--exemplar"), std::string::npos) << r.out;
    r = run({"stylit", "align", "--bogus"});
    EXPECT_EQ(r.code, kExitUsage);
    EXPECT_NE(r.err.find("(see exemplar stylit align --help)"), std::string::npos) << r.err;
}

// Missing output folders are created by stylit, stylit sheet (image and PDF) and stylit align; a
// file in the way of one is a one-line error, and nothing is written.
TEST_F(StylitCli, OutputFoldersAreCreated) {
    CliRun r = run(with(args(), {"-q", "-o", path("out/a/styled.png"), "--save-nnf",
                                 path("out/b/nnf.exr"), "--save-error", path("out/c/error.exr")}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(read("out/a/styled.png").width(), 36);
    EXPECT_TRUE(fs::exists(path("out/b/nnf.exr")));
    EXPECT_TRUE(fs::exists(path("out/c/error.exr")));
    const std::string render = exemplar::testing::example_path("source_fullgi.png");
    r = run({"stylit", "sheet", "--render", render, "-o", path("print/png/sheet.png"), "--pdf",
             path("print/pdf/sheet.pdf")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(path("print/pdf/sheet.pdf")));
    r = run({"stylit", "align", "--scan", path("print/png/sheet.png"), "--render", render, "-o",
             path("scans/aligned/painting.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(read("scans/aligned/painting.png").width(), 600);

    std::ofstream(path("blocker")) << "x";
    const std::string in_the_way = path("blocker") + " is a file, not a folder";
    expect_failure_as_is(with(args(), {"-o", path("blocker/styled.png")}), kExitFailure,
                         in_the_way);
    expect_failure_as_is({"stylit", "sheet", "--render", render, "--pdf", path("blocker/s.pdf")},
                         kExitFailure, "--pdf " + path("blocker/s.pdf") + ": cannot create folder");
    expect_failure_as_is({"stylit", "align", "--scan", path("print/png/sheet.png"), "--render",
                          render, "-o", path("blocker/a/painting.png")},
                         kExitFailure, in_the_way);
}

}  // namespace
}  // namespace exemplar::cli::testing
