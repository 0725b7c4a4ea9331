// Painting by Feature (Lukáč et al. 2013, thesis §3.3.2): the fill tool. Content-aware synthesis
// of a canvas region from a palette region with the engine, the palette region pre-rotated.

#include "exemplar/paint/feature_fill.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "exemplar/core/option_table.hpp"
#include "exemplar/synth/synthesize.hpp"

namespace exemplar::paint {
namespace {

using O = FeatureFillOptions;
const std::array<FeatureFillOptionSpec, 5> kSpecs{{
    {"patch-size", "Patch width of the synthesis, odd; larger keeps larger structures (ours).",
     "px", 3, 31, &O::patch_size},
    {"rotations",
     "Pre-rotated copies of the palette region over [-rotation-range, +rotation-range]; 1 = "
     "unrotated (ours; the chapter: 'a limited range of rotations').",
     "", 1, 36, &O::rotations},
    {"rotation-range", "Half-range of the pre-rotation angles (ours).", "deg", 0, 180,
     &O::rotation_range_deg},
    {"vote-histogram",
     "Colour-histogram weight of the vote: favours colours the fill lacks; 0 = off (default; "
     "with --usage uniform it overshoots, docs/feature.md).",
     "", 0, 100, &O::vote_histogram},
    {"polish-iterations",
     "Plain nearest-neighbour EM iterations on the finest level, from the layout the usage made "
     "on the coarser ones; 0 = the usage on the finest level too (ours: half the time at "
     "1 MPix, docs/feature.md).",
     "iterations", 0, 100, &O::polish_iterations},
}};

// Bounding box [x0, x1) x [y0, y1) of a mask's inside; empty (x0 >= x1) when it has none.
struct Box {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
Box inside_box(const Image& mask) {
    Box box{mask.width(), mask.height(), 0, 0};
    for (int y = 0; y < mask.height(); ++y) {
        for (int x = 0; x < mask.width(); ++x) {
            if (mask.at(x, y, 0) <= 0.5f) continue;
            box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x + 1),
                   std::max(box.y1, y + 1)};
        }
    }
    return box;
}

// True when some patch_size x patch_size window lies entirely inside `mask` (summed-area table).
bool holds_a_patch(const Image& mask, int patch_size) {
    const int w = mask.width(), h = mask.height();
    std::vector<int> sum(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1), 0);
    const auto at = [&](int x, int y) -> int& {
        return sum[static_cast<std::size_t>(y) * static_cast<std::size_t>(w + 1) +
                   static_cast<std::size_t>(x)];
    };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            at(x + 1, y + 1) =
                (mask.at(x, y, 0) > 0.5f ? 1 : 0) + at(x, y + 1) + at(x + 1, y) - at(x, y);
        }
    }
    const int p = patch_size;
    for (int y = 0; y + p <= h; ++y) {
        for (int x = 0; x + p <= w; ++x) {
            if (at(x + p, y + p) - at(x, y + p) - at(x + p, y) + at(x, y) == p * p) return true;
        }
    }
    return false;
}

}  // namespace

std::span<const FeatureFillOptionSpec> feature_fill_option_specs() {
    return kSpecs;
}

double get_option(const FeatureFillOptions& options, const FeatureFillOptionSpec& spec) {
    return get_table_option(options, spec);
}

Status set_option(FeatureFillOptions& options, const FeatureFillOptionSpec& spec, double value) {
    return set_table_option(options, spec, value, spec.name == "patch-size");
}

Status validate(const FeatureFillOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(
        validate_table_options(options, std::span<const FeatureFillOptionSpec>(kSpecs)));
    return parse_usage_strategy(to_string(options.usage)).status();
}

Image region_mask(const Image& region) {
    const int colours = region.channels() == 2 || region.channels() == 4 ? region.channels() - 1
                                                                         : region.channels();
    Image mask(region.width(), region.height(), 1);
    for (int y = 0; y < region.height(); ++y) {
        for (int x = 0; x < region.width(); ++x) {
            float sum = 0.0f;
            for (int c = 0; c < colours; ++c) sum += region.at(x, y, c);
            mask.at(x, y, 0) = sum > 0.5f * static_cast<float>(colours) ? 1.0f : 0.0f;
        }
    }
    return mask;
}

