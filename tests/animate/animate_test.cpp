// TCIA solver: temporal coherence against per-frame stylization, texture kept, disocclusions
// re-synthesized (Bénard Fig. 4), keyframes exact, in-betweens smooth, determinism, errors.

#include "exemplar/animate/animate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "exemplar/animate/lines.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "exemplar/video/warp.hpp"
#include "synthetic_scene.hpp"

namespace exemplar::animate {
namespace {

using testing::gradient_energy;
using testing::make_input;
using testing::make_style;
using testing::Scene;
using testing::warp_error;

// Stylizes every frame on its own with the solver's engine settings (the baseline).
std::vector<Image> independent(const Scene& scene, const testing::Style& style,
                               const AnimateOptions& options) {
    std::vector<Image> out;
    for (int t = 0; t < scene.frames; ++t) {
        SynthesisInput in;
        in.style = style.output;
        in.guides.push_back({"input", style.input, scene.frame(t), options.input_weight, {}});
        SynthesisOptions o = options.synthesis;
        o.style_weight = options.output_weight;
        o.levels = 2;
        out.push_back(synthesize(in, o, RunContext(1)).value().image);
    }
    return out;
}

double mean_warp_error(const Scene& scene, const std::vector<Image>& frames) {
    double sum = 0.0;
    for (int t = 1; t < scene.frames; ++t) {
        const video::FlowPair prev = scene.motion(t - 1);
        sum += warp_error(frames[static_cast<std::size_t>(t - 1)],
                          frames[static_cast<std::size_t>(t)], prev.backward, prev.forward);
    }
    return sum / (scene.frames - 1);
}

double mean_gradient_energy(const std::vector<Image>& frames) {
    double sum = 0.0;
    for (const Image& f : frames) sum += gradient_energy(f);
    return sum / static_cast<double>(frames.size());
}

TEST(Animate, TemporallyCoherentWhereIndependentFramesFlicker) {
    const Scene scene;
    const testing::Style style = make_style();
    AnimateOptions options;
    auto tcia = animate(make_input(scene, style), options, RunContext(2));
    ASSERT_TRUE(tcia.ok()) << tcia.status().message();
    const std::vector<Image> base = independent(scene, style, options);

    const double e_tcia = mean_warp_error(scene, tcia->frames);
    const double e_base = mean_warp_error(scene, base);
    const double g_style = gradient_energy(style.output);
    const double g_tcia = mean_gradient_energy(tcia->frames);
    const double g_base = mean_gradient_energy(base);
    std::printf(
        "warp error: tcia %.5f independent %.5f; gradient energy: style %.5f tcia %.5f "
        "independent %.5f\n",
        e_tcia, e_base, g_style, g_tcia, g_base);
    EXPECT_LT(e_tcia, 0.2 * e_base);
    EXPECT_GT(g_tcia, 0.6 * g_style);
}

// Mean of R − B over the pixels of frame `t` that the square covered at frame 0 but has left by
// frame t (the disoccluded trail): about −0.5 for the background's blue style, +0.5 for the red.
double trail_redness(const Scene& scene, const Image& frame, int t) {
    double sum = 0.0;
    int n = 0;
    for (int y = scene.y0; y < scene.y0 + scene.square; ++y) {
        for (int x = 0; x < scene.width; ++x) {
            if (!scene.in_square(x, y, 0) || scene.in_square(x, y, t)) continue;
            sum += frame.at(x, y, 0) - frame.at(x, y, 2);
            ++n;
        }
    }
    return sum / n;
}

// Sub-pixel motion: a disc rotating in place (every pixel of it moves by a fraction of a pixel
// to about 1.4 px per frame); nearest-sample advection with extrapolation keeps the texture on it.
TEST(Animate, RotatingDiscKeepsItsTexture) {
    const testing::RotatingDisc disc;
    const testing::Style style = make_style();
    AnimationInput in;
    in.style_input = style.input;
    in.style_output = style.output;
    in.frame_count = disc.frames;
    in.frame = [&](int t) -> Result<Image> { return disc.frame(t); };
    in.motion = [&](int t) -> Result<video::FlowPair> { return disc.motion(t); };
    auto r = animate(in, AnimateOptions(), RunContext(2));
    ASSERT_TRUE(r.ok()) << r.status().message();
    std::vector<Image> base;
    for (int t = 0; t < disc.frames; ++t) {
        SynthesisInput s;
        s.style = style.output;
        s.guides.push_back({"input", style.input, disc.frame(t), 2.0f, {}});
        SynthesisOptions o = animate_default_synthesis_options();
        o.levels = 2;
        base.push_back(synthesize(s, o, RunContext(1)).value().image);
    }
    auto mean_error = [&](const std::vector<Image>& frames) {
        double sum = 0.0;
        for (int t = 1; t < disc.frames; ++t) {
            const video::FlowPair m = disc.motion(t - 1);
            sum += warp_error(frames[static_cast<std::size_t>(t - 1)],
                              frames[static_cast<std::size_t>(t)], m.backward, m.forward);
        }
        return sum / (disc.frames - 1);
    };
    // The flow is exact: inside the disc (away from its rim, where bilinear samples mix disc
    // and background) the inputs agree along it up to bilinear resampling.
    {
        const video::WarpResult w =
            video::backward_warp(disc.frame(0), disc.motion(0).backward, 1).value();
        const Image next = disc.frame(1);
        double sum = 0.0;
        int count = 0;
        for (int y = 0; y < disc.height; ++y) {
            for (int x = 0; x < disc.width; ++x) {
                const float dx = static_cast<float>(x) - disc.cx;
                const float dy = static_cast<float>(y) - disc.cy;
                if (dx * dx + dy * dy > (disc.radius - 2) * (disc.radius - 2)) continue;
                const double d = next.at(x, y, 0) - w.image.at(x, y, 0);
                sum += d * d;
                ++count;
            }
        }
        EXPECT_LT(sum / count, 1e-5);
    }
    const double e_tcia = mean_error(r->frames), e_base = mean_error(base);
    const double g = mean_gradient_energy(r->frames) / gradient_energy(style.output);
    std::printf("rotating disc: warp error tcia %.5f independent %.5f; texture kept %.2f\n", e_tcia,
                e_base, g);
    EXPECT_LT(e_tcia, 0.25 * e_base);
    EXPECT_GT(g, 0.6);
}

TEST(Animate, RotatedPatchesAlongOrientationFieldsStayCoherent) {
    const Scene scene;
    const testing::Style style = make_style();
    AnimateOptions options;
    options.orientation = true;
    auto tcia = animate(make_input(scene, style), options, RunContext(2));
    ASSERT_TRUE(tcia.ok()) << tcia.status().message();
    const double e_tcia = mean_warp_error(scene, tcia->frames);
    const double e_base = mean_warp_error(scene, independent(scene, style, AnimateOptions()));
    std::printf("orientation on: warp error tcia %.5f independent %.5f\n", e_tcia, e_base);
    EXPECT_LT(e_tcia, 0.2 * e_base);
    EXPECT_LT(trail_redness(scene, tcia->frames.back(), scene.frames - 1), -0.3);
}

TEST(Animate, DisoccludedBackgroundIsResynthesizedNotSmeared) {
    const Scene scene;
    const testing::Style style = make_style();
    auto tcia = animate(make_input(scene, style), AnimateOptions(), RunContext(2));
    ASSERT_TRUE(tcia.ok()) << tcia.status().message();
    // Naive baseline: advect the previous output everywhere (no occlusion handling).
    std::vector<Image> naive{tcia->frames[0]};
    for (int t = 1; t < scene.frames; ++t) {
        const video::WarpResult w =
            video::backward_warp(naive.back(), scene.motion(t - 1).backward, 1).value();
        naive.push_back(w.image);
    }
    const int last = scene.frames - 1;
    const double tcia_red =
        trail_redness(scene, tcia->frames[static_cast<std::size_t>(last)], last);
    const double naive_red = trail_redness(scene, naive.back(), last);
    std::printf("trail R-B: tcia %.3f naive advection %.3f\n", tcia_red, naive_red);
    EXPECT_LT(tcia_red, -0.3);  // background (blue) style
    EXPECT_GT(naive_red, 0.3);  // the square's red smeared into a trail
}

TEST(Animate, DeterministicForASeedAndAnyThreadCount) {
    Scene scene;
    scene.frames = 4;
    const testing::Style style = make_style();
    AnimateOptions options;
    auto a = animate(make_input(scene, style), options, RunContext(1));
    auto b = animate(make_input(scene, style), options, RunContext(2));
    ASSERT_TRUE(a.ok() && b.ok());
    for (int t = 0; t < scene.frames; ++t) {
        const auto i = static_cast<std::size_t>(t);
        ASSERT_TRUE(std::equal(a->frames[i].data().begin(), a->frames[i].data().end(),
                               b->frames[i].data().begin()))
            << "frame " << t;
    }
    options.synthesis.seed = 2;
    auto c = animate(make_input(scene, style), options, RunContext(2));
    ASSERT_TRUE(c.ok());
    EXPECT_FALSE(std::equal(a->frames[1].data().begin(), a->frames[1].data().end(),
                            c->frames[1].data().begin()));
}

TEST(Animate, ProgressCoversEveryFrameAndEndsComplete) {
    Scene scene;
    scene.frames = 3;
    const testing::Style style = make_style();
    RunContext context(1);
    std::vector<int> forward_frames;
    double last_fraction = 0.0;
    bool monotone = true;
    context.progress = [&](const ProgressEvent& e) {
        if (e.stage == "forward" &&
            (forward_frames.empty() || forward_frames.back() != e.iteration))
            forward_frames.push_back(e.iteration);
        monotone &= e.fraction >= last_fraction;
        last_fraction = e.fraction;
    };
    ASSERT_TRUE(animate(make_input(scene, style), AnimateOptions(), context).ok());
    EXPECT_TRUE(monotone);
    EXPECT_DOUBLE_EQ(last_fraction, 1.0);
    // Two levels, frames 0, 1, 2 each.
    EXPECT_EQ(forward_frames, (std::vector<int>{0, 1, 2, 0, 1, 2}));
}

// A painted frame: the independent stylization of frame t with another seed, with the square
// tinted green so that it is recognisable.
Image painted(const Scene& scene, const testing::Style& style, int t, const Image* base = nullptr) {
    Image key;
    if (base != nullptr) {
        key = *base;
    } else {
        SynthesisInput in;
        in.style = style.output;
        in.guides.push_back({"input", style.input, scene.frame(t), 2.0f, {}});
        SynthesisOptions o = animate_default_synthesis_options();
        o.seed = 99;
        key = synthesize(in, o, RunContext(1)).value().image;
    }
    return key;
}

TEST(Animate, KeyframePixelsAreReproducedExactly) {
    const Scene scene;
    const testing::Style style = make_style();
    AnimationInput in = make_input(scene, style);
    // Full key at frame 0; partial key at frame 5: a green patch over the square only.
    const Image full = painted(scene, style, 0);
    Image partial(scene.width, scene.height, 3, 0.0f), mask(scene.width, scene.height, 1, 0.0f);
    for (int y = 0; y < scene.height; ++y) {
        for (int x = 0; x < scene.width; ++x) {
            if (!scene.in_square(x, y, 5)) continue;
            mask.at(x, y, 0) = 1.0f;
            partial.at(x, y, 1) = 0.6f + 0.01f * static_cast<float>((x * 7 + y * 3) % 11);
        }
    }
    in.keyframes = {{0, full, {}}, {5, partial, mask}};
    auto r = animate(in, AnimateOptions(), RunContext(2));
    ASSERT_TRUE(r.ok()) << r.status().message();
    EXPECT_TRUE(std::equal(full.data().begin(), full.data().end(), r->frames[0].data().begin()));
    int checked = 0;
    for (int y = 0; y < scene.height; ++y) {
        for (int x = 0; x < scene.width; ++x) {
            if (mask.at(x, y, 0) < 1.0f) continue;
            for (int c = 0; c < 3; ++c) ASSERT_EQ(r->frames[5].at(x, y, c), partial.at(x, y, c));
            ++checked;
        }
    }
    EXPECT_EQ(checked, scene.square * scene.square);
    // Outside the partial key the frame is synthesized, not left black.
    EXPECT_LT(trail_redness(scene, r->frames[5], 5), -0.3);
}

TEST(Animate, InBetweensMoveSmoothlyBetweenTwoKeys) {
    const Scene scene;  // 8 frames, keys at 0 and 7
    const testing::Style style = make_style();
    const Image key0 = painted(scene, style, 0);
    const Image bg7 = painted(scene, style, 7);
    // Key 7 is key 0 with the square moved along the motion (the artist painted it the same),
    // the background uncovered behind it painted fresh.
    Image key7 = key0;
    const int shift = scene.speed * 7;
    for (int y = 0; y < scene.height; ++y) {
        for (int x = 0; x < scene.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                if (scene.in_square(x, y, 7)) {
                    key7.at(x, y, c) = key0.at(x - shift, y, c);
                } else if (scene.in_square(x, y, 0)) {
                    key7.at(x, y, c) = bg7.at(x, y, c);
                }
            }
        }
    }
    AnimationInput in = make_input(scene, style);
    in.keyframes = {{0, key0, {}}, {7, key7, {}}};
    auto r = animate(in, AnimateOptions(), RunContext(2));
    ASSERT_TRUE(r.ok()) << r.status().message();
    const std::vector<Image> base = independent(scene, style, AnimateOptions());

