// The stable-fluids solver: projection leaves no divergence, advection moves a blob along a
// known field, the plume rises and its motion carries its density, determinism.

#include "exemplar/fluid/simulate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "exemplar/core/rng.hpp"

namespace exemplar::fluid {
namespace {

float max_divergence(const MacVelocity& v, const std::vector<std::uint8_t>& solid) {
    float m = 0.0f;
    for (int y = 0; y < v.height; ++y) {
        for (int x = 0; x < v.width; ++x) {
            if (!solid.empty() && solid[static_cast<std::size_t>(y) * v.width + x]) continue;
            m = std::max(m, std::abs(divergence(v, x, y)));
        }
    }
    return m;
}

MacVelocity random_velocity(int w, int h, std::uint64_t seed) {
    MacVelocity v(w, h);
    KeyedRng rng(seed);
    for (float& u : v.u) u = 4.0f * rng.uniform() - 2.0f;
    for (float& x : v.v) x = 4.0f * rng.uniform() - 2.0f;
    return v;
}

TEST(FluidProjection, RemovesTheDivergenceOfARandomField) {
    MacVelocity v = random_velocity(48, 40, 7);
    const float before = max_divergence(v, {});
    ASSERT_GT(before, 1.0f);
    const int iterations = project(v, {}, 1e-5f, 5000, 2);
    const float after = max_divergence(v, {});
    std::printf("max |div| %.3f -> %.2g in %d CG iterations\n", before, after, iterations);
    EXPECT_LT(after, 1e-5f);
    EXPECT_LT(iterations, 5000);
}

TEST(FluidProjection, RespectsSolidCellsAndKeepsThemFlowFree) {
    const int w = 40, h = 32;
    std::vector<std::uint8_t> solid(static_cast<std::size_t>(w) * h, 0);
    for (int y = 10; y < 20; ++y) {
        for (int x = 15; x < 25; ++x) solid[static_cast<std::size_t>(y) * w + x] = 1;
    }
    MacVelocity v = random_velocity(w, h, 3);
    project(v, solid, 1e-5f, 5000, 1);
    EXPECT_LT(max_divergence(v, solid), 1e-5f);
    for (int y = 10; y < 20; ++y) {
        EXPECT_EQ(v.u_at(15, y), 0.0f);  // face entering the solid block
        EXPECT_EQ(v.u_at(25, y), 0.0f);  // face leaving it
    }
    for (int x = 15; x < 25; ++x) {
        EXPECT_EQ(v.v_at(x, 10), 0.0f);
        EXPECT_EQ(v.v_at(x, 20), 0.0f);
    }
}

TEST(FluidProjection, IsTheSameForAnyThreadCount) {
    MacVelocity a = random_velocity(33, 29, 11), b = a;
    project(a, {}, 1e-5f, 5000, 1);
    project(b, {}, 1e-5f, 5000, 2);
    EXPECT_EQ(a.u, b.u);
    EXPECT_EQ(a.v, b.v);
}

// Density-weighted centre of a 1-channel image.
void centroid(const Image& image, double& cx, double& cy, double& mass) {
    cx = cy = mass = 0.0;
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            const double d = image.at(x, y, 0);
            cx += d * x;
            cy += d * y;
            mass += d;
        }
    }
    cx /= mass;
    cy /= mass;
}

TEST(FluidAdvection, BlobMovesAlongAUniformField) {
    const int w = 96, h = 80;
    MacVelocity v(w, h);
    for (float& u : v.u) u = 1.5f;
    for (float& x : v.v) x = -0.75f;
    Image blob(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double r2 = std::pow(x - 30.0, 2) + std::pow(y - 50.0, 2);
            blob.at(x, y, 0) = static_cast<float>(std::exp(-r2 / (2 * 4.0 * 4.0)));
        }
    }
    double x0, y0, m0;
    centroid(blob, x0, y0, m0);
    for (int frame = 0; frame < 20; ++frame) blob = advect(blob, v, 2);
    double x1, y1, m1;
    centroid(blob, x1, y1, m1);
    std::printf("centroid (%.2f, %.2f) -> (%.2f, %.2f), mass %.1f -> %.1f\n", x0, y0, x1, y1, m0,
                m1);
    EXPECT_NEAR(x1 - x0, 30.0, 0.2);
    EXPECT_NEAR(y1 - y0, -15.0, 0.2);
    EXPECT_NEAR(m1 / m0, 1.0, 0.01);  // bilinear resampling spreads, it does not lose mass
}

