// `exemplar stylit`: --save-nnf and --save-error (the output files of `stylize`), and JSON job
// files (--config) read with the reader `stylize` uses.

#include "cli_fixture.hpp"
#include "exemplar/synth/nnf.hpp"

namespace exemplar::cli::testing {
namespace {

class StylitOutputs : public Cli {
protected:
    // A painting and 2 source buffers 32x28 (style.png, a.png), 2 target buffers 36x30.
    void SetUp() override {
        Cli::SetUp();
        write("s_spec.png", texture(32, 28, 3, 5));
        write("t_spec.png", texture(36, 30, 3, 7));
    }
    std::vector<std::string> args() const {
        return {"stylit",   "--exemplar",  path("style.png"),
                "--source", path("a.png"), path("s_spec.png"),
                "--target", path("b.png"), path("t_spec.png")};
    }
};

TEST_F(StylitOutputs, SavesTheNnfAndTheErrorMap) {
    const CliRun r = run(with(args(), {"-o", path("out.png"), "--save-nnf", path("nnf.exr"),
                                       "--save-error", path("error.png"), "-j", "2"}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("out.png") + "\n");
    EXPECT_NE(r.err.find(path("nnf.exr") + " was made with patch size"), std::string::npos)
        << r.err;
    // The NNF points into the painting (32x28) from the target pixels (36x30); -1, -1 marks
    // pixels without a match.
    auto nnf = nnf_from_image(read("nnf.exr"));
    ASSERT_TRUE(nnf.ok()) << nnf.status().message();
    ASSERT_EQ(nnf->width(), 36);
    ASSERT_EQ(nnf->height(), 30);
    int matched = 0;
    for (int y = 0; y < 30; ++y) {
        for (int x = 0; x < 36; ++x) {
            const auto& m = nnf->at(x, y);
            if (m.x == -1 && m.y == -1) continue;
            ASSERT_TRUE(m.x >= 0 && m.x < 32 && m.y >= 0 && m.y < 28)
                << x << "," << y << ": " << m.x << "," << m.y;
            ++matched;
        }
    }
    EXPECT_GT(matched, 36 * 30 * 3 / 4);
    // A PNG error map is scaled to [0, 1] with its 99th percentile at white.
    const Image error = read("error.png");
    ASSERT_EQ(error.width(), 36);
    ASSERT_EQ(error.channels(), 1);
    const auto [lo, hi] = std::minmax_element(error.data().begin(), error.data().end());
    EXPECT_GE(*lo, 0.0f);
    EXPECT_EQ(*hi, 1.0f);
    // Quiet: no note either.
    const CliRun q = run(with(args(), {"-o", path("q.png"), "--save-nnf", path("q.exr"), "-q"}));
    ASSERT_EQ(q.code, 0) << q.err;
    EXPECT_TRUE(q.err.empty()) << q.err;
}

TEST_F(StylitOutputs, OutputFilesAreCheckedBeforeTheRun) {
    expect_failure(with(args(), {"--save-nnf", path("nnf.png")}), kExitFailure,
                   "--save-nnf " + path("nnf.png") + ": must be an .exr file");
    expect_failure(with(args(), {"--save-error", path("out.png")}), kExitFailure,
                   "--save-error " + path("out.png") + ": is also the --output file");
    expect_failure(with(args(), {"--save-error", path("style.png/error.png")}), kExitFailure,
                   "--save-error " + path("style.png/error.png") + ": cannot create folder");
    expect_failure(with(args(), {"--quality", "superb"}), kExitFailure,
                   "quality: 'superb' is invalid (must be one of fast, default, best)");
    expect_failure(with(args(), {"--save-error", path("error.xyz")}), kExitFailure,
                   "--save-error " + path("error.xyz"));
}

TEST_F(StylitOutputs, JobFileGivesTheSameBytesAsFlags) {
    ASSERT_EQ(run(with(args(), {"-o", path("flags.png"), "--seed", "5", "--usage", "uniform",
                                "--guidance-weight", "3", "-q"}))
                  .code,
              0);
    // In a sub-folder, so that relative paths must resolve against the job file's folder.
    fs::create_directories(path("jobs"));
    std::ofstream(path("jobs/job.json")) << R"({
        "exemplar": "../style.png",
        "source": ["../a.png", "../s_spec.png"],
        "target": ["../b.png", "../t_spec.png"],
        "guidance_weight": 3, "usage": "uniform", "seed": 5,
        "output": "../job.png", "save-nnf": "../job_nnf.exr", "quiet": true
    })";
    const CliRun r = run({"stylit", "--config", path("jobs/job.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(r.out.empty());  // quiet from the file
    EXPECT_EQ(file_bytes(path("flags.png")), file_bytes(path("job.png")));
    EXPECT_TRUE(fs::exists(path("job_nnf.exr")));
    // Flags win over the file (output path and seed).
    const CliRun f =
        run({"stylit", "--config", path("jobs/job.json"), "-o", path("flag.png"), "--seed", "6"});
    ASSERT_EQ(f.code, 0) << f.err;
    EXPECT_TRUE(fs::exists(path("flag.png")));
    EXPECT_NE(file_bytes(path("flag.png")), file_bytes(path("job.png")));
}

TEST_F(StylitOutputs, TheBundledJobFileNamesTheBundledData) {
    // Run in preview on the bundled StyLit data: the paths in the file resolve.
    const CliRun r =
        run({"stylit", "--config", EXEMPLAR_SOURCE_DIR "/examples/stylit/stylit_job.json",
             "--preview", "-o", path("bundled.png"), "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_GT(read("bundled.png").width(), 100);
}

TEST_F(StylitOutputs, JobFileErrorsNameTheFileAndKey) {
    std::ofstream(path("bad.json")) << R"({"exemplar": "style.png", "colour": "red"})";
    expect_failure({"stylit", "--config", path("bad.json")}, kExitFailure,
                   path("bad.json") + ": unknown key 'colour'");
    std::ofstream(path("bad_source.json")) << R"({"exemplar": "style.png", "source": [1, 2]})";
    expect_failure(
        {"stylit", "--config", path("bad_source.json")}, kExitFailure,
        path("bad_source.json") + ": key 'source' must be a file path or an array of file paths");
    std::ofstream(path("bad_seed.json")) << R"({"exemplar": "style.png", "seed": -3})";
    expect_failure({"stylit", "--config", path("bad_seed.json")}, kExitFailure,
                   path("bad_seed.json") + ": key 'seed' must be >= 0");
    std::ofstream(path("bad_preview.json")) << R"({"exemplar": "style.png", "preview": 1})";
    expect_failure({"stylit", "--config", path("bad_preview.json")}, kExitFailure,
                   path("bad_preview.json") + ": key 'preview' must be true or false");
    std::ofstream(path("bad_quality.json")) << R"({"exemplar": "style.png", "quality": "max"})";
    expect_failure(with(args(), {"--config", path("bad_quality.json")}), kExitFailure,
                   "quality: 'max' is invalid (must be one of fast, default, best)");
    expect_failure({"stylit", "--config", path("none.json")}, kExitFailure,
                   path("none.json") + ": no such file");
}

}  // namespace
}  // namespace exemplar::cli::testing
