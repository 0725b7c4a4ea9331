// The wash-out of §5.3 and its cure: over a 60-frame simulated plume, plain nearest-neighbour
// search (Kwatra et al. 2005, with the temporal term) settles on the exemplar's smoothest
// patches, while uniform usage keeps several times more of the exemplar's texture, with no
// downward trend over the frames. (Measured: nearest neighbours are washed out already in the
// first frame's EM iterations, so there is no frame-by-frame decline to see here; uniform usage
// keeps 0.3-0.55 of the exemplar's gradient energy, not the 0.9-1.1: the final vote
// averages the scattered matches of the uniform assignment. docs/fluid.md.)

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "exemplar/fluid/lazy_fluids.hpp"
#include "exemplar/fluid/simulate.hpp"
#include "fluid_scene.hpp"

namespace exemplar::fluid {
namespace {

// Mean squared forward difference of the luminance over pixel pairs that are both opaque
// (alpha ≥ 0.9): the texture of the fluid's interior, independent of its outline.
double interior_gradient_energy(const Image& rgba) {
    auto luma = [&](int x, int y) {
        return 0.299 * rgba.at(x, y, 0) + 0.587 * rgba.at(x, y, 1) + 0.114 * rgba.at(x, y, 2);
    };
    auto opaque = [&](int x, int y) { return rgba.at(x, y, 3) >= 0.9f; };
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y + 1 < rgba.height(); ++y) {
        for (int x = 0; x + 1 < rgba.width(); ++x) {
            if (!opaque(x, y)) continue;
            if (opaque(x + 1, y)) {
                sum += std::pow(luma(x + 1, y) - luma(x, y), 2);
                ++n;
            }
            if (opaque(x, y + 1)) {
                sum += std::pow(luma(x, y + 1) - luma(x, y), 2);
                ++n;
            }
        }
    }
    return n == 0 ? 0.0 : sum / n;
}

struct PlumeRun {
    std::vector<double> energy;  // per frame, relative to the exemplar's
};

PlumeRun run_plume(bool uniform, float vote_histogram, const std::vector<Image>& alphas,
                   const std::vector<Image>& motions) {
    const Image exemplar = test::fire_exemplar(32);
    const double reference = interior_gradient_energy(exemplar);
    FluidOptions options;
    options.blur_radius_px = 1.5f;
    options.uniform_usage = uniform;
    options.vote_histogram = vote_histogram;
    PlumeRun run;
    Image previous;
    for (std::size_t t = 0; t < alphas.size(); ++t) {
        FluidFrameInput in;
        in.exemplar = &exemplar;
        in.target_alpha = &alphas[t];
        if (t > 0) {
            in.previous_output = &previous;
            in.previous_motion = &motions[t - 1];
        }
        auto result = synthesize_fluid_frame(in, options, RunContext(2));
        EXPECT_TRUE(result.ok()) << result.status().message();
        if (!result.ok()) return run;
        previous = std::move(result->rgba);
        run.energy.push_back(interior_gradient_energy(previous) / reference);
    }
    return run;
}

double mean(const std::vector<double>& v, std::size_t from, std::size_t to) {
    double s = 0.0;
    for (std::size_t i = from; i < to; ++i) s += v[i];
    return s / static_cast<double>(to - from);
}

TEST(LazyFluidsWashOut, UniformUsageKeepsTheTextureOverASixtyFramePlume) {
    constexpr int kFrames = 60;
    FluidScene scene = plume_scene(48, 64);
    scene.warmup_frames = 20;  // start with a plume, not a puff
    std::vector<Image> alphas, motions;
    ASSERT_TRUE(simulate(
                    scene, kFrames,
                    [&](int, const Image& alpha, const Image& motion) {
                        alphas.push_back(alpha);
                        motions.push_back(motion);
                        return Status::ok();
                    },
                    RunContext(2))
                    .is_ok());
    // The paper's comparison (Kwatra et al.'s nearest neighbours against uniform usage, both
    // with the plain vote), then our default: uniform usage with the colour-histogram vote.
    const PlumeRun nearest = run_plume(false, 0.0f, alphas, motions);
    const PlumeRun uniform = run_plume(true, 0.0f, alphas, motions);
    const PlumeRun ours = run_plume(true, FluidOptions{}.vote_histogram, alphas, motions);
    ASSERT_EQ(nearest.energy.size(), static_cast<std::size_t>(kFrames));
    ASSERT_EQ(uniform.energy.size(), static_cast<std::size_t>(kFrames));
    ASSERT_EQ(ours.energy.size(), static_cast<std::size_t>(kFrames));
    std::printf("gradient energy / exemplar's, frames 0, 10, ..., 50, 59:\n");
    for (const auto& [name, run] : {std::pair{"nearest", &nearest}, std::pair{"uniform", &uniform},
                                    std::pair{"default", &ours}}) {
        std::printf("  %s:", name);
        for (int t = 0; t < kFrames; t += 10) std::printf(" %.2f", run->energy[t]);
        std::printf(" %.2f\n", run->energy.back());
    }
    const double mean_nearest = mean(nearest.energy, 0, kFrames);
    const double mean_uniform = mean(uniform.energy, 0, kFrames);
    const double mean_ours = mean(ours.energy, 0, kFrames);
    std::printf("  mean: nearest %.2f, uniform %.2f, default %.2f\n", mean_nearest, mean_uniform,
                mean_ours);
    // Nearest neighbours keep little of the exemplar's texture; uniform usage at least twice as
    // much, and it does not fade over the shot. The histogram vote keeps much more again
    // (measured 0.75 against 0.41), but not the "within 10%" of the exemplar.
    EXPECT_LT(mean_nearest, 0.3);
    EXPECT_GT(mean_uniform, 2.0 * mean_nearest);
    EXPECT_GT(mean(uniform.energy, 40, 60), 0.85 * mean(uniform.energy, 0, 20));
    EXPECT_GT(mean_ours, 1.5 * mean_uniform);
    EXPECT_GT(mean(ours.energy, 40, 60), 0.85 * mean(ours.energy, 0, 20));
    EXPECT_LT(mean_ours, 1.2);  // more texture than the exemplar would be noise, not texture
}

}  // namespace
}  // namespace exemplar::fluid