    // The square's texture travels with it: each in-between's square matches key 0's square.
    double worst_square = 0.0, worst_step = 0.0;
    for (int t = 1; t < 7; ++t) {
        double sum = 0.0;
        int n = 0;
        for (int y = scene.y0; y < scene.y0 + scene.square; ++y) {
            for (int x = scene.square_x(t); x < scene.square_x(t) + scene.square; ++x) {
                for (int c = 0; c < 3; ++c) {
                    const double d = r->frames[static_cast<std::size_t>(t)].at(x, y, c) -
                                     key0.at(x - scene.speed * t, y, c);
                    sum += d * d;
                    ++n;
                }
            }
        }
        worst_square = std::max(worst_square, sum / n);
    }
    for (int t = 1; t < scene.frames; ++t) {
        const video::FlowPair m = scene.motion(t - 1);
        const double e = warp_error(r->frames[static_cast<std::size_t>(t - 1)],
                                    r->frames[static_cast<std::size_t>(t)], m.backward, m.forward);
        worst_step = std::max(worst_step, e);
    }
    const double base_step = mean_warp_error(scene, base);
    std::printf(
        "in-betweens: worst square error vs key 0 %.5f, worst step %.5f (independent "
        "mean step %.5f)\n",
        worst_square, worst_step, base_step);
    EXPECT_LT(worst_square, 0.002);
    // No frame-to-frame jump, not even into the second key.
    EXPECT_LT(worst_step, 0.2 * base_step);
}

// The animation's quality dial: Default is the animation's own defaults (so their changes carry
// over); Fast iterates less and Best more; all are valid.
TEST(Animate, QualityPresetsAroundTheAnimationDefaults) {
    const SynthesisOptions defaults = animate_default_synthesis_options();
    const SynthesisOptions preset = animate_synthesis_options(Quality::Default);
    for (const OptionSpec& spec : synthesis_option_specs()) {
        EXPECT_EQ(get_option(preset, spec), get_option(defaults, spec)) << spec.name;
    }
    EXPECT_EQ(preset.usage, defaults.usage);
    EXPECT_EQ(preset.vote, defaults.vote);
    const SynthesisOptions fast = animate_synthesis_options(Quality::Fast);
    const SynthesisOptions best = animate_synthesis_options(Quality::Best);
    EXPECT_TRUE(validate(fast).is_ok());
    EXPECT_TRUE(validate(best).is_ok());
    EXPECT_EQ(fast.usage, defaults.usage);
    EXPECT_EQ(best.usage, defaults.usage);
    EXPECT_LT(fast.em_iterations, defaults.em_iterations);
    EXPECT_GT(best.em_iterations, defaults.em_iterations);
    EXPECT_LE(fast.warm_search_iterations, defaults.warm_search_iterations);
    EXPECT_GE(best.warm_search_iterations, defaults.warm_search_iterations);
}

TEST(Animate, ErrorsNameTheProblem) {
    Scene scene;
    scene.frames = 3;
    const testing::Style style = make_style();
    auto message = [&](const AnimationInput& in) {
        auto r = animate(in, AnimateOptions(), RunContext(1));
        EXPECT_FALSE(r.ok());
        return r.ok() ? std::string() : r.status().message();
    };
    AnimationInput in = make_input(scene, style);
    in.keyframes = {{5, style.output, {}}};
    EXPECT_EQ(message(in), "keyframe 5: outside the frames 0..2");

    in = make_input(scene, style);
    in.motion = [](int) -> Result<video::FlowPair> {
        return video::FlowPair{Image(32, 24, 2), Image(32, 24, 2)};
    };
    EXPECT_EQ(message(in), "motion 0->1: flow is 32x24 but the frames are 64x48");

    in = make_input(scene, style);
    in.frame = [scene](int t) -> Result<Image> {
        return t == 2 ? Image(10, 10, 1) : scene.frame(t);
    };
    EXPECT_EQ(message(in), "frame 2: is 10x10 but frame 0 is 64x48");

    in = make_input(scene, style);
    in.keyframes = {{1, Image(64, 48, 1), {}}};
    EXPECT_EQ(message(in), "keyframe 1: has 1 channels but the style output has 3");

    AnimateOptions bad;
    bad.temporal_weight = -1.0f;
    auto r = animate(make_input(scene, style), bad, RunContext(1));
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().message(), "temporal-weight: -1.000000 is invalid (must be >= 0)");
}

