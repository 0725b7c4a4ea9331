// Per-frame coordinate synthesis: determinism, temporal coherence along exact motion,
// orientation, tone reproduction after halftoning.
#include "exemplar/npr/synthesis.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "exemplar/filters/resample.hpp"
#include "exemplar/filters/structure_tensor.hpp"
#include "npr_patterns.hpp"

namespace exemplar::npr {
namespace {

constexpr float kPi = 3.14159265f;

Pattern prepared(const Image& image, int levels = 3) {
    PatternOptions options;
    options.levels = levels;
    Result<Pattern> pattern = prepare_pattern(image, options, 0, 2);
    EXPECT_TRUE(pattern.ok()) << pattern.status().message();
    return std::move(pattern).value();
}

// A frame whose whole content moved by (mx, my) px since the previous frame: exact backward
// flow, the entering strip disoccluded.
FrameInput translating_frame(int width, int height, int mx, int my) {
    FrameInput input;
    input.width = width;
    input.height = height;
    input.backward_flow = Image(width, height, 2);
    input.disocclusion = Image(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            input.backward_flow.at(x, y, 0) = static_cast<float>(-mx);
            input.backward_flow.at(x, y, 1) = static_cast<float>(-my);
            const bool entered = x - mx < 0 || y - my < 0 || x - mx >= width || y - my >= height;
            input.disocclusion.at(x, y, 0) = entered ? 1.0f : 0.0f;
        }
    return input;
}

// Mean |S_t(x) - S_{t-1}(x - m)| over the pixels visible in both frames.
float temporal_error(const Image& previous, const Image& current, int mx, int my) {
    double sum = 0.0;
    int count = 0;
    for (int y = 0; y < current.height(); ++y)
        for (int x = 0; x < current.width(); ++x) {
            const int px = x - mx, py = y - my;
            if (px < 0 || py < 0 || px >= current.width() || py >= current.height()) continue;
            sum += std::fabs(current.at(x, y, 0) - previous.at(px, py, 0));
            ++count;
        }
    return static_cast<float>(sum / count);
}

// Dominant orientation of an image (angle along its stripes, [0, π)) from the mean structure
// tensor of its interior.
float dominant_angle(const Image& image) {
    const Image tensor = structure_tensor(image, {1.0f, 2.0f}, 1);
    Image mean(1, 1, 3);
    int count = 0;
    for (int y = 4; y < image.height() - 4; ++y)
        for (int x = 4; x < image.width() - 4; ++x, ++count)
            for (int c = 0; c < 3; ++c) mean.at(0, 0, c) += tensor.at(x, y, c);
    for (int c = 0; c < 3; ++c) mean.at(0, 0, c) /= static_cast<float>(count);
    return orientation_from_tensor(mean, 1).at(0, 0, 0);
}

float angle_difference(float a, float b) {
    const float d = std::fmod(std::fabs(a - b), kPi);
    return std::min(d, kPi - d);
}

TEST(NprSynthesis, IsBitIdenticalForOneAndTwoThreads) {
    const Pattern pattern = prepared(testing::stipple_pattern(64, 6.0f));
    SynthesisOptions options;
    FrameInput first;
    first.width = 96;
    first.height = 64;
    first.orientation = Image(96, 64, 1, 0.6f);
    FrameInput second = translating_frame(96, 64, 2, 1);
    second.orientation = first.orientation;
    Image screens[2], coords[2];
    for (int t = 0; t < 2; ++t) {
        const RunContext context(t + 1);
        const Result<FrameState> a = synthesize_frame(pattern, first, nullptr, 0, options, context);
        ASSERT_TRUE(a.ok()) << a.status().message();
        const Result<FrameState> b =
            synthesize_frame(pattern, second, &a.value(), 1, options, context);
        ASSERT_TRUE(b.ok()) << b.status().message();
        screens[t] = b->screen;
        coords[t] = b->coords[0];
    }
    EXPECT_TRUE(
        std::equal(screens[0].data().begin(), screens[0].data().end(), screens[1].data().begin()));
    EXPECT_TRUE(
        std::equal(coords[0].data().begin(), coords[0].data().end(), coords[1].data().begin()));
}

// The optimized correction against its scalar reference (SynthesisOptions::reference_kernels):
// the same coordinates at every level, bit for bit, on a first frame and a continuing one with
// a varying orientation (0 on the left third: the unrotated fast path), a fractional, varying
// flow and a disoccluded block; for the default 6 appearance dimensions and for 4.
TEST(NprSynthesis, FastCorrectionMatchesTheScalarReference) {
    for (const int dims : {6, 4}) {
        PatternOptions pattern_options;
        pattern_options.appearance_dims = dims;
        Result<Pattern> pattern =
            prepare_pattern(testing::hatching_pattern(64, 8, 2.5f), pattern_options, 0, 2);
        ASSERT_TRUE(pattern.ok()) << pattern.status().message();
        constexpr int kWidth = 83, kHeight = 61;
        FrameInput first;
        first.width = kWidth;
        first.height = kHeight;
        first.orientation = Image(kWidth, kHeight, 1);
        FrameInput second = translating_frame(kWidth, kHeight, 2, 1);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                first.orientation.at(x, y, 0) =
                    x < kWidth / 3 ? 0.0f : 0.05f * static_cast<float>(x) + 0.03f * y;
                second.backward_flow.at(x, y, 0) = -1.7f + 0.02f * static_cast<float>(y);
                second.backward_flow.at(x, y, 1) = -0.6f - 0.01f * static_cast<float>(x);
                if (x > 40 && x < 52 && y > 20 && y < 30) second.disocclusion.at(x, y, 0) = 1.0f;
            }
        second.orientation = first.orientation;
        FrameState states[2][2];
        for (int reference = 0; reference < 2; ++reference) {
            SynthesisOptions options;
            options.reference_kernels = reference == 1;
            const RunContext context(2);
            Result<FrameState> a = synthesize_frame(*pattern, first, nullptr, 3, options, context);
            ASSERT_TRUE(a.ok()) << a.status().message();
            Result<FrameState> b =
                synthesize_frame(*pattern, second, &a.value(), 4, options, context);
            ASSERT_TRUE(b.ok()) << b.status().message();
            states[reference][0] = std::move(a).value();
            states[reference][1] = std::move(b).value();
        }
        for (int frame = 0; frame < 2; ++frame) {
            const FrameState& fast = states[0][frame];
            const FrameState& reference = states[1][frame];
            ASSERT_EQ(fast.coords.size(), reference.coords.size());
            for (std::size_t l = 0; l < fast.coords.size(); ++l)
                EXPECT_TRUE(std::equal(fast.coords[l].data().begin(), fast.coords[l].data().end(),
                                       reference.coords[l].data().begin()))
                    << "dims " << dims << ", frame " << frame << ", level " << l;
            EXPECT_TRUE(std::equal(fast.screen.data().begin(), fast.screen.data().end(),
                                   reference.screen.data().begin()))
                << "dims " << dims << ", frame " << frame;
        }
    }
}

TEST(NprSynthesis, FollowsExactMotionFarBetterThanIndependentFrames) {
    const Pattern pattern = prepared(testing::stipple_pattern(64, 6.0f));
    SynthesisOptions options;
    const RunContext context(2);
    constexpr int kFrames = 5, kWidth = 96, kHeight = 64, kMx = 2, kMy = 1;
    FrameInput first;
    first.width = kWidth;
    first.height = kHeight;
    const FrameInput moving = translating_frame(kWidth, kHeight, kMx, kMy);
    Result<FrameState> coherent = synthesize_frame(pattern, first, nullptr, 0, options, context);
    Result<FrameState> independent = synthesize_frame(pattern, first, nullptr, 0, options, context);
    ASSERT_TRUE(coherent.ok() && independent.ok());
    double coherent_error = 0.0, independent_error = 0.0;
    for (int t = 1; t < kFrames; ++t) {
        Result<FrameState> next =
            synthesize_frame(pattern, moving, &coherent.value(), t, options, context);
        Result<FrameState> alone = synthesize_frame(pattern, first, nullptr, t, options, context);
        ASSERT_TRUE(next.ok() && alone.ok());
        coherent_error += temporal_error(coherent->screen, next->screen, kMx, kMy);
        independent_error += temporal_error(independent->screen, alone->screen, kMx, kMy);
        coherent = std::move(next);
        independent = std::move(alone);
    }
    coherent_error /= kFrames - 1;
    independent_error /= kFrames - 1;
    RecordProperty("coherent_error", std::to_string(coherent_error));
    RecordProperty("independent_error", std::to_string(independent_error));
    std::printf("temporal error along the motion: coherent %.4f, independent %.4f\n",
                coherent_error, independent_error);
    EXPECT_LT(coherent_error, 0.25 * independent_error);
}

TEST(NprSynthesis, AnisotropicPatternFollowsTheOrientationBuffer) {
    // Horizontal hatching; the output's stripes must turn with the orientation buffer
    const Pattern pattern = prepared(testing::hatching_pattern(64, 8, 2.5f));
    SynthesisOptions options;
    const RunContext context(2);
    for (const float angle : {0.0f, kPi / 4, kPi / 2, 2.0f}) {
        FrameInput input;
        input.width = 96;
        input.height = 64;
        input.orientation = Image(96, 64, 1, angle);
        const Result<FrameState> frame =
            synthesize_frame(pattern, input, nullptr, 0, options, context);
        ASSERT_TRUE(frame.ok()) << frame.status().message();
        const float measured = dominant_angle(frame->screen);
        std::printf("orientation %.3f rad: output stripes at %.3f rad\n", angle, measured);
        EXPECT_LT(angle_difference(measured, angle), 12.0f * kPi / 180.0f) << "angle " << angle;
    }
}

TEST(NprSynthesis, HalftoneReproducesTheToneBetterAfterToneCorrection) {
    const Pattern pattern = prepared(testing::stipple_pattern(64, 5.0f));
    SynthesisOptions options;
    const RunContext context(2);
    FrameInput input;
    input.width = 96;
    input.height = 64;
    const Result<FrameState> frame = synthesize_frame(pattern, input, nullptr, 0, options, context);
    ASSERT_TRUE(frame.ok()) << frame.status().message();
    // Shading: a left-to-right ramp with a darker disc
    Image tone(96, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 96; ++x) {
            const float dx = static_cast<float>(x - 60), dy = static_cast<float>(y - 32);
            tone.at(x, y, 0) = 0.1f + 0.8f * static_cast<float>(x) / 95.0f -
                               (dx * dx + dy * dy < 225.0f ? 0.3f : 0.0f);
            tone.at(x, y, 0) = std::clamp(tone.at(x, y, 0), 0.0f, 1.0f);
        }
    const auto score = [&](bool correction, double& correlation) {
        HalftoneOptions halftone_options;
        halftone_options.tone_correction = correction;
        const Image result = halftone(frame->screen, tone, halftone_options, 1);
        // Measured at another scale than the correction's blur (3 px), not to grade itself
        const Image seen = gaussian_blur(result, 4.0f, 1);
        const Image reference = gaussian_blur(tone, 4.0f, 1);
        double error = 0.0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
        int n = 0;
        for (int y = 6; y < 58; ++y)
            for (int x = 6; x < 90; ++x, ++n) {
                const double a = seen.at(x, y, 0), b = reference.at(x, y, 0);
                error += std::fabs(a - b);
                sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
            }
        const double cov = sab / n - sa / n * sb / n;
        correlation = cov / std::sqrt((saa / n - sa * sa / n / n) * (sbb / n - sb * sb / n / n));
        return error / n;
    };
    double corr_before = 0.0, corr_after = 0.0;
    const double before = score(false, corr_before);
    const double after = score(true, corr_after);
    std::printf("local tone: error %.4f -> %.4f, correlation %.3f -> %.3f\n", before, after,
                corr_before, corr_after);
    EXPECT_GT(corr_before, 0.8);
    EXPECT_GT(corr_after, corr_before);
    EXPECT_LT(after, before);
}

TEST(NprSynthesis, RejectsMismatchedBuffersAndBadOptionsByName) {
    const Pattern pattern = prepared(testing::halftone_pattern(32, 8));
    FrameInput input;
    input.width = 40;
    input.height = 30;
    input.orientation = Image(20, 30, 1);
    const Result<FrameState> bad = synthesize_frame(pattern, input, nullptr, 0, {});
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.status().message().find("orientation: 20x30x1 does not match the frame 40x30"),
              std::string::npos)
        << bad.status().message();
    SynthesisOptions options;
    options.init_patch_size = 2;
    EXPECT_EQ(validate(options).message(), "init_patch_size: 2 is invalid (must be 3..32)");
    HalftoneOptions halftone_options;
    halftone_options.blur_sigma_px = 0.0f;
    EXPECT_FALSE(validate(halftone_options).is_ok());
}

}  // namespace
}  // namespace exemplar::npr

