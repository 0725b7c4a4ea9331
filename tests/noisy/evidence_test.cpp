// Evidence that the synthesis meets Color Me Noisy's criteria (thesis §4.3.1), measured as in
// §4.4.1.1 on a static reference shown for many frames (so motion compensation is the
// identity): the temporal power spectrum is flat (white noise), the temporal energy rises with
// the low-pass strength f, every frame keeps the reference's low frequencies (coarse
// consistency), and a per-pixel noise map lowers the noise only where it is low.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "exemplar/core/check.hpp"
#include "exemplar/noisy/noisy.hpp"
#include "procedural.hpp"

namespace exemplar::noisy {
namespace {

// Frames of 64x64 from a 128x128 medium. Patches of 5 (the chapter's 7 at its ~1 Mpix frames):
// at these sizes a low-pass of strength f turns a patch into 5f frame pixels, and the shapes
// must stay larger than that for the coarse levels to find matching source patches.
constexpr int kSize = 64;
constexpr int kPatch = 5;

const Image& source() {
    static const Image image = testing::medium(2 * kSize, 2 * kSize);
    return image;
}

const Image& reference() {
    static const Image image = testing::cel(kSize, kSize, 28, 24, 16);
    return image;
}

// Frames 0..count-1 of the static reference at strength f with an optional noise map named
// `map_name` (cached: several tests share them; a longer cached run serves shorter requests).
std::vector<Image> frames(float noise, int count, const Image& noise_map = {},
                          const std::string& map_name = "",
                          float coarse_weight = NoisyOptions{}.coarse_weight) {
    static std::map<std::tuple<float, std::string, float>, std::vector<Image>> cache;
    std::vector<Image>& out = cache[{noise, map_name, coarse_weight}];
    if (static_cast<int>(out.size()) >= count) return {out.begin(), out.begin() + count};
    out.clear();
    NoisyOptions options;
    options.noise = noise;
    options.patch_size = kPatch;
    options.coarse_weight = coarse_weight;
    // Half the chapter's EM and PatchMatch iterations keep the ~100 frames of these tests to
    // seconds; the criteria concern the pyramid and the randomization, not the convergence.
    options.em_iterations = 2;
    options.search_iterations = 4;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < count; ++i) {
        Result<Image> frame =
            synthesize_frame(source(), NoisyFrame{reference(), noise_map, {}, {}}, options, i, {});
        EXEMPLAR_CHECK(frame.ok());
        out.push_back(std::move(frame.value()));
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("f = %g: %d frames of %dx%d in %.2f s (%.3f s per frame)\n", noise, count, kSize,
                kSize, seconds, seconds / count);
    return out;
}

// Average temporal power spectrum |F(q)|^2 over pixels and channels, bins 0..N/2.
std::vector<double> temporal_spectrum(const std::vector<Image>& seq) {
    const int n = static_cast<int>(seq.size());
    std::vector<double> power(static_cast<std::size_t>(n / 2 + 1), 0.0);
    const Image& first = seq.front();
    long count = 0;
    std::vector<double> signal(static_cast<std::size_t>(n));
    for (int y = 0; y < first.height(); ++y) {
        for (int x = 0; x < first.width(); ++x) {
            for (int c = 0; c < first.channels(); ++c) {
                for (int i = 0; i < n; ++i)
                    signal[static_cast<std::size_t>(i)] = seq[i].at(x, y, c);
                for (int k = 0; k <= n / 2; ++k) {
                    std::complex<double> sum = 0.0;
                    for (int i = 0; i < n; ++i) {
                        sum += signal[static_cast<std::size_t>(i)] *
                               std::polar(1.0, -2.0 * std::numbers::pi * k * i / n);
                    }
                    power[static_cast<std::size_t>(k)] += std::norm(sum) / n;
                }
                ++count;
            }
        }
    }
    for (double& p : power) p /= static_cast<double>(count);
    return power;
}

// Worst over frames of ||h_f * T_i - h_f * R|| (RMS), and the reference's own contrast at that
// scale, ||h_f * R - mean||.
std::pair<double, double> low_pass_distance(const std::vector<Image>& seq, double f) {
    const Image target_low = low_pass(reference(), f, LowPassFilter::Box, 1);
    double worst = 0.0;
    for (const Image& frame : seq) {
        worst = std::max(
            worst, testing::rms_difference(low_pass(frame, f, LowPassFilter::Box, 1), target_low));
    }
    return {worst, testing::rms_difference(target_low, testing::uniform_like(target_low))};
}

TEST(NoisyEvidence, TemporalSpectrumIsFlatOver32Frames) {
    // f = 3; 32 frames give 16 non-zero temporal frequencies.
    const std::vector<double> power = temporal_spectrum(frames(3.0f, 32));
    double mean = 0.0;
    for (std::size_t k = 1; k < power.size(); ++k) mean += power[k];
    mean /= static_cast<double>(power.size() - 1);
    double worst = 0.0;
    for (std::size_t k = 1; k < power.size(); ++k) {
        worst = std::max(worst, std::abs(power[k] / mean - 1.0));
        std::printf("bin %2zu: %.3e (%.2f of the mean)\n", k, power[k], power[k] / mean);
    }
    // White noise: every non-zero temporal frequency carries the mean power within 30%
    // (measured: 0.88..1.17 of the mean). The frames are independent draws, so the spectrum is
    // flat in expectation; the tolerance is the estimate's spread with a few hundred
    // independent patches per frame.
    EXPECT_LT(worst, 0.3);
    EXPECT_GT(mean, 0.0);
}

TEST(NoisyEvidence, TemporalEnergyRisesWithTheStrength) {
    double previous = 0.0;
    for (float f : {1.0f, 2.0f, 3.0f, 4.0f, 6.0f, 8.0f}) {
        const double energy = testing::temporal_energy(frames(f, 6));
        std::printf("f = %g: temporal energy %.3e\n", f, energy);
        EXPECT_GT(energy, previous) << "f = " << f;
        previous = energy;
    }
}

TEST(NoisyEvidence, EveryFrameKeepsTheReferencesLowFrequencies) {
    // Coarse consistency (eq. 4.2): every frame's low-pass at strength f is close to the
    // reference's, relative to the reference's own contrast at that scale. Measured with the
    // default coarse-consistency guide (coarse-weight 0.5): 0.25 (f = 2) and 0.22 (f = 3) of the
    // contrast on these 64x64 frames; with the chapter's algorithm (coarse-weight 0, eq. 4.2
    // only through the coarsest level's start) 0.39 and 0.42: the levels after the start drift
    // away from it.
    for (float f : {2.0f, 3.0f}) {
        const auto [worst, contrast] = low_pass_distance(frames(f, f == 3.0f ? 32 : 6), f);
        const auto [chapter_worst, chapter_contrast] =
            low_pass_distance(frames(f, 6, {}, "", 0.0f), f);
        std::printf(
            "f = %g: worst low-pass RMS difference %.4f (coarse-weight 0: %.4f), reference "
            "contrast %.4f\n",
            f, worst, chapter_worst, contrast);
        EXPECT_LT(worst, 0.3 * contrast) << "f = " << f;
        EXPECT_LT(chapter_worst, 0.5 * contrast) << "f = " << f;
        EXPECT_LT(worst, 0.75 * chapter_worst) << "f = " << f;
    }
}

TEST(NoisyEvidence, ZeroNoiseMapKeepsTheReferencesLowFrequencies) {
    // f = 8 everywhere but a noise map of 0: every pixel starts on the finest level from the
    // reference itself, so the low frequencies are the reference's (tighter than f = 8
    // without the map, which redraws them) and the temporal energy is that of f = 1.
    const Image zero(kSize, kSize, 1, 0.0f);
    const std::vector<Image> mapped = frames(8.0f, 6, zero, "zero");
    const auto [mapped_worst, contrast] = low_pass_distance(mapped, 4.0);
    const auto [free_worst, free_contrast] = low_pass_distance(frames(8.0f, 6), 4.0);
    std::printf("h_4 distance: map 0 %.4f, no map %.4f, contrast %.4f\n", mapped_worst, free_worst,
                contrast);
    EXPECT_LT(mapped_worst, 0.2 * contrast);  // measured 0.14
    EXPECT_LT(mapped_worst, 0.5 * free_worst);
    const double energy = testing::temporal_energy(mapped);
    const double energy_f1 = testing::temporal_energy(frames(1.0f, 6));
    std::printf("temporal energy: map 0 %.3e, f = 1 %.3e\n", energy, energy_f1);
    EXPECT_NEAR(energy / energy_f1, 1.0, 0.35);
}

TEST(NoisyEvidence, NoiseMapLowersTheNoiseOnlyWhereItIsLow) {
    // Map 0 on the left half, 1 on the right; f = 6. Compared over the left and right thirds
    // (away from the seam) with f = 6 everywhere and with f = 1 (the least noise there is):
    // the left falls to the energy of f = 1 (measured 1.13x of it; 16% of the uniform run's),
    // the right keeps several times the left's and most of the uniform run's (measured 67%;
    // 40% without the coarse-consistency guide: on 64x64 frames the coarse levels of f = 6 are
    // 11-20 px wide, so every patch there overlaps the half held at the reference).
    Image half(kSize, kSize, 1, 1.0f);
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize / 2; ++x) half.at(x, y, 0) = 0.0f;
    }
    const std::vector<Image> mapped = frames(6.0f, 6, half, "half");
    const std::vector<Image> uniform = frames(6.0f, 6);
    const int third = kSize / 3;
    const double mapped_left = testing::temporal_energy(mapped, 0, 0, third, kSize);
    const double mapped_right = testing::temporal_energy(mapped, kSize - third, 0, kSize, kSize);
    const double uniform_left = testing::temporal_energy(uniform, 0, 0, third, kSize);
    const double uniform_right = testing::temporal_energy(uniform, kSize - third, 0, kSize, kSize);
    const double least_left = testing::temporal_energy(frames(1.0f, 6), 0, 0, third, kSize);
    std::printf("energy left/right: map %.3e / %.3e, uniform %.3e / %.3e, f = 1 left %.3e\n",
                mapped_left, mapped_right, uniform_left, uniform_right, least_left);
    EXPECT_LT(mapped_left, 1.35 * least_left);
    EXPECT_LT(mapped_left, 0.25 * uniform_left);
    EXPECT_GT(mapped_right, 4.0 * mapped_left);
    EXPECT_GT(mapped_right, 0.5 * uniform_right);
}

}  // namespace
}  // namespace exemplar::noisy