// A pair of painted textures moving like FlyingChairs (tests/data/flow, reduced to 128x96) with
// flow estimated by DIS: the stylized pair is far more consistent along the motion than two
// independently stylized frames.
TEST(Animate, RealPairWithEstimatedFlowIsCoherent) {
    const std::string dir = EXEMPLAR_TEST_DATA_DIR "/flow/synthetic-";
    std::vector<Image> frames;
    for (const char* name : {"img0.png", "img1.png"}) {
        auto im = load_image(dir + name);
        ASSERT_TRUE(im.ok()) << im.status().message();
        frames.push_back(resize(*im, 128, 96, ResampleFilter::Gaussian, 1));
    }
    // Style: frame 0 itself (S) and a "painted" version of it (Ŝ): posterized colours plus
    // per-pixel grain, so that independent runs pick different grain.
    testing::Style style{frames[0], frames[0]};
    KeyedRng rng(5);
    for (float& v : style.output.data()) {
        v = std::clamp(std::round(v * 4.0f) / 4.0f + 0.3f * (rng.uniform() - 0.5f), 0.0f, 1.0f);
    }
    AnimationInput in;
    in.style_input = style.input;
    in.style_output = style.output;
    in.frame_count = 2;
    in.frame = [&](int t) -> Result<Image> { return frames[static_cast<std::size_t>(t)]; };
    AnimateOptions options;
    auto r = animate(in, options, RunContext(2));  // motion estimated (DIS)
    ASSERT_TRUE(r.ok()) << r.status().message();

    const video::FlowPair flow = video::estimate_flow_pair(frames[0], frames[1]).value();
    auto independent_frame = [&](int t) {
        SynthesisInput s;
        s.style = style.output;
        s.guides.push_back(
            {"input", style.input, frames[static_cast<std::size_t>(t)], options.input_weight, {}});
        SynthesisOptions o = options.synthesis;
        o.levels = 3;
        return synthesize(s, o, RunContext(1)).value().image;
    };
    const double e_tcia = warp_error(r->frames[0], r->frames[1], flow.backward, flow.forward, 8.0f);
    const double e_base =
        warp_error(independent_frame(0), independent_frame(1), flow.backward, flow.forward, 8.0f);
    // The inputs themselves are not constant along the estimated flow (flow errors, lighting):
    // their own warp error is the floor a stylization that follows the input can reach.
    const double e_input = warp_error(frames[0], frames[1], flow.backward, flow.forward, 8.0f);
    const double g_tcia = gradient_energy(r->frames[1]);
    const double g_style = gradient_energy(style.output);
    std::printf(
        "synthetic pair: warp error tcia %.5f independent %.5f input frames %.5f; gradient "
        "energy tcia %.4f style %.4f\n",
        e_tcia, e_base, e_input, g_tcia, g_style);
    EXPECT_LT(e_tcia, 0.5 * e_base);
    EXPECT_LT(e_tcia, e_input);
    EXPECT_GT(g_tcia, 0.5 * g_style);
}