namespace exemplar::npr {
namespace {

// Element size of a screen: the first zero crossing of its radially averaged autocorrelation
// (interpolated, in px), over the central region.
float element_size(const Image& screen) {
    const int margin = 12;
    double mean = 0.0;
    int n = 0;
    for (int y = margin; y < screen.height() - margin; ++y)
        for (int x = margin; x < screen.width() - margin; ++x, ++n) mean += screen.at(x, y, 0);
    mean /= n;
    std::vector<double> sum(13, 0.0);
    std::vector<int> count(13, 0);
    for (int dy = -12; dy <= 12; ++dy)
        for (int dx = -12; dx <= 12; ++dx) {
            const int r = static_cast<int>(std::lround(std::sqrt(dx * dx + dy * dy)));
            if (r > 12) continue;
            for (int y = margin; y < screen.height() - margin; ++y)
                for (int x = margin; x < screen.width() - margin; ++x) {
                    sum[static_cast<std::size_t>(r)] +=
                        (screen.at(x, y, 0) - mean) * (screen.at(x + dx, y + dy, 0) - mean);
                    ++count[static_cast<std::size_t>(r)];
                }
        }
    double previous = 1.0;
    for (int r = 1; r <= 12; ++r) {
        const double value = sum[static_cast<std::size_t>(r)] / count[static_cast<std::size_t>(r)] /
                             (sum[0] / count[0]);
        if (value <= 0.0) return static_cast<float>(r - 1 + previous / (previous - value));
        previous = value;
    }
    return 12.0f;
}

// A camera zoom of 2x about the centre over 6 frames (exact backward flow): the screen of the
// last frame and the texture-mapped baseline (frame 0's screen magnified 2x).
struct ZoomResult {
    Image first, last, mapped;
};

ZoomResult zoom_2x(const Pattern& pattern, const SynthesisOptions& options) {
    const RunContext context(2);
    constexpr int kFrames = 6, kWidth = 128, kHeight = 96;
    const float cx = (kWidth - 1) / 2.0f, cy = (kHeight - 1) / 2.0f;
    const auto scale = [&](int t) { return std::pow(2.0f, static_cast<float>(t) / (kFrames - 1)); };
    FrameInput first;
    first.width = kWidth;
    first.height = kHeight;
    Result<FrameState> state = synthesize_frame(pattern, first, nullptr, 0, options, context);
    EXPECT_TRUE(state.ok());
    ZoomResult result;
    result.first = state->screen;
    for (int t = 1; t < kFrames; ++t) {
        // Pixel x was at c + (x - c) s_{t-1} / s_t
        FrameInput input = first;
        input.backward_flow = Image(kWidth, kHeight, 2);
        const float ratio = scale(t - 1) / scale(t);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                input.backward_flow.at(x, y, 0) = (static_cast<float>(x) - cx) * (ratio - 1.0f);
                input.backward_flow.at(x, y, 1) = (static_cast<float>(y) - cy) * (ratio - 1.0f);
            }
        Result<FrameState> next =
            synthesize_frame(pattern, input, &state.value(), t, options, context);
        EXPECT_TRUE(next.ok());
        state = std::move(next);
    }
    result.last = state->screen;
    result.mapped = Image(kWidth, kHeight, 1);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const float sx = cx + (static_cast<float>(x) - cx) / 2.0f;
            const float sy = cy + (static_cast<float>(y) - cy) / 2.0f;
            const int x0 = static_cast<int>(sx), y0 = static_cast<int>(sy);
            const float fx = sx - static_cast<float>(x0), fy = sy - static_cast<float>(y0);
            const Image& f = result.first;
            result.mapped.at(x, y, 0) =
                (1 - fy) * ((1 - fx) * f.at(x0, y0, 0) + fx * f.at(x0 + 1, y0, 0)) +
                fy * ((1 - fx) * f.at(x0, y0 + 1, 0) + fx * f.at(x0 + 1, y0 + 1, 0));
        }
    return result;
}

