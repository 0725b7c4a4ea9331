// LazyFluids (Jamriška, Fišer, Asente, Lu, Shechtman, Sýkora 2015, "LazyFluids: appearance
// transfer for fluid animations"; Fišer's thesis ch. 5) on the engine's public API: one
// exemplar::synthesize call per frame with
//   style  = the exemplar's premultiplied RGBA, alpha weighted 3 (eq. 5.9, 2nd term),
//   guide  = blurred alpha Z_α : X_α, weight η (eq. 5.9, 3rd term),
//   guide  = previous exemplar frame : previous output advected, weight λ with the per-pixel map
//            λ_q / λ of eq. 5.6, its alpha channel scaled by √3 (eq. 5.9, 4th and 5th terms),
//   labels = the boundary / interior segments of both (§5.4.2), so that the engine's uniform
//            usage (§5.4.1) counts K and R per segment,
//   target mask = the target's fluid (blurred alpha > l); outside stays transparent.
// Deviations: colours are premultiplied inside (the paper compares straight RGB, whose value
// under alpha 0 is arbitrary in real exemplars); "radius r" of the blur is used as the Gaussian's
// σ; the previous output is carried by semi-Lagrangian advection along frame t−1's forward
// motion sampled at the arrival pixel (the paper forward-warps; the simulator advects the same
// way, so a simulated target is followed exactly to first order); the target is synthesized
// only where it has fluid plus the engine's patch-radius ring (the paper's targets are whole
// frames).

#include "exemplar/fluid/lazy_fluids.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "exemplar/core/check.hpp"
#include "exemplar/core/option_table.hpp"
#include "exemplar/core/parallel.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "exemplar/video/warp.hpp"