// The line term g_dt: with uninformative shading (uniform grey frames and style input), only
// the distance transforms of the line drawings tell the outline of the moving square to take
// the style's dark strokes.
TEST(Animate, LineTermDrawsTheStylesStrokesAlongTheLines) {
    const Scene scene;
    const int n = 64;
    Image style_lines(n, n, 1, 1.0f), out(n, n, 3);
    auto on_rect = [](int x, int y, int lo, int hi) {
        const bool in = x >= lo && x <= hi && y >= lo && y <= hi;
        return in && (x <= lo + 1 || x >= hi - 1 || y <= lo + 1 || y >= hi - 1);
    };
    KeyedRng rng(3);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            const bool line = on_rect(x, y, 12, 51);
            if (line) style_lines.at(x, y, 0) = 0.0f;
            const float v = line ? 0.05f + 0.1f * rng.uniform() : 0.8f + 0.2f * rng.uniform();
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = v;
        }
    }
    AnimationInput in;
    in.style_input = Image(n, n, 1, 0.5f);
    in.style_output = out;
    in.frame_count = scene.frames;
    in.frame = [&](int) -> Result<Image> { return Image(scene.width, scene.height, 1, 0.5f); };
    in.motion = [&](int t) -> Result<video::FlowPair> { return scene.motion(t); };
    auto outline = [&](int x, int y, int t) {
        return on_rect(x - scene.square_x(t) + 12, y - scene.y0 + 12, 12, 12 + scene.square - 1);
    };
    auto frame_lines = [&](int t) {
        Image lines(scene.width, scene.height, 1, 1.0f);
        for (int y = 0; y < scene.height; ++y) {
            for (int x = 0; x < scene.width; ++x) {
                if (outline(x, y, t)) lines.at(x, y, 0) = 0.0f;
            }
        }
        return lines;
    };
    auto outline_mean = [&](const std::vector<Image>& frames) {
        double sum = 0.0;
        int count = 0;
        for (int t = 0; t < scene.frames; ++t) {
            for (int y = 0; y < scene.height; ++y) {
                for (int x = 0; x < scene.width; ++x) {
                    if (!outline(x, y, t)) continue;
                    sum += frames[static_cast<std::size_t>(t)].at(x, y, 0);
                    ++count;
                }
            }
        }
        return sum / count;
    };
    auto without = animate(in, AnimateOptions(), RunContext(2));
    ASSERT_TRUE(without.ok()) << without.status().message();
    in.style_lines = style_lines;
    in.lines = [&](int t) -> Result<Image> { return frame_lines(t); };
    auto with = animate(in, AnimateOptions(), RunContext(2));
    ASSERT_TRUE(with.ok()) << with.status().message();
    const double dark_with = outline_mean(with->frames);
    const double dark_without = outline_mean(without->frames);
    std::printf("outline luminance: with lines %.3f, without %.3f\n", dark_with, dark_without);
    EXPECT_LT(dark_with, 0.25);  // the strokes are 0.05..0.15
    EXPECT_GT(dark_without, 0.6);
    EXPECT_LT(mean_warp_error(scene, with->frames), 0.002);
}