TEST(FluidAdvection, BlobTurnsWithARigidRotation) {
    // u = −ω (y − cy), v = ω (x − cx): a quarter turn in n frames takes the blob from the right
    // of the centre to below it (y down).
    const int w = 80, h = 80;
    const float cx = 40, cy = 40;
    const int frames = 40;
    const float omega = static_cast<float>(M_PI / 2 / frames);
    MacVelocity v(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x <= w; ++x) v.u_at(x, y) = -omega * (static_cast<float>(y) - cy);
    }
    for (int y = 0; y <= h; ++y) {
        for (int x = 0; x < w; ++x) v.v_at(x, y) = omega * (static_cast<float>(x) - cx);
    }
    Image blob(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double r2 = std::pow(x - 60.0, 2) + std::pow(y - 40.0, 2);
            blob.at(x, y, 0) = static_cast<float>(std::exp(-r2 / (2 * 3.0 * 3.0)));
        }
    }
    for (int f = 0; f < frames; ++f) blob = advect(blob, v, 1);
    double x1, y1, m1;
    centroid(blob, x1, y1, m1);
    std::printf("rotated blob centroid (%.2f, %.2f), expected (40, 60)\n", x1, y1);
    EXPECT_NEAR(x1, 40.0, 1.0);
    EXPECT_NEAR(y1, 60.0, 1.0);
}

TEST(FluidSimulator, PlumeRisesAndItsMotionIsDivergenceFree) {
    const FluidScene scene = plume_scene(64, 96);
    ASSERT_TRUE(validate(scene).is_ok());
    std::vector<int> top_y;
    float worst_divergence = 0.0f;
    const Status s = simulate(
        scene, 40,
        [&](int, const Image& alpha, const Image& motion) {
            EXPECT_EQ(alpha.width(), 64);
            EXPECT_EQ(motion.channels(), 2);
            int top = alpha.height();
            for (int y = alpha.height() - 1; y >= 0; --y) {
                for (int x = 0; x < alpha.width(); ++x) {
                    if (alpha.at(x, y, 0) > 0.1f) top = y;
                }
            }
            top_y.push_back(top);
            for (float a : alpha.data()) EXPECT_TRUE(a >= 0.0f && a <= 1.0f);
            return Status::ok();
        },
        RunContext(2));
    ASSERT_TRUE(s.is_ok()) << s.message();
    FluidSimulator sim(scene);
    for (int f = 0; f < 10; ++f) {
        sim.update_velocity(1);
        worst_divergence = std::max(worst_divergence, max_divergence(sim.velocity(), {}));
        sim.advance_density(1);
    }
    ASSERT_EQ(top_y.size(), 40u);
    std::printf("plume top (alpha > 0.1): frame 0 y = %d, frame 39 y = %d; max |div| %.2g\n",
                top_y.front(), top_y.back(), worst_divergence);
    EXPECT_LT(top_y.back(), top_y.front() - 20);  // it rises (y down)
    EXPECT_LT(worst_divergence, 1.5e-3f);         // the simulator projects to 1e-3 per frame
}

TEST(FluidSimulator, SameFramesForAnyThreadCount) {
    FluidScene scene = plume_scene(48, 48);
    scene.obstacles.push_back({24.0f, 20.0f, 5.0f});
    std::vector<Image> one, two;
    auto collect = [](std::vector<Image>& into) {
        return [&into](int, const Image& alpha, const Image& motion) {
            into.push_back(alpha);
            into.push_back(motion);
            return Status::ok();
        };
    };
    ASSERT_TRUE(simulate(scene, 12, collect(one), RunContext(1)).is_ok());
    ASSERT_TRUE(simulate(scene, 12, collect(two), RunContext(2)).is_ok());
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
        ASSERT_TRUE(std::equal(one[i].data().begin(), one[i].data().end(), two[i].data().begin()))
            << "image " << i;
    }
}

TEST(FluidSimulator, RejectsBadScenes) {
    FluidScene scene = plume_scene(64, 64);
    scene.emitters[0].radius_px = -2.0f;
    const Status s = validate(scene);
    EXPECT_FALSE(s.is_ok());
    EXPECT_NE(s.message().find("emitters[0].radius"), std::string::npos) << s.message();
    scene = plume_scene(4, 64);
    EXPECT_NE(validate(scene).message().find("width"), std::string::npos);
    const Status frames = simulate(plume_scene(16, 16), 0,
                                   [](int, const Image&, const Image&) { return Status::ok(); });
    EXPECT_NE(frames.message().find("frames: 0"), std::string::npos) << frames.message();
}

}  // namespace
}  // namespace exemplar::fluid
