// LazyFluids frame synthesis: uniform usage per segment, the alpha follows the target, the
// temporal term, determinism, input errors.

#include "exemplar/fluid/lazy_fluids.hpp"

#include <gtest/gtest.h>

#include <map>

#include "exemplar/core/check.hpp"
#include "exemplar/filters/measures.hpp"
#include "fluid_scene.hpp"

namespace exemplar::fluid {
namespace {

using test::ellipse_alpha;
using test::fire_exemplar;
using test::uniform_motion;

FluidOptions small_options() {
    FluidOptions o;
    o.blur_radius_px = 2.0f;  // small images
    return o;
}

double alpha_iou(const Image& rgba, const Image& alpha) {
    int both = 0, either = 0;
    for (int y = 0; y < alpha.height(); ++y) {
        for (int x = 0; x < alpha.width(); ++x) {
            const bool a = rgba.at(x, y, 3) > 0.5f, b = alpha.at(x, y, 0) > 0.5f;
            both += a && b;
            either += a || b;
        }
    }
    return either == 0 ? 1.0 : static_cast<double>(both) / either;
}

TEST(LazyFluids, SegmentsBoundaryAndInteriorByTheBlurredAlpha) {
    const Image alpha = ellipse_alpha(60, 50, 30, 25, 16, 12);
    const Image labels = segment(alpha, small_options());
    EXPECT_EQ(labels.at(30, 25, 0), kInterior);
    EXPECT_EQ(labels.at(46, 25, 0), kBoundary);  // on the rim
    EXPECT_EQ(labels.at(2, 2, 0), kOutside);
}

TEST(LazyFluids, EveryExemplarPatchIsUsedKOrKPlusOneTimesPerSegment) {
    const Image exemplar = fire_exemplar(36);
    const Image alpha = ellipse_alpha(96, 80, 48, 40, 36, 28);
    FluidFrameInput in;
    in.exemplar = &exemplar;
    in.target_alpha = &alpha;
    auto result = synthesize_fluid_frame(in, small_options(), RunContext(2));
    ASSERT_TRUE(result.ok()) << result.status().message();
    const Nnf& nnf = result->nnf;
    const int r = small_options().patch_size / 2;
    // Usage per source patch, counted over the target patches inside the frame (those over the
    // border take plain nearest neighbours, docs/algorithms.md).
    const Image& sl = result->source_segments;
    const Image& tl = result->target_segments;
    std::map<int, int> targets, sources;
    std::vector<int> used(static_cast<std::size_t>(sl.width()) * sl.height(), 0);
    for (int y = r; y < nnf.height() - r; ++y) {
        for (int x = r; x < nnf.width() - r; ++x) {
            const Match& m = nnf.at(x, y);
            const int seg = static_cast<int>(tl.at(x, y, 0));
            if (m.x < 0 || seg == kOutside) continue;
            ASSERT_EQ(static_cast<int>(sl.at(m.x, m.y, 0)), seg) << "at " << x << "," << y;
            ++targets[seg];
            ++used[static_cast<std::size_t>(m.y) * sl.width() + m.x];
        }
    }
    for (int y = r; y < sl.height() - r; ++y) {
        for (int x = r; x < sl.width() - r; ++x) ++sources[static_cast<int>(sl.at(x, y, 0))];
    }
    for (int seg : {kBoundary, kInterior}) {
        ASSERT_GT(sources[seg], 0);
        const int K = targets[seg] / sources[seg];
        int below = 0, above = 0, exact_plus_one = 0;
        for (int y = r; y < sl.height() - r; ++y) {
            for (int x = r; x < sl.width() - r; ++x) {
                if (static_cast<int>(sl.at(x, y, 0)) != seg) continue;
                const int u = used[static_cast<std::size_t>(y) * sl.width() + x];
                below += u < K;
                above += u > K + 1;
                exact_plus_one += u == K + 1;
            }
        }
        std::printf("segment %d: %d targets, %d sources, K = %d, K+1 used by %d\n", seg,
                    targets[seg], sources[seg], K, exact_plus_one);
        EXPECT_GE(K, 1);
        EXPECT_EQ(below, 0) << "segment " << seg;
        EXPECT_EQ(above, 0) << "segment " << seg;
        EXPECT_EQ(exact_plus_one, targets[seg] - K * sources[seg]) << "segment " << seg;
    }
}

TEST(LazyFluids, OutputAlphaFollowsTheTargetAlpha) {
    const Image exemplar = fire_exemplar(36);
    const Image alpha = ellipse_alpha(96, 72, 44, 36, 30, 22);
    FluidFrameInput in;
    in.exemplar = &exemplar;
    in.target_alpha = &alpha;
    auto result = synthesize_fluid_frame(in, small_options(), RunContext(2));
    ASSERT_TRUE(result.ok()) << result.status().message();
    const double iou = alpha_iou(result->rgba, alpha);
    std::printf("alpha IoU %.3f\n", iou);
    EXPECT_GE(iou, 0.9);
    EXPECT_EQ(result->rgba.at(1, 1, 3), 0.0f);  // outside the fluid: transparent
}

// Mean squared RGBA difference (premultiplied) between `a` and `b` where either has fluid.
double fluid_difference(const Image& a, const Image& b_premultiplied) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < a.height(); ++y) {
        for (int x = 0; x < a.width(); ++x) {
            const float aa = a.at(x, y, 3);
            if (aa < 0.5f && b_premultiplied.at(x, y, 3) < 0.5f) continue;
            for (int c = 0; c < 4; ++c) {
                const float va = c < 3 ? a.at(x, y, c) * aa : aa;
                const double d = va - b_premultiplied.at(x, y, c);
                sum += d * d;
            }
            ++n;
        }
    }
    return sum / std::max(n, 1);
}

