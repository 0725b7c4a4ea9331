// `exemplar directions` run in-process: files written, their channels, and
// one-line errors naming the file or parameter.

#include <cmath>

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

}  // namespace
}  // namespace exemplar::cli::testing
