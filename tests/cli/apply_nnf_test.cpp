// `exemplar apply-nnf`: a saved NNF re-applied to the style reproduces the stylize output, keeps a
// 16-bit source's precision, and refuses a patch size or source that do not fit the NNF.

#include <limits>

#include "cli_fixture.hpp"

namespace exemplar::cli::testing {
namespace {

class ApplyNnf : public Cli {
protected:
    void SetUp() override {
        Cli::SetUp();
        const CliRun r =
            run(with(stylize_args(), {"-o", path("styled.png"), "--save-nnf", path("nnf.exr")}));
        ASSERT_EQ(r.code, 0) << r.err;
        // The default preset's votes weigh coherence and its last vote blends seams: the note
        // says so.
        ASSERT_NE(
            r.err.find("(apply-nnf --patch-size 3 --vote-size 3 --vote-seams --vote-coherence 2)"),
            std::string::npos)
            << r.err;
    }
    std::vector<std::string> apply_args(const std::string& source) const {
        return {"apply-nnf",    "--nnf", path("nnf.exr"),    "--source", path(source),
                "--patch-size", "3",     "--vote-coherence", "2",        "--vote-seams"};
    }
};

TEST_F(ApplyNnf, ReproducesTheStylizeOutput) {
    const CliRun r = run(with(apply_args("style.png"), {"-o", path("again.png")}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("again.png") + "\n");
    const Image out = read("styled.png");
    const Image again = read("again.png");
    ASSERT_TRUE(again.same_size(out));
    ASSERT_EQ(again.channels(), out.channels());
    EXPECT_LE(max_abs_diff(out, again), 1.0f / 255.0f);
    EXPECT_EQ(png_bit_depth(path("again.png")), 8);
}

TEST_F(ApplyNnf, ReproducesTheDefaultNarrowVote) {
    // Without the 3x3 pass the 5x5 NNF votes with its central 3x3 (--final-vote-size 3; seams
    // not blended, which the default preset does).
    auto args = with(stylize_args(), {"-o", path("styled5.png"), "--save-nnf", path("nnf5.exr"),
                                      "--final-vote-seams", "0"});
    args[args.size() - 7] = "0";  // --final-pass-iterations 0
    const CliRun r = run(args);
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_NE(r.err.find("(apply-nnf --patch-size 5 --vote-size 3 --vote-coherence 2)"),
              std::string::npos)
        << r.err;
    const std::vector<std::string> apply = {
        "apply-nnf",    "--nnf", path("nnf5.exr"),   "--source", path("style.png"),
        "--patch-size", "5",     "--vote-coherence", "2"};
    ASSERT_EQ(run(with(apply, {"-q", "-o", path("again5.png")})).code, 0);
    EXPECT_LE(max_abs_diff(read("again5.png"), read("styled5.png")), 1.0f / 255.0f);
    // Whole 5x5 patches average more: a different image.
    ASSERT_EQ(run(with(apply, {"-q", "--vote-size", "0", "-o", path("whole5.png")})).code, 0);
    EXPECT_GT(max_abs_diff(read("whole5.png"), read("styled5.png")), 2.0f / 255.0f);
    // A run with seams blended (--final-vote-seams 1, in the presets) notes --vote-seams and
    // is reproduced with it.
    auto seams = with(stylize_args(), {"-o", path("seams5.png"), "--save-nnf", path("seams5.exr"),
                                       "--final-vote-seams", "1"});
    seams[seams.size() - 7] = "0";  // --final-pass-iterations 0
    const CliRun s = run(seams);
    ASSERT_EQ(s.code, 0) << s.err;
    ASSERT_NE(
        s.err.find("(apply-nnf --patch-size 5 --vote-size 3 --vote-seams --vote-coherence 2)"),
        std::string::npos)
        << s.err;
    std::vector<std::string> apply_seams = apply;
    apply_seams[2] = path("seams5.exr");
    ASSERT_EQ(run(with(apply_seams, {"-q", "--vote-seams", "-o", path("again_s.png")})).code, 0);
    EXPECT_LE(max_abs_diff(read("again_s.png"), read("seams5.png")), 1.0f / 255.0f);
    ASSERT_EQ(run(with(apply_seams, {"-q", "-o", path("narrow_s.png")})).code, 0);
    EXPECT_GT(max_abs_diff(read("narrow_s.png"), read("seams5.png")), 1.0f / 255.0f);
    // A run whose votes do not weigh coherence (--vote-coherence 0; 2 in the default and best
    // presets) notes no coherence and is reproduced without it; with it, a different image.
    auto plain = with(stylize_args(), {"-o", path("plain5.png"), "--save-nnf", path("plain5.exr"),
                                       "--vote-coherence", "0", "--final-vote-seams", "0"});
    plain[plain.size() - 9] = "0";  // --final-pass-iterations 0
    const CliRun c = run(plain);
    ASSERT_EQ(c.code, 0) << c.err;
    ASSERT_NE(c.err.find("(apply-nnf --patch-size 5 --vote-size 3)"), std::string::npos) << c.err;
    const std::vector<std::string> apply_plain = {
        "apply-nnf",    "--nnf", path("plain5.exr"), "--source", path("style.png"),
        "--patch-size", "5"};
    ASSERT_EQ(run(with(apply_plain, {"-q", "-o", path("again_p.png")})).code, 0);
    EXPECT_LE(max_abs_diff(read("again_p.png"), read("plain5.png")), 1.0f / 255.0f);
    ASSERT_EQ(run(with(apply_plain, {"-q", "--vote-coherence", "2", "-o", path("coh_p.png")})).code,
              0);
    EXPECT_GT(max_abs_diff(read("coh_p.png"), read("plain5.png")), 1.0f / 255.0f);
    expect_failure(with(apply, {"--vote-size", "2"}), 1,
                   "--vote-size: 2 is invalid (must be 0 or odd, 0..31)");
    expect_failure(with(apply_plain, {"--vote-coherence", "-2"}), 1,
                   "vote-coherence: -2 is invalid (must be 0..100)");
}

TEST_F(ApplyNnf, SixteenBitSourceGivesSixteenBitOutput) {
    // The style with 16-bit precision: the re-applied result keeps it.
    Image fine = texture(32, 28, 3, 1);
    for (float& v : fine.data()) v = std::round(v * 65535.0f) / 65535.0f;
    write("style16.png", fine, SaveOptions{PixelFormat::UInt16});
    const CliRun r = run(with(apply_args("style16.png"), {"-q", "-o", path("out16.png")}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(r.out.empty());
    EXPECT_EQ(png_bit_depth(path("out16.png")), 16);
    EXPECT_LE(max_abs_diff(read("out16.png"), read("styled.png")), 1.0f / 255.0f);
    // A 16-bit file holding 8-bit values (a converted 8-bit image) is still 16-bit in, 16 out.
    write("style8in16.png", read("style.png"), SaveOptions{PixelFormat::UInt16});
    ASSERT_EQ(run(with(apply_args("style8in16.png"), {"-q", "-o", path("out8in16.png")})).code, 0);
    EXPECT_EQ(png_bit_depth(path("out8in16.png")), 16);
    EXPECT_LE(max_abs_diff(read("out8in16.png"), read("styled.png")), 1.0f / 255.0f);
}

TEST_F(ApplyNnf, ExtraChannelsAreCarried) {
    write("five.exr", texture(32, 28, 5, 4));
    ASSERT_EQ(run(with(apply_args("five.exr"), {"-q", "-o", path("five_out.exr")})).code, 0);
    const Image out = read("five_out.exr");
    EXPECT_EQ(out.channels(), 5);
    EXPECT_EQ(out.width(), 36);
}

TEST_F(ApplyNnf, Errors) {
    auto args = apply_args("style.png");
    args[6] = "4";
    expect_failure(args, 1, "patch-size: 4 is invalid (must be odd, 3..31)");
    // A source smaller than the style the NNF points into.
    write("small.png", texture(12, 12, 3, 5));
    expect_failure(apply_args("small.png"), 1, "--source " + path("small.png"));
    Image nan_source = texture(32, 28, 3, 1);
    nan_source.at(1, 1, 1) = std::numeric_limits<float>::infinity();
    write("nan.exr", nan_source);
    expect_failure(apply_args("nan.exr"), 1, "--source " + path("nan.exr") + ": contains NaN");
    expect_failure(apply_args("missing.png"), 1, path("missing.png") + ": no such file");
    args = apply_args("style.png");
    args[2] = path("style.png");  // not an NNF: 3 channels of colour
    expect_failure(args, 1, "--nnf " + path("style.png"));
    expect_failure({"apply-nnf", "--nnf", path("nnf.exr"), "--source", path("style.png")}, 2,
                   "--patch-size is required");
    expect_failure(with(apply_args("style.png"), {"--vote", "loudly"}), 1,
                   "vote: 'loudly' is invalid");
}

// Missing output folders are created; a file in the way of one is a one-line error.
TEST_F(ApplyNnf, OutputFoldersAreCreated) {
    const CliRun r = run(with(apply_args("style.png"), {"-o", path("new/deeper/again.png")}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("new/deeper/again.png") + "\n");
    EXPECT_EQ(read("new/deeper/again.png").width(), 36);
    std::ofstream(path("blocker")) << "x";
    expect_failure_as_is(with(apply_args("style.png"), {"-o", path("blocker/sub/again.png")}), 1,
                         "--output " + path("blocker/sub/again.png") + ": cannot create folder \"" +
                             path("blocker/sub") + "\": " + path("blocker") +
                             " is a file, not a folder");
}

}  // namespace
}  // namespace exemplar::cli::testing
