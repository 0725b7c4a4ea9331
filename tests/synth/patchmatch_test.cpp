#include "patchmatch.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "level_builder.hpp"
#include "test_images.hpp"

namespace exemplar::synth {
namespace {

struct Fixture {
    SynthesisInput in;
    SynthesisOptions opt;
    Level L;
};

Fixture make(int sw, int sh, int tw, int th, std::uint64_t seed) {
    Fixture f;
    // The target shows the same kind of content as the source, shifted and with its own noise
    // (an analogy, as in real use), so there are good matches but no exact ones.
    f.in.style = testing::texture(sw, sh, 3, seed, 0.1f);
    GuidePair g;
    g.source = testing::texture(sw, sh, 1, seed + 1, 0.1f);
    g.target = testing::texture(tw, th, 1, seed + 1, 0.1f, 9, 4, 77);
    f.in.guides.push_back(g);
    LevelBuilder builder(f.in, f.opt, 1, 1);
    f.L = builder.build(0);
    set_target_style(f.L, testing::texture(tw, th, 3, seed, 0.1f, 9, 4, 78));
    return f;
}

double brute_force_energy(const Level& L) {
    double energy = 0.0;
    for (int ty = 0; ty < L.th; ++ty) {
        for (int tx = 0; tx < L.tw; ++tx) {
            if (!L.target_active[L.target_index(tx, ty)]) continue;
            float best = std::numeric_limits<float>::infinity();
            for (int s : L.valid_by_group[0]) {
                best = std::min(best, patch_distance_reference(L, tx, ty, s % L.sw, s / L.sw, 0));
            }
            energy += best;
        }
    }
    return energy;
}

Nnf run(const Level& L, int iterations, int threads, std::uint64_t key) {
    ForwardProblem problem{L, L.target_active.data()};
    Nnf nnf(L.tw, L.th);
    for (Match& m : nnf.matches()) m = Match{-1, -1, 0.0f, 0.0f};
    evaluate_field(problem, nnf, key, threads);
    run_patchmatch(problem, nnf, iterations, key + 1, threads);
    return nnf;
}

TEST(PatchMatch, ReachesBruteForceEnergyWithinOnePercent) {
    const Fixture f = make(40, 36, 30, 28, 11);
    const double exact = brute_force_energy(f.L);
    const Nnf nnf = run(f.L, 6, 2, 5);  // StyLit's 6 iterations
    double energy = 0.0;
    for (std::size_t i = 0; i < nnf.pixel_count(); ++i) {
        if (f.L.target_active[i]) energy += nnf[i].error;
    }
    EXPECT_LE(energy, exact * 1.01) << "exact " << exact;
    EXPECT_GE(energy, exact * (1.0 - 1e-5));
}

TEST(PatchMatch, NeverIncreasesAnyPixelsError) {
    const Fixture f = make(32, 32, 24, 24, 21);
    ForwardProblem problem{f.L, f.L.target_active.data()};
    Nnf nnf(f.L.tw, f.L.th);
    for (Match& m : nnf.matches()) m = Match{-1, -1, 0.0f, 0.0f};
    evaluate_field(problem, nnf, 3, 1);
    for (int it = 0; it < 4; ++it) {
        const Nnf before = nnf;
        run_patchmatch(problem, nnf, 1, 100 + it, 1);
        for (std::size_t i = 0; i < nnf.pixel_count(); ++i) {
            if (!f.L.target_active[i]) continue;
            ASSERT_LE(nnf[i].error, before[i].error);
            // The stored error is the true distance of the stored match.
            ASSERT_NEAR(
                nnf[i].error,
                patch_distance_reference(f.L, static_cast<int>(i % f.L.tw),
                                         static_cast<int>(i / f.L.tw), nnf[i].x, nnf[i].y, 0.0f),
                1e-4f);
        }
    }
}

TEST(PatchMatch, IdenticalForAnyThreadCount) {
    const Fixture f = make(50, 40, 45, 37, 31);
    const Nnf a = run(f.L, 4, 1, 9);
    for (int threads : {2, 3}) {
        const Nnf b = run(f.L, 4, threads, 9);
        for (std::size_t i = 0; i < a.pixel_count(); ++i) {
            ASSERT_EQ(a[i].x, b[i].x);
            ASSERT_EQ(a[i].y, b[i].y);
            ASSERT_EQ(a[i].error, b[i].error);
        }
    }
}

// upsample_nnf's tables and integer rounding against its definition written per pixel: the
// nearest coarse pixel, the offset within it rotated with the match, std::lround. Rotated and
// unrotated matches, no-match entries, halves (2x) and odd ratios, up and down in source size;
// on 1 and 3 threads (rows in parallel).
TEST(UpsampleNnf, EqualsThePerPixelDefinition) {
    Nnf coarse(13, 9);
    for (int y = 0; y < coarse.height(); ++y) {
        for (int x = 0; x < coarse.width(); ++x) {
            const int k = x * 7 + y * 3;
            const float angle = k % 3 == 0 ? 0.0f : k % 3 == 1 ? 0.7f * (k % 5) : -2.1f;
            coarse.at(x, y) = k % 11 == 0 ? Match{-1, -1, 0.0f, 0.0f}
                                          : Match{(k * 5) % 20, (k * 3) % 15, angle, 0.0f};
        }
    }
    for (const auto& [fw, fh, cdw, cdh, fdw, fdh] :
         {std::array{26, 18, 20, 15, 40, 30}, std::array{31, 20, 20, 15, 47, 33},
          std::array{13, 9, 20, 15, 20, 15}, std::array{27, 19, 21, 16, 43, 31}}) {
        for (const int threads : {1, 3}) {
            const Nnf fine = upsample_nnf(coarse, cdw, cdh, fw, fh, fdw, fdh, threads);
            for (int y = 0; y < fh; ++y) {
                for (int x = 0; x < fw; ++x) {
                    const double u = (x + 0.5) * (static_cast<double>(coarse.width()) / fw) - 0.5;
                    const double v = (y + 0.5) * (static_cast<double>(coarse.height()) / fh) - 0.5;
                    const int cx =
                        std::clamp(static_cast<int>(std::lround(u)), 0, coarse.width() - 1);
                    const int cy =
                        std::clamp(static_cast<int>(std::lround(v)), 0, coarse.height() - 1);
                    const Match& m = coarse.at(cx, cy);
                    const Match& o = fine.at(x, y);
                    if (m.x < 0) {
                        ASSERT_EQ(o.x, -1);
                        continue;
                    }
                    const double du = u - cx, dv = v - cy;
                    const double c = std::cos(m.angle_rad), s = std::sin(m.angle_rad);
                    const double su = m.x + c * du - s * dv, sv = m.y + s * du + c * dv;
                    ASSERT_EQ(o.x, std::lround((su + 0.5) * (static_cast<double>(fdw) / cdw) - 0.5))
                        << x << "," << y;
                    ASSERT_EQ(o.y, std::lround((sv + 0.5) * (static_cast<double>(fdh) / cdh) - 0.5))
                        << x << "," << y;
                    ASSERT_EQ(o.angle_rad, m.angle_rad);
                }
            }
        }
    }
}

}  // namespace
}  // namespace exemplar::synth