TEST(Animate, LineDistanceIsBoundedAndNormalized) {
    Image lines(20, 5, 1, 1.0f);
    lines.at(2, 2, 0) = 0.0f;
    const Image d = line_distance(lines, 4.0f).value();
    EXPECT_FLOAT_EQ(d.at(2, 2, 0), 0.0f);
    EXPECT_NEAR(d.at(5, 2, 0), 0.75f, 1e-4);  // 3 px of 4
    EXPECT_FLOAT_EQ(d.at(15, 2, 0), 1.0f);    // beyond d_max
    EXPECT_FLOAT_EQ(line_distance(Image(4, 4, 1, 1.0f), 4.0f).value().at(1, 1, 0), 1.0f);
    EXPECT_FALSE(line_distance(lines, 0.0f).ok());
}

TEST(Animate, ExtrapolatedFlowTakesTheNearestCoveredPixel) {
    Image flow(10, 4, 2), coverage(10, 4, 1, 0.0f);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 3; ++x) {
            coverage.at(x, y, 0) = 1.0f;
            flow.at(x, y, 0) = 1.0f + static_cast<float>(y);
            flow.at(x, y, 1) = -2.0f;
        }
    }
    const Image out = extrapolate_flow(flow, coverage).value();
    EXPECT_FLOAT_EQ(out.at(9, 2, 0), 3.0f);  // row 2's nearest covered pixel (2, 2)
    EXPECT_FLOAT_EQ(out.at(9, 2, 1), -2.0f);
    EXPECT_FLOAT_EQ(out.at(1, 3, 0), 4.0f);  // covered pixels keep theirs
}

