// `exemplar fill` runs in-process: the region filled over the canvas (every other pixel kept),
// the free-standing fill without a canvas, and one-line errors naming the file and the problem
// with no output written.

#include <cstring>

#include "cli_fixture.hpp"

namespace exemplar::cli::testing {
namespace {

// A region image: white inside the rectangle [x0, x1) x [y0, y1).
Image rectangle(int w, int h, int x0, int y0, int x1, int y1) {
    Image im(w, h, 1);
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) im.at(x, y, 0) = 1.0f;
    }
    return im;
}

TEST_F(Cli, FillFillsTheTargetRegionOverTheCanvas) {
    write("palette.png", texture(64, 48, 3, 5));
    write("source.png", rectangle(64, 48, 4, 4, 40, 40));
    write("canvas.png", texture(80, 60, 3, 9));
    write("target.png", rectangle(80, 60, 20, 15, 60, 45));
    const CliRun r =
        run({"fill", "--palette", path("palette.png"), "--source-region", path("source.png"),
             "--target-region", path("target.png"), "--canvas", path("canvas.png"), "-o",
             path("out/filled.png"), "--threads", "2", "--rotations", "3"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("out/filled.png") + "\n");
    const Image out = read("out/filled.png");
    const Image canvas = read("canvas.png");
    ASSERT_TRUE(out.same_size(canvas));
    ASSERT_EQ(out.channels(), 3);
    int changed_inside = 0;
    for (int y = 0; y < 60; ++y) {
        for (int x = 0; x < 80; ++x) {
            const bool inside = x >= 20 && x < 60 && y >= 15 && y < 45;
            const bool same =
                std::memcmp(out.pixel(x, y), canvas.pixel(x, y), 3 * sizeof(float)) == 0;
            if (!inside) {
                ASSERT_TRUE(same) << x << ", " << y;
            } else if (!same) {
                ++changed_inside;
            }
        }
    }
    EXPECT_GT(changed_inside, 1000);
}

TEST_F(Cli, FillWithoutACanvasIsTransparentOutsideTheRegion) {
    write("palette.png", texture(64, 48, 3, 5));
    write("source.png", rectangle(64, 48, 4, 4, 40, 40));
    write("target.png", rectangle(50, 40, 10, 10, 40, 30));
    const CliRun r =
        run({"fill", "--palette", path("palette.png"), "--source-region", path("source.png"),
             "--target-region", path("target.png"), "-o", path("filled.png"), "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    const Image out = read("filled.png");
    ASSERT_EQ(out.channels(), 4);
    EXPECT_EQ(out.at(5, 5, 3), 0.0f);
    EXPECT_EQ(out.at(20, 20, 3), 1.0f);
}

TEST_F(Cli, FillRejectsBadInputs) {
    write("palette.png", texture(64, 48, 3, 5));
    write("source.png", rectangle(64, 48, 4, 4, 40, 40));
    write("canvas.png", texture(80, 60, 3, 9));
    write("target.png", rectangle(80, 60, 20, 15, 60, 45));
    write("small_source.png", rectangle(64, 48, 4, 4, 8, 40));
    write("empty_source.png", rectangle(64, 48, 0, 0, 0, 0));
    write("empty_target.png", rectangle(80, 60, 0, 0, 0, 0));
    write("wrong_size.png", rectangle(30, 30, 0, 0, 10, 10));
    auto args = [&](const std::string& source, const std::string& target,
                    const std::string& canvas) {
        return std::vector<std::string>{
            "fill",       "--palette",       path("palette.png"), "--source-region",
            path(source), "--target-region", path(target),        "--canvas",
            path(canvas)};
    };
    expect_failure(args("wrong_size.png", "target.png", "canvas.png"), 1,
                   "--source-region " + path("wrong_size.png") + ": is 30x30 but --palette " +
                       path("palette.png") + " is 64x48");
    expect_failure(args("source.png", "wrong_size.png", "canvas.png"), 1,
                   "wrong_size.png: is 30x30 but --canvas " + path("canvas.png") + " is 80x60");
    expect_failure(args("empty_source.png", "target.png", "canvas.png"), 1,
                   "--source-region " + path("empty_source.png") + ": selects no pixel");
    expect_failure(args("source.png", "empty_target.png", "canvas.png"), 1,
                   "--target-region " + path("empty_target.png") + ": selects no pixel");
    expect_failure(args("small_source.png", "target.png", "canvas.png"), 1,
                   "small_source.png: holds no 5x5 patch (smaller than the patch size)");
    expect_failure(args("source.png", "target.png", "missing.png"), 1, "missing.png");
    expect_failure(args("missing.png", "target.png", "canvas.png"), 1, "missing.png");
    std::vector<std::string> bad_usage = args("source.png", "target.png", "canvas.png");
    bad_usage.insert(bad_usage.end(), {"--usage", "often"});
    expect_failure(bad_usage, 1, "--usage: 'often' is invalid");
    std::vector<std::string> bad_patch = args("source.png", "target.png", "canvas.png");
    bad_patch.insert(bad_patch.end(), {"--patch-size", "4"});
    expect_failure(bad_patch, 1, "patch-size: 4 is invalid (must be odd, 3..31)");
}

}  // namespace
}  // namespace exemplar::cli::testing
