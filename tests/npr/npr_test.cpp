// The styles around the coordinate synthesis (npr::stylize_frame): the option table, which
// buffers a frame reads, thresholding against the tone (linear or encoded), line inking,
// buffer errors named, determinism, progress and cancellation.
#include "exemplar/npr/npr.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "exemplar/render/render.hpp"
#include "npr_patterns.hpp"

namespace exemplar::npr {
namespace {

constexpr int kWidth = 48, kHeight = 32;

Pattern prepared(const NprOptions& options) {
    Result<Pattern> pattern = prepare_pattern(testing::stipple_pattern(64, 5.0f), options);
    EXPECT_TRUE(pattern.ok()) << pattern.status().message();
    return std::move(pattern).value();
}

// A linear-light tone ramp from dark (left) to light (right), 3 channels as render's.
Image tone_ramp() {
    Image tone(kWidth, kHeight, 3);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            for (int c = 0; c < 3; ++c)
                tone.at(x, y, c) = static_cast<float>(x) / static_cast<float>(kWidth - 1);
    return tone;
}

// A vertical line at x = 20.
Image lines() {
    Image image(kWidth, kHeight, 1);
    for (int y = 0; y < kHeight; ++y) image.at(20, y, 0) = 1.0f;
    return image;
}

// The frame after one whose content moved right by 2 px.
NprFrame moved_frame() {
    NprFrame frame;
    frame.tone = tone_ramp();
    frame.tone_linear = true;
    frame.lines = lines();
    frame.backward_flow = Image(kWidth, kHeight, 2);
    frame.disocclusion = Image(kWidth, kHeight, 1);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            frame.backward_flow.at(x, y, 0) = -2.0f;
            frame.disocclusion.at(x, y, 0) = x < 2 ? 1.0f : 0.0f;
        }
    return frame;
}

std::vector<float> pixels(const Image& image) {
    return {image.data().begin(), image.data().end()};
}

std::vector<std::string> names(const std::vector<BufferNeed>& needs) {
    std::vector<std::string> out;
    for (const BufferNeed& need : needs) out.push_back(need.name);
    return out;
}

TEST(NprStyle, OptionTableChecksRangesAndTheToneAgainstTheStyle) {
    NprOptions options;
    const auto specs = npr_option_specs();
    ASSERT_EQ(specs.size(), 6u);
    EXPECT_EQ(get_option(options, specs[0]), 3.0);  // levels
    Status status = set_option(options, specs[0], 9);
    EXPECT_EQ(status.message(), "levels: 9 is invalid (must be an integer, 1..6)");
    status = set_option(options, specs[1], 12.5);
    EXPECT_EQ(status.message(), "patch-size: 12.5 is invalid (must be an integer, 3..32)");
    ASSERT_TRUE(set_option(options, specs[2], 0.25).is_ok());
    EXPECT_FLOAT_EQ(options.coherence_weight, 0.25f);
    EXPECT_EQ(get_option(options, specs[3]), 0.0);  // motion-levels
    EXPECT_EQ(set_option(options, specs[3], 7).message(),
              "motion-levels: 7 is invalid (must be an integer, 0..6)");
    EXPECT_EQ(set_option(options, specs[4], 1.5).message(),
              "paper-grain: 1.5 is invalid (must be 0..1)");
    EXPECT_EQ(set_option(options, specs[5], 0.25).message(),
              "erosion: 0.25 is invalid (must be 0.5..20)");
    EXPECT_TRUE(validate(options).is_ok());
    options.levels = 0;
    EXPECT_EQ(validate(options).message(), "levels: 0 is invalid (must be an integer, 1..6)");
    options = {};
    options.style = Style::Pattern;
    options.tone = "fullgi";
    EXPECT_EQ(validate(options).message(), "tone: not used by style pattern (it shows no tone)");
    EXPECT_EQ(parse_style("crosshatch").status().message(),
              "style: 'crosshatch' is invalid (must be one of stipple, hatch, halftone, pattern)");
    for (Style style : {Style::Stipple, Style::Halftone, Style::Hatch, Style::Pattern})
        EXPECT_EQ(*parse_style(to_string(style)), style);
}

TEST(NprStyle, NeedsTheBuffersTheStyleReads) {
    NprOptions options;
    using V = std::vector<std::string>;
    EXPECT_EQ(names(needed_buffers(options, false)), (V{"direct_diffuse", "lines"}));
    EXPECT_EQ(names(needed_buffers(options, true)),
              (V{"direct_diffuse", "backward_flow", "disocclusion", "lines"}));
    options.style = Style::Hatch;
    options.tone = "fullgi";
    EXPECT_EQ(names(needed_buffers(options, false)), (V{"fullgi", "orientation", "lines"}));
    options.orientation = "none";
    options.lines = false;
    EXPECT_EQ(names(needed_buffers(options, false)), (V{"fullgi"}));
    // The pattern style without lines reads `lines` for the frame's size only
    options = {};
    options.style = Style::Pattern;
    options.lines = false;
    EXPECT_EQ(names(needed_buffers(options, false)), (V{"lines"}));
    EXPECT_EQ(names(needed_buffers(options, true)), (V{"backward_flow", "disocclusion"}));
    EXPECT_EQ(needed_buffers(options, true)[0].role, BufferRole::BackwardFlow);
}

TEST(NprStyle, ThresholdsTheToneAndInksTheLines) {
    const NprOptions options;
    const Pattern pattern = prepared(options);
    NprFrame frame;
    frame.tone = tone_ramp();
    frame.tone_linear = true;
    frame.lines = lines();
    const Result<NprFrameResult> result = stylize_frame(pattern, frame, nullptr, 0, options);
    ASSERT_TRUE(result.ok()) << result.status().message();
    const Image& image = result->image;
    ASSERT_EQ(image.width(), kWidth);
    ASSERT_EQ(image.channels(), 1);
    // Ink and paper only; the line inked; more ink in the dark half than in the light half
    int dark_ink = 0, light_ink = 0;
    for (int y = 0; y < kHeight; ++y) {
        EXPECT_EQ(image.at(20, y, 0), 0.0f);
        for (int x = 0; x < kWidth; ++x) {
            const float v = image.at(x, y, 0);
            ASSERT_TRUE(v == 0.0f || v == 1.0f) << v;
            if (x == 20) continue;
            (x < kWidth / 2 ? dark_ink : light_ink) += v == 0.0f;
        }
    }
    EXPECT_GT(dark_ink, 2 * light_ink);
    EXPECT_EQ(result->state.coords.size(), 3u);
    // A linear tone is sRGB-encoded first: the same as the encoded buffer given as such
    NprFrame encoded = frame;
    encoded.tone = render::encode_srgb(frame.tone);
    encoded.tone_linear = false;
    const Result<NprFrameResult> same = stylize_frame(pattern, encoded, nullptr, 0, options);
    ASSERT_TRUE(same.ok());
    EXPECT_EQ(pixels(same->image), pixels(image));
    const Result<NprFrameResult> raw =
        stylize_frame(pattern, {frame.tone, false, {}, {}, {}, frame.lines, {}, {}, nullptr},
                      nullptr, 0, options);
    ASSERT_TRUE(raw.ok());
    EXPECT_NE(pixels(raw->image), pixels(image));
}

TEST(NprStyle, PatternStyleIsTheSynthesizedScreen) {
    NprOptions options;
    options.style = Style::Pattern;
    options.lines = false;
    const Pattern pattern = prepared(options);
    NprFrame frame;
    frame.lines = lines();  // only its size is read
    const Result<NprFrameResult> result = stylize_frame(pattern, frame, nullptr, 3, options);
    ASSERT_TRUE(result.ok()) << result.status().message();
    EXPECT_EQ(pixels(result->image), pixels(result->state.screen));
    int grey = 0;
    for (float v : pixels(result->image)) grey += v > 0.0f && v < 1.0f;
    EXPECT_GT(grey, 0);
}

TEST(NprStyle, ContinuesFromThePreviousStateIdenticallyForOneAndTwoThreads) {
    const NprOptions options;
    const Pattern pattern = prepared(options);
    std::vector<float> images[2];
    for (int t = 0; t < 2; ++t) {
        const RunContext context(t + 1);
        NprFrame first = moved_frame();
        first.backward_flow = {};  // ignored without a previous frame anyway
        const Result<NprFrameResult> a =
            stylize_frame(pattern, first, nullptr, 0, options, context);
        ASSERT_TRUE(a.ok()) << a.status().message();
        const Result<NprFrameResult> b =
            stylize_frame(pattern, moved_frame(), &a->state, 1, options, context);
        ASSERT_TRUE(b.ok()) << b.status().message();
        images[t] = pixels(b->image);
    }
    EXPECT_EQ(images[0], images[1]);
}

// The paper layer (§6, §6.0.2): synthesized like the pattern and coherent along the motion;
// outside the shape only paper; along the shape's boundary an uneven band eroded to paper;
// inside the result shaded by the paper's grain.
TEST(NprStyle, PaperLayerShadesAndErodesTheShapeBoundary) {
    NprOptions options;
    options.paper = true;
    const Pattern pattern = prepared(options);
    Result<Pattern> paper = prepare_pattern(testing::halftone_pattern(64, 6), options);
    ASSERT_TRUE(paper.ok()) << paper.status().message();
    // The shape: a disc of radius 12 px
    NprFrame frame;
    frame.tone = tone_ramp();
    frame.tone_linear = true;
    frame.lines = Image(kWidth, kHeight, 1);
    frame.mask = Image(kWidth, kHeight, 1);
    const auto radius = [](int x, int y) {
        return std::hypot(static_cast<float>(x) - 24.0f, static_cast<float>(y) - 16.0f);
    };
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) frame.mask.at(x, y, 0) = radius(x, y) < 12.0f ? 1 : 0;
    const Result<NprFrameResult> on_paper =
        stylize_frame(pattern, frame, nullptr, 0, options, {}, {&*paper, nullptr});
    ASSERT_TRUE(on_paper.ok()) << on_paper.status().message();
    NprOptions plain = options;
    plain.paper = false;
    const Result<NprFrameResult> without = stylize_frame(pattern, frame, nullptr, 0, plain);
    ASSERT_TRUE(without.ok());
    const Image& grain = on_paper->paper_state.screen;
    ASSERT_EQ(grain.width(), kWidth);
    int eroded = 0, kept_in_band = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const float shade = 1.0f - options.paper_grain * (1.0f - grain.at(x, y, 0));
            const float value = on_paper->image.at(x, y, 0);
            const float r = radius(x, y);
            if (r >= 12.0f) {
                EXPECT_FLOAT_EQ(value, shade) << x << "," << y;  // paper only
            } else if (r < 7.0f) {
                EXPECT_FLOAT_EQ(value, without->image.at(x, y, 0) * shade) << x << "," << y;
            } else if (r > 10.0f && without->image.at(x, y, 0) == 0.0f) {
                // Ink of the band along the boundary: eroded where the paper is light
                (value == shade ? eroded : kept_in_band) += 1;
            }
        }
    EXPECT_GT(eroded, 3);
    EXPECT_GT(kept_in_band, 3);
    // The paper continues along the motion like the pattern
    NprFrame next = moved_frame();
    next.mask = frame.mask;
    const Result<NprFrameResult> continued = stylize_frame(
        pattern, next, &on_paper->state, 1, options, {}, {&*paper, &on_paper->paper_state});
    ASSERT_TRUE(continued.ok()) << continued.status().message();
    const Result<NprFrameResult> alone =
        stylize_frame(pattern, frame, nullptr, 1, options, {}, {&*paper, nullptr});
    ASSERT_TRUE(alone.ok());
    const auto moved_error = [&](const Image& screen) {
        double sum = 0.0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 2; x < kWidth; ++x)
                sum += std::fabs(screen.at(x, y, 0) - grain.at(x - 2, y, 0));
        return sum / ((kWidth - 2) * kHeight);
    };
    const double coherent = moved_error(continued->paper_state.screen);
    const double independent = moved_error(alone->paper_state.screen);
    std::printf("paper along the motion: %.4f, independent %.4f\n", coherent, independent);
    EXPECT_LT(coherent, 0.5 * independent);
    // Errors: no paper pattern, paper pattern without the layer, no alpha buffer
    EXPECT_EQ(stylize_frame(pattern, frame, nullptr, 0, options).status().message(),
              "paper: the paper layer needs a paper pattern");
    EXPECT_EQ(
        stylize_frame(pattern, frame, nullptr, 0, plain, {}, {&*paper, nullptr}).status().message(),
        "paper: a paper pattern is given but the paper layer is off");
    frame.mask = {};
    EXPECT_EQ(stylize_frame(pattern, frame, nullptr, 0, options, {}, {&*paper, nullptr})
                  .status()
                  .message(),
              "missing buffer 'alpha'");
}

