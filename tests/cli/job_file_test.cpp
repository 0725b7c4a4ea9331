// `exemplar stylize --config job.json`: the same options as JSON keys, paths relative to the job
// file, flags overriding the file, and errors naming the file and the key.

#include "cli_fixture.hpp"

namespace exemplar::cli::testing {
namespace {

TEST_F(Cli, JobFileGivesTheSameBytesAsFlags) {
    ASSERT_EQ(run(with(stylize_args(), {"--weight", "0.5", "--usage", "uniform", "--patch-size",
                                        "3", "--seed", "7", "-o", path("flags.png"), "-q"}))
                  .code,
              0);
    // In a sub-folder, so that relative paths must resolve against the job file's folder.
    fs::create_directories(path("jobs"));
    std::ofstream(path("jobs/job.json")) << R"({
        "style": "../style.png",
        "guides": [{"source": "../a.png", "target": "../b.png", "weight": 0.5}],
        "levels": 1, "em_iterations": 2, "final-pass-iterations": 1, "seed": 7,
        "usage": "uniform", "patch-size": 3, "output": "../job.png", "quiet": true
    })";
    const CliRun r = run({"stylize", "--config", path("jobs/job.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(r.out.empty());  // quiet from the file
    ASSERT_TRUE(fs::exists(path("job.png")));
    EXPECT_EQ(file_bytes(path("flags.png")), file_bytes(path("job.png")));
}

TEST_F(Cli, FlagsOverrideTheJobFile) {
    std::ofstream(path("job.json")) << R"({
        "style": "style.png", "guides": [{"source": "a.png", "target": "b.png"}],
        "levels": 1, "em-iterations": 2, "patch-size": 3, "output": "job.png"
    })";
    expect_failure({"stylize", "--config", path("job.json"), "--patch-size", "4"}, 1,
                   "patch-size: 4 is invalid (must be odd");
    EXPECT_FALSE(fs::exists(path("job.png")));
    // Output and guides from the command line replace the file's.
    write("small.png", texture(20, 18, 3, 9));
    const CliRun r = run({"stylize", "--config", path("job.json"), "--guide", path("a.png"),
                          path("small.png"), "-o", path("flag.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("flag.png") + "\n");
    EXPECT_FALSE(fs::exists(path("job.png")));
    EXPECT_EQ(read("flag.png").width(), 20);
}

TEST_F(Cli, JobFileErrorsNameTheFileAndKey) {
    std::ofstream(path("bad.json")) << R"({"style": "style.png", "colour": "red"})";
    expect_failure({"stylize", "--config", path("bad.json")}, 1,
                   path("bad.json") + ": unknown key 'colour'");
    std::ofstream(path("bad_guide.json"))
        << R"({"style": "style.png", "guides": [{"source": "a.png", "target": "b.png", "wieght": 2}]})";
    expect_failure({"stylize", "--config", path("bad_guide.json")}, 1,
                   path("bad_guide.json") + ": unknown key 'guides.wieght'");
    std::ofstream(path("bad_type.json")) << R"({"style": "style.png", "patch-size": "five"})";
    expect_failure({"stylize", "--config", path("bad_type.json")}, 1,
                   path("bad_type.json") + ": key 'patch-size' must be a number");
    std::ofstream(path("bad_quality.json")) << R"({"style": "style.png", "quality": "max"})";
    expect_failure({"stylize", "--config", path("bad_quality.json")}, 1,
                   "quality: 'max' is invalid (must be one of fast, default, best)");
    std::ofstream(path("quality_number.json")) << R"({"style": "style.png", "quality": 2})";
    expect_failure({"stylize", "--config", path("quality_number.json")}, 1,
                   path("quality_number.json") + ": key 'quality' must be a string");
    std::ofstream(path("broken.json")) << "{ not json";
    expect_failure({"stylize", "--config", path("broken.json")}, 1,
                   path("broken.json") + ": not valid JSON");
    expect_failure({"stylize", "--config", path("missing.json")}, 1,
                   path("missing.json") + ": no such file");
    // A job file without an output and none on the command line.
    std::ofstream(path("no_output.json"))
        << R"({"style": "style.png", "guides": [{"source": "a.png", "target": "b.png"}]})";
    expect_failure_as_is({"stylize", "--config", path("no_output.json")}, 2,
                         "--output: is required");
}

}  // namespace
}  // namespace exemplar::cli::testing