// The evidence at the default options: under a 2x camera zoom the element size (first
// zero of the autocorrelation) stays within 10% while texture mapping doubles it.
TEST(NprSynthesis, ElementSizeStaysConstantUnderA2xCameraZoom) {
    const Pattern pattern = prepared(testing::stipple_pattern(64, 6.0f));
    const ZoomResult zoom = zoom_2x(pattern, SynthesisOptions{});
    const float before = element_size(zoom.first);
    const float after = element_size(zoom.last);
    const float baseline = element_size(zoom.mapped);
    RecordProperty("size_ratio", std::to_string(after / before));
    std::printf(
        "element size: first frame %.2f px, after 2x zoom %.2f px, texture-mapped %.2f px\n",
        before, after, baseline);
    EXPECT_NEAR(after / before, 1.0f, 0.10f);
    EXPECT_GT(baseline / before, 1.7f);
}

// What motion_levels trades: with the previous frame's per-pixel candidates at every level the
// coordinates follow the exact motion, and the pattern grows with the zoom like texture mapping.
TEST(NprSynthesis, PerPixelMotionCandidatesAtEveryLevelGrowThePatternWithAZoom) {
    const Pattern pattern = prepared(testing::stipple_pattern(64, 6.0f));
    SynthesisOptions options;
    options.motion_levels = 3;
    const ZoomResult zoom = zoom_2x(pattern, options);
    const float ratio = element_size(zoom.last) / element_size(zoom.first);
    std::printf("motion_levels 3: element size x%.2f after a 2x zoom\n", ratio);
    EXPECT_GT(ratio, 1.7f);
}