// Delayed visibility (§5.2.1): visible in every frame since the update frame, followed along
// the backward flow.
TEST(NprStyle, DelayedVisibilityChainsAlongTheMotion) {
    Image flow(8, 1, 2), hidden(8, 1, 1);
    for (int x = 0; x < 8; ++x) flow.at(x, 0, 0) = -1.0f;  // moved right by 1 px
    hidden.at(0, 0, 0) = 1.0f;                             // entered at the left
    const Result<Image> first = delayed_visibility({}, hidden, flow);
    ASSERT_TRUE(first.ok());
    EXPECT_EQ(pixels(*first), (std::vector<float>{0, 1, 1, 1, 1, 1, 1, 1}));
    // Next frame: pixel 1 was pixel 0 (not visible since the update frame), so it stays hidden
    const Result<Image> second = delayed_visibility(*first, hidden, flow);
    ASSERT_TRUE(second.ok());
    EXPECT_EQ(pixels(*second), (std::vector<float>{0, 0, 1, 1, 1, 1, 1, 1}));
    EXPECT_FALSE(delayed_visibility(Image(4, 1, 1), hidden, flow).ok());
}

TEST(NprStyle, NamesMissingAndMismatchedBuffers) {
    NprOptions options;
    const Pattern pattern = prepared(options);
    NprFrame frame = moved_frame();
    frame.lines = {};
    EXPECT_EQ(stylize_frame(pattern, frame, nullptr, 0, options).status().message(),
              "missing buffer 'lines'");
    frame = moved_frame();
    frame.lines = Image(kWidth + 1, kHeight, 1);
    EXPECT_EQ(stylize_frame(pattern, frame, nullptr, 0, options).status().message(),
              "buffer 'lines' is 49x32 but the frames are 48x32");
    // A previous frame needs the backward flow
    frame = moved_frame();
    const Result<NprFrameResult> first = stylize_frame(pattern, frame, nullptr, 0, options);
    ASSERT_TRUE(first.ok());
    frame.backward_flow = {};
    EXPECT_EQ(stylize_frame(pattern, frame, &first->state, 1, options).status().message(),
              "missing buffer 'backward_flow'");
    frame = moved_frame();
    frame.backward_flow = Image(kWidth, kHeight, 1);
    EXPECT_EQ(stylize_frame(pattern, frame, &first->state, 1, options).status().message(),
              "buffer 'backward_flow' has 1 channels (needs 2)");
    // Another frame size than the previous frame's
    NprFrame larger;
    larger.tone = Image(kWidth * 2, kHeight, 1);
    larger.lines = Image(kWidth * 2, kHeight, 1);
    larger.backward_flow = Image(kWidth * 2, kHeight, 2);
    larger.disocclusion = Image(kWidth * 2, kHeight, 1);
    EXPECT_EQ(stylize_frame(pattern, larger, &first->state, 1, options).status().message(),
              "frame size differs from the previous frame's (48x32)");
    // A pattern prepared for other levels
    NprOptions two = options;
    two.levels = 2;
    EXPECT_EQ(stylize_frame(pattern, moved_frame(), nullptr, 0, two).status().message(),
              "pattern: prepared with 3 levels but levels is 2");
    // Too small a pattern for the patch size and levels
    EXPECT_EQ(prepare_pattern(testing::halftone_pattern(16, 8), options).status().message(),
              "pattern: 16x16 is too small (needs at least 48x48 for the patch size)");
}

TEST(NprStyle, ReportsProgressPerLevelAndStopsWhenCancelled) {
    const NprOptions options;
    const Pattern pattern = prepared(options);
    std::vector<double> fractions;
    RunContext context(1);
    context.progress = [&](const ProgressEvent& event) {
        EXPECT_EQ(event.stage, "synthesis");
        EXPECT_EQ(event.levels, 3);
        fractions.push_back(event.fraction);
    };
    ASSERT_TRUE(stylize_frame(pattern, moved_frame(), nullptr, 0, options, context).ok());
    ASSERT_EQ(fractions.size(), 3u);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
    CancelToken token;
    token.cancel();
    context.cancel = &token;
    const Result<NprFrameResult> stopped =
        stylize_frame(pattern, moved_frame(), nullptr, 0, options, context);
    EXPECT_EQ(stopped.status().code(), ErrorCode::Cancelled);
}

}  // namespace
}  // namespace exemplar::npr