Image rotated_exemplar(const Image& palette, const Image& source_mask,
                       const FeatureFillOptions& options, Image& exemplar_mask) {
    // The region's bounding box, grown by half a patch (rotated copies read around it).
    const int r = options.patch_size / 2;
    Box box = inside_box(source_mask);
    box = {std::max(0, box.x0 - r), std::max(0, box.y0 - r), std::min(palette.width(), box.x1 + r),
           std::min(palette.height(), box.y1 + r)};
    const int bw = box.x1 - box.x0, bh = box.y1 - box.y0;
    const float cx = 0.5f * static_cast<float>(box.x0 + box.x1);
    const float cy = 0.5f * static_cast<float>(box.y0 + box.y1);

    // One copy per angle: its size holds the rotated box (same parity as the box, so the
    // unrotated copy reads the palette's pixels exactly).
    struct Copy {
        float angle = 0.0f;
        int width = 0, height = 0;
    };
    std::vector<Copy> copies;
    int atlas_width = 0, atlas_height = 0;
    for (int k = 0; k < options.rotations; ++k) {
        const float t =
            options.rotations == 1
                ? 0.0f
                : -1.0f + 2.0f * static_cast<float>(k) / static_cast<float>(options.rotations - 1);
        const float angle =
            t * options.rotation_range_deg * static_cast<float>(std::numbers::pi) / 180.0f;
        const float c = std::abs(std::cos(angle)), s = std::abs(std::sin(angle));
        int w = static_cast<int>(
            std::ceil(c * static_cast<float>(bw) + s * static_cast<float>(bh) - 1e-3f));
        int h = static_cast<int>(
            std::ceil(s * static_cast<float>(bw) + c * static_cast<float>(bh) - 1e-3f));
        w += (w - bw) & 1;
        h += (h - bh) & 1;
        copies.push_back({angle, w, h});
        atlas_width += w;
        atlas_height = std::max(atlas_height, h);
    }

    Image atlas(atlas_width, atlas_height, palette.channels());
    atlas.set_channel_names(palette.channel_names());
    exemplar_mask = Image(atlas_width, atlas_height, 1);
    const int channels = palette.channels();
    int x0 = 0;
    for (const Copy& copy : copies) {
        // Inverse rotation about the copy's centre onto the box's centre; bilinear, and inside
        // only where every tap with weight lies inside the region.
        const float ca = std::cos(copy.angle), sa = std::sin(copy.angle);
        const float ox = 0.5f * static_cast<float>(copy.width);
        const float oy = 0.5f * static_cast<float>(copy.height);
        for (int y = 0; y < copy.height; ++y) {
            for (int x = 0; x < copy.width; ++x) {
                const float dx = static_cast<float>(x) + 0.5f - ox;
                const float dy = static_cast<float>(y) + 0.5f - oy;
                // Continuous palette position, as a pixel index (centres at integers).
                const float u = cx + ca * dx + sa * dy - 0.5f;
                const float v = cy - sa * dx + ca * dy - 0.5f;
                const float fu = std::floor(u), fv = std::floor(v);
                const int iu = static_cast<int>(fu), iv = static_cast<int>(fv);
                const float au = u - fu, av = v - fv;
                const std::array<float, 4> weights{(1 - au) * (1 - av), au * (1 - av),
                                                   (1 - au) * av, au * av};
                bool inside = true;
                float* out = atlas.pixel(x0 + x, y);
                for (int tap = 0; tap < 4 && inside; ++tap) {
                    if (weights[tap] <= 1e-4f) continue;
                    const int px = iu + (tap & 1), py = iv + (tap >> 1);
                    if (px < box.x0 || py < box.y0 || px >= box.x1 || py >= box.y1 ||
                        source_mask.at(px, py, 0) <= 0.5f) {
                        inside = false;
                        break;
                    }
                    const float* in = palette.pixel(px, py);
                    for (int c = 0; c < channels; ++c) out[c] += weights[tap] * in[c];
                }
                if (!inside) {
                    std::fill_n(out, channels, 0.0f);
                    continue;
                }
                // Exact copies where a single tap carries the weight (the unrotated copy).
                for (int tap = 0; tap < 4; ++tap) {
                    if (weights[tap] < 1.0f - 1e-4f) continue;
                    std::copy_n(palette.pixel(iu + (tap & 1), iv + (tap >> 1)), channels, out);
                }
                exemplar_mask.at(x0 + x, y, 0) = 1.0f;
            }
        }
        x0 += copy.width;
    }
    return atlas;
}