namespace exemplar::fluid {

namespace {

// RGBA with the colour multiplied by alpha.
Image premultiplied(const Image& rgba) {
    Image out = rgba;
    for (std::size_t i = 0; i + 3 < out.size(); i += 4) {
        float* p = out.data().data() + i;
        p[3] = std::clamp(p[3], 0.0f, 1.0f);
        for (int c = 0; c < 3; ++c) p[c] *= p[3];
    }
    return out;
}

// Back to straight alpha; colour 0 where alpha is (almost) 0.
Image straight(const Image& rgba) {
    Image out = rgba;
    for (std::size_t i = 0; i + 3 < out.size(); i += 4) {
        float* p = out.data().data() + i;
        p[3] = std::clamp(p[3], 0.0f, 1.0f);
        for (int c = 0; c < 3; ++c) p[c] = p[3] > 1e-4f ? std::clamp(p[c] / p[3], 0.0f, 1.0f) : 0;
    }
    return out;
}

Image channel(const Image& image, int c) {
    Image out = extract_channels(image, c, 1);
    out.set_channel_names({"A"});
    return out;
}

// RGBA with its alpha channel multiplied by `scale` (folds a channel weight into a guide).
Image scale_alpha(Image rgba, float scale) {
    for (std::size_t i = 3; i < rgba.size(); i += 4) rgba.data()[i] *= scale;
    return rgba;
}

Status check_rgba(const char* name, const Image* image) {
    if (image == nullptr || image->empty())
        return invalid_argument(std::string(name) + " is missing");
    if (image->channels() != 4) {
        return invalid_argument(std::string(name) + " has " + std::to_string(image->channels()) +
                                " channels (must be RGBA, 4)");
    }
    return Status::ok();
}

Status check_size(const char* name, const Image& image, const Image& like, const char* like_name) {
    if (image.width() == like.width() && image.height() == like.height()) return Status::ok();
    return invalid_argument(std::string(name) + " is " + size_str(image) + " but " + like_name +
                            " is " + size_str(like));
}

Image rotated(const Image& in, int quarter_turns) {
    const int w = in.width(), h = in.height(), c = in.channels();
    const bool swap = quarter_turns % 2 == 1;
    Image out(swap ? h : w, swap ? w : h, c);
    for (int y = 0; y < out.height(); ++y) {
        for (int x = 0; x < out.width(); ++x) {
            int sx = x, sy = y;
            switch (quarter_turns) {
                case 1:
                    sx = w - 1 - y;
                    sy = x;
                    break;  // 90° counter-clockwise
                case 2:
                    sx = w - 1 - x;
                    sy = h - 1 - y;
                    break;  // 180°
                case 3:
                    sx = y;
                    sy = h - 1 - x;
                    break;  // 270°
                default: break;
            }
            std::copy_n(in.pixel(sx, sy), c, out.pixel(x, y));
        }
    }
    return out;
}

}  // namespace

std::span<const FluidOptionSpec> fluid_option_specs() {
    using O = FluidOptions;
    static const FluidOptionSpec specs[] = {
        {"patch-size", "Patch width (odd). Paper: 5", "px", 3, 15, &O::patch_size},
        {"temporal-weight",
         "lambda: weight of the previous output advected along the motion (0 = every frame on its "
         "own; 0 at emitters and in the first frame). Paper: 0.2",
         "", 0, 10, &O::temporal_weight},
        {"boundary-weight",
         "eta: weight of the blurred alpha guide; lower = more varied boundaries. Paper: 3", "", 0,
         100, &O::boundary_weight},
        {"alpha-weight", "Weight of the synthesized alpha channel (1 per colour channel). Paper: 3",
         "", 0, 100, &O::alpha_weight},
        {"blur-radius",
         "r: Gaussian blur (sigma) of the alpha masks before segmentation; scale with the "
         "resolution. Paper: 3",
         "px", 0, 50, &O::blur_radius_px},
        {"boundary-low", "l: blurred alpha above this is fluid (boundary or interior). Paper: 0.1",
         "", 0, 0.999, &O::boundary_low},
        {"boundary-high", "u: blurred alpha at or above this is interior. Paper: 0.9", "", 0.001, 1,
         &O::boundary_high},
        {"motion-blur",
         "Motion blur along the motion, sigma as a fraction of the motion's length (0 = off)", "",
         0, 2, &O::motion_blur},
        {"vote-histogram",
         "Colour-histogram weight of the vote: values the frame already holds more of than the "
         "exemplar weigh less, so the texture is not averaged flat (0 = the paper's vote). Ours: 2",
         "", 0, 100, &O::vote_histogram},
        {"vote-coherence",
         "Coherence weight of the vote (variance of the mapping discrepancy): patches whose "
         "neighbours map where they do outweigh the scattered matches between them, so the "
         "exemplar's fine grain is not averaged away (0 = the paper's vote). Ours: 2",
         "px^2", 0, 100, &O::vote_coherence},
        {"coherence-sweeps",
         "Sweeps in which stray matches of the uniform assignment take a neighbour's shifted "
         "exemplar patch (moves and swaps that keep every count K or K + 1): larger coherent "
         "pieces of the exemplar, less texture averaged away (0 = the paper's assignment). Ours: 2",
         "", 0, 100, &O::coherence_sweeps},
    };
    return specs;
}

double get_option(const FluidOptions& options, const FluidOptionSpec& spec) {
    return get_table_option(options, spec);
}

Status set_option(FluidOptions& options, const FluidOptionSpec& spec, double value) {
    const bool integral = std::holds_alternative<int FluidOptions::*>(spec.field);
    if (!(value >= spec.min && value <= spec.max) || (integral && value != std::round(value))) {
        std::ostringstream msg;
        msg << spec.name << ": " << value << " is invalid (must be "
            << (integral ? "an integer " : "") << spec.min << ".." << spec.max << ")";
        return invalid_argument(msg.str());
    }
    if (integral) {
        options.*std::get<int FluidOptions::*>(spec.field) = static_cast<int>(value);
    } else {
        options.*std::get<float FluidOptions::*>(spec.field) = static_cast<float>(value);
    }
    return Status::ok();
}

Status validate(const FluidOptions& o) {
    EXEMPLAR_RETURN_IF_ERROR(validate_table_options(o, fluid_option_specs()));
    if (o.patch_size % 2 == 0) {
        return invalid_argument("patch-size: " + std::to_string(o.patch_size) +
                                " is invalid (must be odd, 3..15)");
    }
    if (!(o.boundary_high > o.boundary_low)) {
        std::ostringstream msg;
        msg << "boundary-high: " << o.boundary_high << " is invalid (must be above boundary-low "
            << o.boundary_low << ")";
        return invalid_argument(msg.str());
    }
    return validate(o.synthesis);
}

Image segment(const Image& alpha, const FluidOptions& options, int threads) {
    Image a = channel(alpha, 0);
    if (options.blur_radius_px > 0.0f) a = gaussian_blur(a, options.blur_radius_px, threads);
    Image labels(a.width(), a.height(), 1);
    labels.set_channel_names({"segment"});
    for (std::size_t i = 0; i < a.size(); ++i) {
        const float v = a.data()[i];
        labels.data()[i] = static_cast<float>(v >= options.boundary_high ? kInterior
                                              : v > options.boundary_low ? kBoundary
                                                                         : kOutside);
    }
    return labels;
}

Image advect_along_motion(const Image& image, const Image& motion, int threads) {
    Image back = motion;
    for (float& v : back.data()) v = -v;
    auto warped = video::backward_warp(image, back, threads);
    EXEMPLAR_CHECK(warped.ok());
    return std::move(warped->image);
}

Image temporal_weight_map(const Image& alpha, const Image& advected_previous_alpha) {
    Image map(alpha.width(), alpha.height(), 1);
    map.set_channel_names({"weight"});
    for (int y = 0; y < alpha.height(); ++y) {
        for (int x = 0; x < alpha.width(); ++x) {
            const float appeared = alpha.at(x, y, 0) - advected_previous_alpha.at(x, y, 0);
            map.at(x, y, 0) = 1.0f - std::clamp(appeared, 0.0f, 1.0f);
        }
    }
    return map;
}

Image rotation_atlas(const Image& exemplar, int gap) {
    std::vector<Image> copies;
    for (int q = 0; q < 4; ++q) copies.push_back(rotated(exemplar, q));
    int width = -gap, height = 0;
    for (const Image& c : copies) {
        width += c.width() + gap;
        height = std::max(height, c.height());
    }
    Image atlas(width, height, exemplar.channels());
    atlas.set_channel_names(exemplar.channel_names());
    int x0 = 0;
    for (const Image& c : copies) {
        for (int y = 0; y < c.height(); ++y) {
            std::copy_n(c.pixel(0, y), static_cast<std::size_t>(c.width()) * c.channels(),
                        atlas.pixel(x0, y));
        }
        x0 += c.width() + gap;
    }
    return atlas;
}

Image motion_blur(const Image& image, const Image& motion, float strength, int threads) {
    if (strength <= 0.0f) return image;
    Image out(image.width(), image.height(), image.channels());
    out.set_channel_names(image.channel_names());
    parallel_for(0, image.height(), threads, [&](int y) {
        std::vector<float> sum(static_cast<std::size_t>(image.channels()));
        for (int x = 0; x < image.width(); ++x) {
            const float mx = motion.at(x, y, 0), my = motion.at(x, y, 1);
            const float length = std::hypot(mx, my);
            const float sigma = strength * length;
            if (!(sigma > 0.25f)) {
                std::copy_n(image.pixel(x, y), image.channels(), out.pixel(x, y));
                continue;
            }
            const int steps = static_cast<int>(std::ceil(length)) + 1;  // ~1 sample per pixel
            std::fill(sum.begin(), sum.end(), 0.0f);
            float total = 0.0f;
            for (int k = -steps; k <= steps; ++k) {
                const float s = static_cast<float>(k) / static_cast<float>(steps);
                const float d = s * length;
                const float w = std::exp(-d * d / (2 * sigma * sigma));
                const float px = static_cast<float>(x) + s * mx;
                const float py = static_cast<float>(y) + s * my;
                float v = 0.0f;
                if (!video::sample_bilinear(image, px, py, 0, v)) continue;
                for (int c = 0; c < image.channels(); ++c) {
                    video::sample_bilinear(image, px, py, c, v);
                    sum[static_cast<std::size_t>(c)] += w * v;
                }
                total += w;
            }
            for (int c = 0; c < image.channels(); ++c) {
                out.at(x, y, c) =
                    total > 0 ? sum[static_cast<std::size_t>(c)] / total : image.at(x, y, c);
            }
        }
    });
    return out;
}

Result<FluidFrameResult> synthesize_fluid_frame(const FluidFrameInput& in,
                                                const FluidOptions& options,
                                                const RunContext& context) {
    // Check the inputs.
    if (Status s = validate(options); !s.is_ok()) return s;
    if (Status s = check_rgba("exemplar", in.exemplar); !s.is_ok()) return s;
    const Image& previous_exemplar_in =
        in.previous_exemplar != nullptr ? *in.previous_exemplar : *in.exemplar;
    if (Status s = check_rgba("previous exemplar", &previous_exemplar_in); !s.is_ok()) return s;
    if (Status s = check_size("previous exemplar", previous_exemplar_in, *in.exemplar, "exemplar");
        !s.is_ok()) {
        return s;
    }
    if (in.target_alpha == nullptr || in.target_alpha->empty()) {
        return invalid_argument("target alpha is missing");
    }
    const Image& target_alpha_in = *in.target_alpha;
    const bool temporal = in.previous_output != nullptr && options.temporal_weight > 0.0f;
    if (in.previous_output != nullptr) {
        if (Status s = check_rgba("previous output", in.previous_output); !s.is_ok()) return s;
        if (Status s = check_size("previous output", *in.previous_output, target_alpha_in,
                                  "the target alpha");
            !s.is_ok()) {
            return s;
        }
        if (in.previous_motion == nullptr || in.previous_motion->channels() != 2) {
            return invalid_argument("previous motion is missing (needed with a previous output)");
        }
        if (Status s = check_size("previous motion", *in.previous_motion, target_alpha_in,
                                  "the target alpha");
            !s.is_ok()) {
            return s;
        }
    }
    if (in.motion != nullptr && options.motion_blur > 0.0f) {
        if (Status s = check_size("motion", *in.motion, target_alpha_in, "the target alpha");
            !s.is_ok()) {
            return s;
        }
    }
    const int threads = context.threads;

    // Exemplar: premultiplied, optionally with its rotated copies; segments from its alpha.
    const int gap = options.patch_size + 1;
    Image style = premultiplied(*in.exemplar);
    Image previous_style = premultiplied(previous_exemplar_in);
    if (options.rotations) {
        style = rotation_atlas(style, gap);
        previous_style = rotation_atlas(previous_style, gap);
    }
    Image source_alpha = channel(style, 3);
    Image target_alpha = channel(target_alpha_in, 0);
    for (float& v : target_alpha.data()) v = std::clamp(v, 0.0f, 1.0f);

    FluidFrameResult result;
    result.source_segments = segment(source_alpha, options, threads);
    result.target_segments = segment(target_alpha, options, threads);
    const bool source_has_fluid =
        std::any_of(result.source_segments.data().begin(), result.source_segments.data().end(),
                    [](float v) { return v != static_cast<float>(kOutside); });
    if (!source_has_fluid) {
        return invalid_argument("exemplar: no pixel has alpha above boundary-low " +
                                std::to_string(options.boundary_low) +
                                " (an RGB exemplar needs an alpha channel)");
    }
    Image target_mask(target_alpha.width(), target_alpha.height(), 1);
    for (std::size_t i = 0; i < target_mask.size(); ++i) {
        target_mask.data()[i] =
            result.target_segments.data()[i] != static_cast<float>(kOutside) ? 1.0f : 0.0f;
    }
    Image advected;
    if (in.previous_output != nullptr) {
        advected =
            advect_along_motion(premultiplied(*in.previous_output), *in.previous_motion, threads);
    }
    const bool any_fluid = std::any_of(target_mask.data().begin(), target_mask.data().end(),
                                       [](float v) { return v > 0.5f; });
    if (!any_fluid) {
        // Nothing to synthesize: a transparent frame.
        result.rgba = Image(target_alpha.width(), target_alpha.height(), 4);
        result.rgba.set_channel_names({"R", "G", "B", "A"});
        result.advected_previous = std::move(advected);
        return result;
    }

    // The engine's input (eq. 5.9).
    SynthesisInput input;
    input.style = style;
    input.style_channel_weights = {1.0f, 1.0f, 1.0f, options.alpha_weight};
    if (options.boundary_weight > 0.0f) {
        Image source_blurred = options.blur_radius_px > 0
                                   ? gaussian_blur(source_alpha, options.blur_radius_px, threads)
                                   : source_alpha;
        Image target_blurred = options.blur_radius_px > 0
                                   ? gaussian_blur(target_alpha, options.blur_radius_px, threads)
                                   : target_alpha;
        input.guides.push_back({"blurred alpha",
                                std::move(source_blurred),
                                std::move(target_blurred),
                                options.boundary_weight,
                                {}});
    }
    if (temporal) {
        result.temporal_weight_map = temporal_weight_map(target_alpha, channel(advected, 3));
        const float alpha_scale = std::sqrt(options.alpha_weight);
        input.guides.push_back({"previous frame", scale_alpha(previous_style, alpha_scale),
                                scale_alpha(advected, alpha_scale), options.temporal_weight,
                                result.temporal_weight_map});
    }
    input.target_width = target_alpha.width();
    input.target_height = target_alpha.height();
    input.target_mask = std::move(target_mask);
    input.initial_target = Image(target_alpha.width(), target_alpha.height(), 4);
    input.source_labels = result.source_segments;
    input.target_labels = result.target_segments;

    SynthesisOptions synthesis = options.synthesis;
    synthesis.patch_size = options.patch_size;
    synthesis.usage = options.uniform_usage ? UsageStrategy::Uniform : UsageStrategy::None;
    synthesis.vote_histogram = options.vote_histogram;
    synthesis.vote_coherence = options.vote_coherence;
    synthesis.uniform_coherence_sweeps = options.coherence_sweeps;

    auto run = synthesize(std::move(input), synthesis, context);
    if (!run.ok()) return run.status();

    // Back to straight alpha; outside the fluid the engine kept the transparent start.
    // Motion blur on the premultiplied colours, so transparent pixels do not darken the fluid.
    if (options.motion_blur > 0.0f && in.motion != nullptr) {
        result.rgba = straight(motion_blur(run->image, *in.motion, options.motion_blur, threads));
    } else {
        result.rgba = straight(run->image);
    }
    result.rgba.set_channel_names({"R", "G", "B", "A"});
    result.nnf = std::move(run->nnf);
    result.advected_previous = std::move(advected);
    return result;
}

}  // namespace exemplar::fluid