// Frames of an ellipse moving 2 px right and 1 px up per frame; returns the mean difference
// between each output frame and the previous output advected to it.
double moving_ellipse_error(float temporal_weight, int frames) {
    const Image exemplar = fire_exemplar(36);
    const Image motion = uniform_motion(96, 72, 2.0f, -1.0f);
    FluidOptions options = small_options();
    options.temporal_weight = temporal_weight;
    Image previous;
    double total = 0.0;
    for (int t = 0; t < frames; ++t) {
        const Image alpha = ellipse_alpha(96, 72, 36.0f + 2.0f * static_cast<float>(t),
                                          40.0f - static_cast<float>(t), 24, 18);
        FluidFrameInput in;
        in.exemplar = &exemplar;
        in.target_alpha = &alpha;
        if (t > 0) {
            in.previous_output = &previous;
            in.previous_motion = &motion;
        }
        auto result = synthesize_fluid_frame(in, options, RunContext(2));
        EXEMPLAR_CHECK(result.ok());
        if (t > 0) {
            // The previous frame carried along the motion (premultiplied).
            Image carried = advect_along_motion(previous, motion);
            for (std::size_t i = 0; i + 3 < carried.size(); i += 4) {
                for (int c = 0; c < 3; ++c) carried.data()[i + c] *= carried.data()[i + 3];
            }
            total += fluid_difference(result->rgba, carried);
        }
        previous = std::move(result->rgba);
    }
    return total / (frames - 1);
}

TEST(LazyFluids, TemporalTermLowersTheChangeAlongTheMotion) {
    const double without = moving_ellipse_error(0.0f, 4);
    const double with = moving_ellipse_error(0.2f, 4);
    std::printf("mean squared change along the motion: lambda 0.2 %.5f, lambda 0 %.5f\n", with,
                without);
    EXPECT_LT(with, 0.7 * without);
}

TEST(LazyFluids, EmittersGetNoTemporalWeight) {
    // The previous frame had fluid on the left only; the new frame adds a blob on the right.
    const Image before = ellipse_alpha(64, 48, 18, 24, 10, 10);
    Image now = before;
    const Image added = ellipse_alpha(64, 48, 46, 24, 10, 10);
    for (std::size_t i = 0; i < now.size(); ++i) {
        now.data()[i] = std::max(now.data()[i], added.data()[i]);
    }
    const Image map = temporal_weight_map(now, before);
    EXPECT_FLOAT_EQ(map.at(18, 24, 0), 1.0f);  // fluid in both frames: full λ
    EXPECT_FLOAT_EQ(map.at(46, 24, 0), 0.0f);  // new fluid: λ = 0
    EXPECT_FLOAT_EQ(map.at(2, 2, 0), 1.0f);    // empty in both
}