Result<Image> fill_area(const Image& palette, const Image& source_region, const Image& canvas,
                        const Image& target_region, const FeatureFillOptions& options,
                        const RunContext& context) {
    // Checks: options, sizes, channels, the regions.
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (palette.empty()) return invalid_argument("palette: is empty");
    if (!source_region.same_size(palette)) {
        return invalid_argument("source region: is " + size_str(source_region) +
                                " but the palette is " + size_str(palette));
    }
    if (target_region.empty()) return invalid_argument("target region: is empty");
    if (!canvas.empty()) {
        if (!target_region.same_size(canvas)) {
            return invalid_argument("target region: is " + size_str(target_region) +
                                    " but the canvas is " + size_str(canvas));
        }
        if (canvas.channels() != palette.channels()) {
            return invalid_argument("canvas: has " + std::to_string(canvas.channels()) +
                                    " channels but the palette has " +
                                    std::to_string(palette.channels()));
        }
    }
    const Image source_mask = region_mask(source_region);
    Image target_mask = region_mask(target_region);
    if (inside_box(source_mask).x0 >= inside_box(source_mask).x1) {
        return invalid_argument("source region: selects no pixel (white marks the region)");
    }
    if (inside_box(target_mask).x0 >= inside_box(target_mask).x1) {
        return invalid_argument("target region: selects no pixel (white marks the region)");
    }
    if (!holds_a_patch(source_mask, options.patch_size)) {
        const std::string p = std::to_string(options.patch_size);
        return invalid_argument("source region: holds no " + p + "x" + p +
                                " patch (smaller than the patch size)");
    }

    // The exemplar: the palette region at every angle, masked to the region's inside.
    SynthesisInput in;
    Image exemplar_mask;
    in.style = rotated_exemplar(palette, source_mask, options, exemplar_mask);
    in.source_mask = std::move(exemplar_mask);
    in.target_width = target_region.width();
    in.target_height = target_region.height();
    // The target: the region only, starting from the canvas, whose fixed pixels the border
    // patches match. Without a canvas the region is synthesized free-standing.
    if (!canvas.empty()) {
        in.target_mask = target_mask;
        in.initial_target = canvas;
    }

    SynthesisOptions so;
    so.patch_size = options.patch_size;
    so.usage = options.usage;
    so.vote_histogram = options.vote_histogram;
    so.seed = options.seed;
    so.budget_polish_iterations = options.polish_iterations;
    auto synthesized = synthesize(std::move(in), so, context);
    if (!synthesized.ok()) return synthesized.status();

    // Outside the region: the canvas, bit for bit (0 without one).
    Image out = std::move(synthesized->image);
    const int channels = out.channels();
    for (int y = 0; y < out.height(); ++y) {
        for (int x = 0; x < out.width(); ++x) {
            if (target_mask.at(x, y, 0) > 0.5f) continue;
            if (canvas.empty()) {
                std::fill_n(out.pixel(x, y), channels, 0.0f);
            } else {
                std::copy_n(canvas.pixel(x, y), channels, out.pixel(x, y));
            }
        }
    }
    out.set_channel_names(canvas.empty() ? palette.channel_names() : canvas.channel_names());
    return out;
}

Image with_channels(const Image& image, int channels) {
    if (image.channels() == channels) return image;
    Image out(image.width(), image.height(), channels, 1.0f);
    const int colours_in = image.channels() >= 3 ? 3 : 1;
    const int colours_out = channels >= 3 ? 3 : 1;
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            const float* in = image.pixel(x, y);
            float* o = out.pixel(x, y);
            for (int c = 0; c < colours_out; ++c) {
                o[c] = colours_in == 3 ? (colours_out == 3 ? in[c] : (in[0] + in[1] + in[2]) / 3)
                                       : in[0];
            }
            if (channels == 4 && image.channels() == 4) o[3] = in[3];
        }
    }
    return out;
}

Result<Image> fill_with_palette(const Image& palette, const Image& source_region,
                                const Image& canvas, const Image& target_region,
                                const FeatureFillOptions& options, const RunContext& context) {
    for (const auto& [image, name] :
         {std::pair{&palette, "palette: "}, std::pair{&canvas, "canvas: "}}) {
        const int c = image->channels();
        if (!image->empty() && c != 1 && c != 3 && c != 4) {
            return invalid_argument(std::string(name) + "has " + std::to_string(c) +
                                    " channels (must be grey, RGB or RGBA)");
        }
    }
    const int channels = canvas.empty() ? 4 : canvas.channels();
    return fill_area(with_channels(palette, channels), source_region, canvas, target_region,
                     options, context);
}

}  // namespace exemplar::paint