// The bidirectional loop's backward pass: held pixels keep their coordinates at the finest
// level exactly, the rest is synthesized again (coherent with the reference frame).
TEST(NprSynthesis, HeldPixelsKeepTheirCoordinates) {
    const Pattern pattern = prepared(testing::stipple_pattern(64, 6.0f));
    const RunContext context(2);
    FrameInput first;
    first.width = 96;
    first.height = 64;
    const Result<FrameState> forward = synthesize_frame(pattern, first, nullptr, 0, {}, context);
    const Result<FrameState> next = synthesize_frame(pattern, first, nullptr, 1, {}, context);
    ASSERT_TRUE(forward.ok() && next.ok());
    // Hold the left half (x < 40); the reference: the next frame, moved by (2, 1) px
    FrameInput input = translating_frame(96, 64, 2, 1);
    input.hold = Image(96, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 40; ++x) input.hold.at(x, y, 0) = 1.0f;
    input.held = &forward.value();
    const Result<FrameState> backward =
        synthesize_frame(pattern, input, &next.value(), 0, {}, context);
    ASSERT_TRUE(backward.ok()) << backward.status().message();
    int changed = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 96; ++x)
            for (int c = 0; c < 2; ++c) {
                const float kept = forward->coords[0].at(x, y, c);
                if (x < 40)
                    EXPECT_EQ(backward->coords[0].at(x, y, c), kept) << x << "," << y;
                else
                    changed += backward->coords[0].at(x, y, c) != kept;
            }
    EXPECT_GT(changed, 1000);
    // The rest follows the reference frame
    EXPECT_LT(temporal_error(next->screen, backward->screen, 2, 1) * 2.0f,
              temporal_error(next->screen, forward->screen, 2, 1));
    input.held = nullptr;
    EXPECT_FALSE(synthesize_frame(pattern, input, &next.value(), 0, {}, context).ok());
}

TEST(NprSynthesis, PackedStateRestoresTheCoordinatesAndAppearance) {
    const Pattern pattern = prepared(testing::halftone_pattern(64, 8));
    FrameInput input;
    input.width = 45;
    input.height = 30;
    const Result<FrameState> frame = synthesize_frame(pattern, input, nullptr, 0, {});
    ASSERT_TRUE(frame.ok());
    const Result<FrameState> restored = unpack_state(pattern, pack_state(*frame));
    ASSERT_TRUE(restored.ok()) << restored.status().message();
    ASSERT_EQ(restored->coords.size(), frame->coords.size());
    for (std::size_t l = 0; l < frame->coords.size(); ++l) {
        EXPECT_TRUE(std::equal(frame->coords[l].data().begin(), frame->coords[l].data().end(),
                               restored->coords[l].data().begin()));
        EXPECT_TRUE(std::equal(frame->appearance[l].data().begin(),
                               frame->appearance[l].data().end(),
                               restored->appearance[l].data().begin()));
    }
    EXPECT_FALSE(unpack_state(pattern, Image(45, 30, 4)).ok());
}

}  // namespace
}  // namespace exemplar::npr