TEST(LazyFluids, SameBytesForOneAndTwoThreads) {
    const Image exemplar = fire_exemplar(32);
    const Image a0 = ellipse_alpha(64, 56, 30, 28, 18, 14);
    const Image a1 = ellipse_alpha(64, 56, 32, 27, 18, 14);
    const Image motion = uniform_motion(64, 56, 2.0f, -1.0f);
    auto run = [&](int threads) {
        FluidFrameInput in;
        in.exemplar = &exemplar;
        in.target_alpha = &a0;
        auto first = synthesize_fluid_frame(in, small_options(), RunContext(threads));
        EXEMPLAR_CHECK(first.ok());
        in.target_alpha = &a1;
        in.previous_output = &first->rgba;
        in.previous_motion = &motion;
        auto second = synthesize_fluid_frame(in, small_options(), RunContext(threads));
        EXEMPLAR_CHECK(second.ok());
        return std::move(second->rgba);
    };
    const Image one = run(1), two = run(2);
    EXPECT_TRUE(std::equal(one.data().begin(), one.data().end(), two.data().begin()));
}

TEST(LazyFluids, RotatedCopiesAndMotionBlurRun) {
    const Image exemplar = fire_exemplar(28);
    const Image atlas = rotation_atlas(exemplar, 6);
    EXPECT_EQ(atlas.width(), 4 * 28 + 3 * 6);
    EXPECT_EQ(atlas.height(), 28);
    // The 90° copy's top-left pixel is the exemplar's top-right one (counter-clockwise turn).
    for (int c = 0; c < 4; ++c) EXPECT_EQ(atlas.at(28 + 6, 0, c), exemplar.at(27, 0, c));

    const Image alpha = ellipse_alpha(80, 64, 40, 32, 26, 20);
    const Image motion = uniform_motion(80, 64, 6.0f, 0.0f);
    FluidOptions options = small_options();
    options.rotations = true;
    options.motion_blur = 0.5f;
    FluidFrameInput in;
    in.exemplar = &exemplar;
    in.target_alpha = &alpha;
    in.motion = &motion;
    auto result = synthesize_fluid_frame(in, options, RunContext(2));
    ASSERT_TRUE(result.ok()) << result.status().message();
    EXPECT_GE(alpha_iou(result->rgba, alpha), 0.85);
    options.motion_blur = 0.0f;
    auto sharp = synthesize_fluid_frame(in, options, RunContext(2));
    ASSERT_TRUE(sharp.ok());
    // Blur along x removes horizontal detail: less gradient energy.
    EXPECT_LT(gradient_energy(result->rgba), gradient_energy(sharp->rgba));
}

TEST(LazyFluids, RejectsBadInput) {
    const Image exemplar = fire_exemplar(32);
    const Image alpha = ellipse_alpha(64, 48, 30, 24, 16, 12);
    const Image wrong_motion = uniform_motion(60, 48, 1.0f, 0.0f);
    Image previous(64, 48, 4);
    FluidFrameInput in;
    in.exemplar = &exemplar;
    in.target_alpha = &alpha;
    in.previous_output = &previous;
    in.previous_motion = &wrong_motion;
    auto r = synthesize_fluid_frame(in, small_options());
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().message(), "previous motion is 60x48 but the target alpha is 64x48");

    Image opaque_nothing(32, 32, 4);  // alpha 0 everywhere
    FluidFrameInput empty;
    empty.exemplar = &opaque_nothing;
    empty.target_alpha = &alpha;
    auto e = synthesize_fluid_frame(empty, small_options());
    ASSERT_FALSE(e.ok());
    EXPECT_NE(e.status().message().find("exemplar: no pixel has alpha"), std::string::npos);

    FluidOptions bad = small_options();
    bad.boundary_high = 0.05f;
    EXPECT_NE(validate(bad).message().find("boundary-high"), std::string::npos);
}

}  // namespace
}  // namespace exemplar::fluid
