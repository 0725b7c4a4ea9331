// `exemplar flow`: the synthetic FlyingChairs-like pair (tests/data/flow) end to end, and
// one-line errors for bad inputs.

#include "cli_fixture.hpp"
#include "exemplar/io/flow_io.hpp"

namespace exemplar::cli::testing {
namespace {

const std::string kPair = std::string(EXEMPLAR_TEST_DATA_DIR) + "/flow/synthetic-";

TEST_F(Cli, FlowWritesForwardBackwardAndOcclusion) {
    const CliRun r = run({"flow", "--from", kPair + "img0.png", "--to", kPair + "img1.png", "-o",
                          path("fwd.flo"), "--backward", path("bwd.exr"), "--occlusion",
                          path("occ.png"), "--epsilon", "8"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("fwd.flo") + "\n" + path("bwd.exr") + "\n" + path("occ.png") + "\n");
    auto forward = load_flow(path("fwd.flo"));
    auto backward = load_flow(path("bwd.exr"));
    ASSERT_TRUE(forward.ok() && backward.ok());
    EXPECT_EQ(forward->width(), 256);
    EXPECT_EQ(backward->height(), 192);
    const Image occlusion = read("occ.png");
    ASSERT_EQ(occlusion.channels(), 1);
    double occluded = 0.0;
    for (float v : occlusion.data()) occluded += v;
    occluded /= static_cast<double>(occlusion.pixel_count());
    EXPECT_GT(occluded, 0.12);  // 21.2% measured, see tests/video/flow_test.cpp
    EXPECT_LT(occluded, 0.30);
}

TEST_F(Cli, FlowRejectsBadInputs) {
    const std::string a = path("a.png"), b = path("b.png"), out = path("out.flo");
    expect_failure_as_is({"flow", "--from", a, "--to", b, "-o", out}, 1,
                         "--from " + a + " is 32x28 but --to " + b + " is 36x30");
    expect_failure_as_is({"flow", "--from", path("none.png"), "--to", b, "-o", out}, 1,
                         "none.png: no such file");
    expect_failure_as_is({"flow", "--from", a, "--to", a, "-o", out, "--epsilon", "0"}, 1,
                         "--epsilon: 0");
    expect_failure_as_is({"flow", "--from", a, "--to", a, "-o", out, "--preset", "slow"}, 1,
                         "--preset");
    expect_failure_as_is({"flow", "--from", a, "--to", a, "-o", path("out.png")}, 1,
                         "use .flo or .exr");
    expect_failure_as_is({"flow", "--from", a, "--to", a}, 2, "--output");
}

// Missing output folders are created for each of the three outputs; a file in the way of one
// is a one-line error, and nothing is written.
TEST_F(Cli, FlowCreatesOutputFolders) {
    const std::string a = path("a.png");
    const CliRun r =
        run({"flow", "--from", a, "--to", a, "-o", path("f/fwd.flo"), "--backward",
             path("b/deeper/bwd.exr"), "--occlusion", path("o/occ.png"), "--preset", "ultrafast"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(load_flow(path("f/fwd.flo")).ok());
    EXPECT_TRUE(load_flow(path("b/deeper/bwd.exr")).ok());
    EXPECT_EQ(read("o/occ.png").channels(), 1);
    std::ofstream(path("blocker")) << "x";
    expect_failure_as_is({"flow", "--from", a, "--to", a, "-o", path("out.flo"), "--occlusion",
                          path("blocker/occ.png")},
                         1, "--occlusion " + path("blocker/occ.png") + ": cannot create folder");
}

}  // namespace
}  // namespace exemplar::cli::testing