// Layers (Bénard §4): a static background layer and the moving square as its own layer, each
// with its exact motion. The background layer is solved whole, so what the square uncovers is
// the background texture that was there all along (not re-synthesized), and the composite takes
// each layer where it covers.
TEST(Animate, LayersKeepTheBackgroundBehindAMovingObject) {
    const Scene scene;
    const testing::Style style = make_style();
    auto square_mask = [&](int t) {
        Image m(scene.width, scene.height, 1, 0.0f);
        for (int y = 0; y < scene.height; ++y) {
            for (int x = 0; x < scene.width; ++x) m.at(x, y, 0) = scene.in_square(x, y, t);
        }
        return m;
    };
    Layer background{make_input(scene, style), [&](int) -> Result<Image> {
                         return Image(scene.width, scene.height, 1, 1.0f);
                     }};
    background.input.frame = [&](int) -> Result<Image> {  // the background rendered alone
        Scene empty = scene;
        empty.square = 0;
        return empty.frame(0);
    };
    background.input.motion = [&](int) -> Result<video::FlowPair> {
        return video::FlowPair{Image(scene.width, scene.height, 2),
                               Image(scene.width, scene.height, 2)};
    };
    Layer square{make_input(scene, style), [&](int t) -> Result<Image> { return square_mask(t); }};
    auto r = animate_layers({background, square}, AnimateOptions(), RunContext(2));
    ASSERT_TRUE(r.ok()) << r.status().message();
    ASSERT_EQ(r->layers.size(), 2u);

    // The background layer does not change at all over time, under the square included.
    double change = 0.0;
    for (int t = 1; t < scene.frames; ++t) {
        const Image& a = r->layers[0][static_cast<std::size_t>(t - 1)];
        const Image& b = r->layers[0][static_cast<std::size_t>(t)];
        for (std::size_t i = 0; i < a.size(); ++i) {
            change += (a.data()[i] - b.data()[i]) * (a.data()[i] - b.data()[i]);
        }
    }
    const double per_value = change / static_cast<double>(r->layers[0][0].size());
    // The uncovered trail shows that same background: blue, equal to layer 0 at frame 0.
    const int last = scene.frames - 1;
    double trail = 0.0;
    int n = 0;
    for (int y = 0; y < scene.height; ++y) {
        for (int x = 0; x < scene.width; ++x) {
            if (!scene.in_square(x, y, 0) || scene.in_square(x, y, last)) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = r->frames[static_cast<std::size_t>(last)].at(x, y, c) -
                                 r->layers[0][0].at(x, y, c);
                trail += d * d;
            }
            ++n;
        }
    }
    std::printf("layers: background change per value %.6f, trail vs hidden background %.6f\n",
                per_value, trail / (3 * n));
    // Both far below the flicker of independently stylized frames.
    const double flicker = mean_warp_error(scene, independent(scene, style, AnimateOptions()));
    EXPECT_LT(per_value, 0.1 * flicker);
    EXPECT_LT(trail / (3 * n), 0.1 * flicker);
    EXPECT_LT(trail_redness(scene, r->frames[static_cast<std::size_t>(last)], last), -0.3);
    // The composite is the square layer on the square, the background elsewhere.
    EXPECT_EQ(r->frames[3].at(scene.square_x(3) + 5, scene.y0 + 5, 0),
              r->layers[1][3].at(scene.square_x(3) + 5, scene.y0 + 5, 0));
    EXPECT_EQ(r->frames[3].at(2, 2, 1), r->layers[0][3].at(2, 2, 1));
    // And the square keeps its coherence.
    EXPECT_LT(mean_warp_error(scene, r->frames), 0.002);
}

}  // namespace
}  // namespace exemplar::animate
