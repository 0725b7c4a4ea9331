// The `exemplar` command line, run in-process: exit codes, one-line messages that name the file
// or parameter, nothing written on failure, and equivalence of flags and job files.
#include "cli.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/options.hpp"
#include "test_images.hpp"

namespace exemplar::cli {
namespace {

namespace fs = std::filesystem;

struct CliRun {
    int code;
    std::string out;
    std::string err;
};

CliRun run(std::vector<std::string> args) {
    args.insert(args.begin(), "exemplar");
    std::vector<const char*> argv;
    for (const std::string& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    const int code = run_cli(static_cast<int>(argv.size()), argv.data(), out, err);
    return {code, out.str(), err.str()};
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("exemplar_cli_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        write("style.png", testing::texture(32, 28, 3, 1));
        write("a.png", testing::texture(32, 28, 3, 2));
        write("b.png", testing::texture(36, 30, 3, 3));
        write("ramp_a.exr", testing::ramp(32, 28));
        write("ramp_b.exr", testing::ramp(36, 30));
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    void write(const std::string& name, const Image& image) {
        ASSERT_TRUE(save_image(image, path(name)).is_ok());
    }
    std::vector<std::string> base_args() const {
        return {"stylize",
                "--style",
                path("style.png"),
                "--guide",
                path("a.png"),
                path("b.png"),
                "--levels",
                "1",
                "--em-iterations",
                "2",
                "--final-pass-iterations",
                "1"};
    }
    // Runs a failing command and checks the exit code, the one-line message and that no output
    // file was written.
    void expect_failure(std::vector<std::string> args, int code, const std::string& part) {
        args.push_back("-o");
        args.push_back(path("out.png"));
        const CliRun r = run(args);
        EXPECT_EQ(r.code, code) << r.err;
        EXPECT_NE(r.err.find(part), std::string::npos) << "message: " << r.err;
        EXPECT_EQ(r.err.rfind("exemplar: ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(fs::exists(path("out.png")));
    }

    fs::path dir_;
};

TEST_F(Cli, StylizeWritesTheOutputAndPrintsItsPath) {
    auto args = base_args();
    args.insert(args.end(), {"--weight", "2", "--guide", path("ramp_a.exr"), path("ramp_b.exr"),
                             "--weight", "5", "-o", path("out.png"), "--save-nnf", path("nnf.exr"),
                             "--save-error", path("error.exr"), "-j", "2"});
    const CliRun r = run(args);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find(path("out.png")), std::string::npos);
    auto out = load_image(path("out.png"));
    ASSERT_TRUE(out.ok());
    EXPECT_EQ(out->width(), 36);
    EXPECT_EQ(out->height(), 30);
    EXPECT_EQ(out->channels(), 3);
    EXPECT_TRUE(load_image(path("error.exr")).ok());

    // apply-nnf on the same style reproduces the output (up to 8-bit rounding).
    const CliRun a = run({"apply-nnf", "--nnf", path("nnf.exr"), "--source", path("style.png"),
                          "-o", path("again.png")});
    ASSERT_EQ(a.code, 0) << a.err;
    auto again = load_image(path("again.png"));
    ASSERT_TRUE(again.ok());
    float max_diff = 0.0f;
    for (std::size_t i = 0; i < again->size(); ++i) {
        max_diff = std::max(max_diff, std::abs(again->data()[i] - out->data()[i]));
    }
    EXPECT_LE(max_diff, 1.0f / 255.0f);
}

TEST_F(Cli, JobFileEqualsFlags) {
    auto args = base_args();
    args.insert(args.end(), {"--weight", "0.5", "--usage", "uniform", "--patch-size", "3", "-o",
                             path("flags.png"), "-q"});
    ASSERT_EQ(run(args).code, 0);
    std::ofstream(path("job.json")) << R"({
        "style": "style.png",
        "guides": [{"source": "a.png", "target": "b.png", "weight": 0.5}],
        "levels": 1, "em_iterations": 2, "final-pass-iterations": 1,
        "usage": "uniform", "patch-size": 3, "output": "job.png", "quiet": true
    })";
    const CliRun r = run({"stylize", "--config", path("job.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(r.out.empty());  // quiet
    auto a = load_image(path("flags.png"));
    auto b = load_image(path("job.png"));
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_TRUE(std::equal(a->data().begin(), a->data().end(), b->data().begin()));
    // Flags override the file.
    const CliRun o = run({"stylize", "--config", path("job.json"), "--patch-size", "4"});
    EXPECT_EQ(o.code, 1);
    EXPECT_NE(o.err.find("patch-size: 4 is invalid (must be odd"), std::string::npos) << o.err;
}

TEST_F(Cli, MissingAndCorruptFiles) {
    auto args = base_args();
    args[2] = path("nope.png");
    expect_failure(args, 1, path("nope.png") + ": no such file");
    std::ofstream(path("corrupt.png")) << "definitely not a png";
    args[2] = path("corrupt.png");
    expect_failure(args, 1, path("corrupt.png"));
    std::ofstream(path("style.xyz")) << "?";
    args[2] = path("style.xyz");
    expect_failure(args, 1, path("style.xyz"));
}

TEST_F(Cli, SizeAndChannelMismatches) {
    write("small.png", testing::texture(10, 10, 3, 4));
    write("gray.png", testing::texture(36, 30, 1, 5));
    auto args = base_args();
    args[4] = path("small.png");
    expect_failure(args, 1, "source guide is 10x10 but the style is 32x28");
    args = base_args();
    args.insert(args.end(), {"--guide", path("a.png"), path("small.png")});
    expect_failure(args, 1, "target guide is 10x10");
    args = base_args();
    args[5] = path("gray.png");
    expect_failure(args, 1, "has 3 channels but the target guide has 1");
}

TEST_F(Cli, BadParameters) {
    auto args = base_args();
    args.insert(args.end(), {"--patch-size", "4"});
    expect_failure(args, 1, "patch-size: 4 is invalid (must be odd, 3..31)");
    args = base_args();
    args.insert(args.end(), {"--patch-size", "31"});
    expect_failure(args, 1, "too large");
    args = base_args();
    args.insert(args.end(), {"--usage", "sometimes"});
    expect_failure(args, 1, "usage: 'sometimes' is invalid");
    args = {"stylize",         "--weight", "2",           "--style",
            path("style.png"), "--guide",  path("a.png"), path("b.png")};
    expect_failure(args, 1, "--weight must follow the --guide");
    args = base_args();
    args.push_back("--frobnicate");
    expect_failure(args, 2, "--frobnicate");
    args = base_args();
    args.insert(args.end(), {"--threads", "-3"});
    expect_failure(args, 1, "--threads");
}

TEST_F(Cli, MasksAndFloatInput) {
    write("empty.png", Image(36, 30, 1, 0.0f));
    auto args = base_args();
    args.insert(args.end(), {"--target-mask", path("empty.png"), "--init", path("b.png")});
    expect_failure(args, 1, "target mask: is empty");
    write("full.png", Image(36, 30, 1, 1.0f));
    args = base_args();
    args.insert(args.end(), {"--target-mask", path("full.png")});
    expect_failure(args, 1, "initial target");

    Image nan_guide = testing::ramp(36, 30);
    nan_guide.at(4, 4, 1) = std::numeric_limits<float>::quiet_NaN();
    write("nan.exr", nan_guide);
    args = base_args();
    args.insert(args.end(), {"--guide", path("ramp_a.exr"), path("nan.exr")});
    expect_failure(args, 1, "NaN");
}

TEST_F(Cli, JobFileErrorsNameTheFileAndKey) {
    std::ofstream(path("bad.json")) << R"({"style": "style.png", "colour": "red"})";
    expect_failure({"stylize", "--config", path("bad.json")}, 1,
                   path("bad.json") + ": unknown key 'colour'");
    std::ofstream(path("broken.json")) << "{ not json";
    expect_failure({"stylize", "--config", path("broken.json")}, 1, path("broken.json"));
}

TEST_F(Cli, HelpAndVersion) {
    const CliRun h = run({"stylize", "--help"});
    EXPECT_EQ(h.code, 0);
    EXPECT_NE(h.out.find("--patch-size"), std::string::npos);
    EXPECT_NE(h.out.find("default 5"), std::string::npos);
    EXPECT_NE(h.out.find("--guide"), std::string::npos);
    const CliRun v = run({"--version"});
    EXPECT_EQ(v.code, 0);
    EXPECT_NE(v.out.find("exemplar"), std::string::npos);
    EXPECT_EQ(run({}).code, 2);  // a subcommand is required
}

}  // namespace
}  // namespace exemplar::cli

namespace exemplar::cli {
namespace {

TEST(CliDocs, ReferenceListsEveryNumericOption) {
    std::ifstream in(std::string(EXEMPLAR_SOURCE_DIR) + "/docs/cli.md");
    ASSERT_TRUE(in);
    const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const OptionSpec& spec : synthesis_option_specs()) {
        EXPECT_NE(doc.find("`--" + std::string(spec.name) + "`"), std::string::npos) << spec.name;
    }
}

}  // namespace
}  // namespace exemplar::cli
