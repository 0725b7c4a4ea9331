// Color Me Noisy (Fišer et al. 2014; thesis chapter 4): per-frame synthesis with a low-passed
// source pyramid, the target's coarsest level taken from the low-passed reference frame, a
// random rigid-MLS pre-deformation of the source and a PatchMatch seed per frame.
//
// Built on the engine's public API: one synthesize() call per pyramid level (levels = 1), each
// with its own low-passed source and an initial target upsampled from the level before, so the
// engine is untouched. Deviations from the chapter:
// - the M-step is the engine's weighted average whose last vote per level uses the central 3x3
//   of each patch (SynthesisOptions defaults), not Wexler's mode;
// - the solution is carried between levels as an image (Lanczos-3 upsampling) and, by default,
//   as a nearest-neighbour field too (upsample_nnf, as the engine does between its own levels):
//   a level whose pixels all continue from the level before runs warm-em-iterations x
//   warm-search-iterations (1 x 2) from that field instead of the chapter's 4 x 8 from a random
//   one, about 10x less work per frame for the same evidence (docs/noisy.md, "Speed");
//   warm-search-iterations 0 restores the chapter's schedule;
// - local choice of source (§4.3.3; the chapter leaves its details to the supplementary
//   material): media side by side as one engine source with a label each, the source map as
//   the target's labels; the reference is low-passed within each region of the map, so a
//   region's start and coarse guide carry no other region's colours;
// - patches are rotated only by orientation fields (§4.3.3), never reflected, and there is no
//   free rotation search (the chapter allows rotations and reflections in eq. 4.1).

#include "exemplar/noisy/noisy.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "exemplar/core/option_table.hpp"
#include "exemplar/core/rng.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/noisy/mls.hpp"
#include "exemplar/synth/synthesize.hpp"

namespace exemplar::noisy {

namespace {

using O = NoisyOptions;

const std::array<NoisyOptionSpec, 11> kSpecs{{
    {"noise",
     "Low-pass strength f: width of the box separating the reference's low frequencies (kept) "
     "from the details (re-synthesized at random in every frame). Larger = more temporal "
     "noise; <= 1 = the least (finest level only). At most min side / patch-size.",
     "px", 0, 256, &O::noise},
    {"level-ratio",
     "Ratio of the sampling rates of consecutive pyramid levels between strength f and 1 "
     "(chapter: 0.85).",
     "", 0.5, 0.95, &O::level_ratio},
    {"patch-size", "Patch width; odd (chapter: 7).", "px", 3, 31, &O::patch_size},
    {"em-iterations", "Search+vote iterations per pyramid level (chapter: 4).", "iterations", 1,
     100, &O::em_iterations},
    {"search-iterations", "PatchMatch iterations per nearest-neighbour search (chapter: 8).",
     "iterations", 1, 100, &O::search_iterations},
    {"warm-search-iterations",
     "PatchMatch iterations per search on a level whose pixels all continue from the level "
     "before, starting from its upsampled field; 0 = a random field and the chapter's "
     "em-iterations x search-iterations on every level.",
     "iterations", 0, 100, &O::warm_search_iterations},
    {"warm-em-iterations",
     "Search+vote iterations on such a level (with warm-search-iterations > 0).", "iterations", 1,
     100, &O::warm_em_iterations},
    {"lattice-spacing",
     "Spacing of the control lattice of the random rigid-MLS pre-deformation of the source, "
     "in source pixels (chapter: 50).",
     "px", 4, 10000, &O::lattice_spacing_px},
    {"min-offset",
     "Shortest random move of a lattice point (chapter: 15); 0 with max-offset 0 turns the "
     "pre-deformation off.",
     "px", 0, 1000, &O::min_offset_px},
    {"max-offset", "Longest random move of a lattice point (chapter: 25).", "px", 0, 1000,
     &O::max_offset_px},
    {"coarse-weight",
     "Weight of the low-passed reference as a guide on every level (coarse consistency, eq. "
     "4.2, as a term of the patch distance); 0 = only the coarsest level starts from it.",
     "", 0, 100, &O::coarse_weight},
}};

bool same_name(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const char x = a[i] == '_' ? '-' : a[i], y = b[i] == '_' ? '-' : b[i];
        if (x != y) return false;
    }
    return true;
}

int scaled_size(int size, double strength) {
    return std::max(1, static_cast<int>(std::lround(size / strength)));
}

// The reference in the source's channel count: grey replicated, alpha dropped or added as 1.
Result<Image> to_channels(const Image& image, int channels) {
    const int have = image.channels();
    if (have == channels) return image;
    const int colour_have = have == 2 || have == 4 ? have - 1 : have;
    const int colour_want = channels == 2 || channels == 4 ? channels - 1 : channels;
    if (colour_have != colour_want && colour_have != 1) {
        return invalid_argument("reference: has " + std::to_string(have) +
                                " channels but the source has " + std::to_string(channels) +
                                " (give grey, RGB or RGBA frames for an RGB or RGBA source)");
    }
    Image out(image.width(), image.height(), channels);
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            const float* in = image.pixel(x, y);
            float* o = out.pixel(x, y);
            for (int c = 0; c < colour_want; ++c) o[c] = in[colour_have == 1 ? 0 : c];
            if (colour_want != channels) o[channels - 1] = colour_have != have ? in[have - 1] : 1;
        }
    }
    return out;
}

// Images side by side, left to right and top-aligned, on a ground of `ground` (one image is
// returned as it is): a level's sources as the engine's one source.
Image side_by_side(const std::vector<Image>& images, float ground = 0.0f) {
    if (images.size() == 1) return images.front();
    int width = 0, height = 0;
    for (const Image& image : images) {
        width += image.width();
        height = std::max(height, image.height());
    }
    Image out(width, height, images.front().channels(), ground);
    int x0 = 0;
    for (const Image& image : images) {
        for (int y = 0; y < image.height(); ++y) {
            std::copy_n(image.pixel(0, y),
                        static_cast<std::size_t>(image.width()) * image.channels(),
                        out.pixel(x0, y));
        }
        x0 += image.width();
    }
    return out;
}

// Each image resized to the size of its counterpart in `sizes`.
std::vector<Image> resized_like(const std::vector<Image>& images, const std::vector<Image>& sizes,
                                ResampleFilter filter, int threads) {
    std::vector<Image> out;
    for (std::size_t k = 0; k < images.size(); ++k) {
        out.push_back(resize(images[k], sizes[k].width(), sizes[k].height(), filter, threads));
    }
    return out;
}

// The reference low-passed within each region of the source map (normalized convolution): per
// region k, the low-pass of R·1_k over that of 1_k, so no region's low frequencies carry another
// region's colours across the map's boundaries. `region_parts` returns them at strength f,
// `within_regions` combines them on a level where the map's label is k.
struct RegionParts {
    std::vector<Image> weighted;  // h_f * (R·1_k)
    std::vector<Image> weights;   // h_f * 1_k
};

RegionParts region_parts(const Image& reference, const Image& map, std::size_t regions,
                         double strength, LowPassFilter filter, int threads) {
    RegionParts parts;
    for (std::size_t k = 0; k < regions; ++k) {
        Image inside(map.width(), map.height(), 1, 0.0f);
        Image weighted(reference.width(), reference.height(), reference.channels(), 0.0f);
        for (int y = 0; y < map.height(); ++y) {
            for (int x = 0; x < map.width(); ++x) {
                if (std::lround(map.at(x, y, 0)) != static_cast<long>(k)) continue;
                inside.at(x, y, 0) = 1.0f;
                std::copy_n(reference.pixel(x, y), reference.channels(), weighted.pixel(x, y));
            }
        }
        parts.weighted.push_back(low_pass(weighted, strength, filter, threads));
        parts.weights.push_back(low_pass(inside, strength, filter, threads));
    }
    return parts;
}

// `fallback` (the plain low-pass, the level's size) where a region's weight is too small to
// divide by (a region thinner than the filter's support on this level).
Image within_regions(const RegionParts& parts, const Image& labels, Image fallback) {
    for (int y = 0; y < fallback.height(); ++y) {
        for (int x = 0; x < fallback.width(); ++x) {
            const auto k = static_cast<std::size_t>(std::lround(labels.at(x, y, 0)));
            const float weight = parts.weights[k].at(x, y, 0);
            if (!(weight > 1e-3f)) continue;
            for (int c = 0; c < fallback.channels(); ++c) {
                fallback.at(x, y, c) = parts.weighted[k].at(x, y, c) / weight;
            }
        }
    }
    return fallback;
}

}  // namespace

std::string_view to_string(LowPassFilter filter) {
    return filter == LowPassFilter::Box ? "box" : "lanczos3";
}

Result<LowPassFilter> parse_low_pass_filter(std::string_view name) {
    if (name == "box") return LowPassFilter::Box;
    if (name == "lanczos3") return LowPassFilter::Lanczos3;
    return invalid_argument("filter: '" + std::string(name) +
                            "' is invalid (must be one of box, lanczos3)");
}

std::span<const NoisyOptionSpec> noisy_option_specs() {
    return kSpecs;
}

const NoisyOptionSpec* find_noisy_option(std::string_view name) {
    for (const NoisyOptionSpec& spec : kSpecs) {
        if (same_name(spec.name, name)) return &spec;
    }
    return nullptr;
}

double get_option(const NoisyOptions& options, const NoisyOptionSpec& spec) {
    return get_table_option(options, spec);
}

Status set_option(NoisyOptions& options, const NoisyOptionSpec& spec, double value) {
    // Patches are odd
    return set_table_option(options, spec, value, spec.name == "patch-size");
}

Status validate(const NoisyOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(validate_table_options(
        options, std::span<const NoisyOptionSpec>(kSpecs),
        [](NoisyOptions& o, const NoisyOptionSpec& spec, double value) {
            // Any seed is valid in the library; the table's range is the flag's.
            if (std::holds_alternative<std::uint64_t NoisyOptions::*>(spec.field)) {
                return Status::ok();
            }
            return set_option(o, spec, value);
        }));
    if (options.min_offset_px > options.max_offset_px) {
        return invalid_argument("min-offset: " + format_option_number(options.min_offset_px) +
                                " is invalid (must be at most max-offset, " +
                                format_option_number(options.max_offset_px) + ")");
    }
    if (options.filter != LowPassFilter::Box && options.filter != LowPassFilter::Lanczos3) {
        return invalid_argument("filter: is invalid (must be one of box, lanczos3)");
    }
    return Status::ok();
}

std::vector<double> level_strengths(double noise, double level_ratio) {
    if (!(noise > 1.0)) return {1.0};
    // The fewest steps from f to 1 whose ratio is at least level_ratio.
    const int steps =
        std::max(1, static_cast<int>(std::ceil(std::log(noise) / -std::log(level_ratio) - 1e-9)));
    std::vector<double> strengths(static_cast<std::size_t>(steps) + 1);
    for (int k = 0; k <= steps; ++k) {
        strengths[static_cast<std::size_t>(k)] =
            k == steps ? 1.0 : std::pow(noise, static_cast<double>(steps - k) / steps);
    }
    return strengths;
}

Image low_pass(const Image& image, double strength, LowPassFilter filter, int threads) {
    if (strength <= 1.0) return image;
    return resize(
        image, scaled_size(image.width(), strength), scaled_size(image.height(), strength),
        filter == LowPassFilter::Box ? ResampleFilter::Box : ResampleFilter::Lanczos3, threads);
}

Result<Image> synthesize_frame(const Image& source, const NoisyFrame& frame,
                               const NoisyOptions& options, std::int64_t frame_index,
                               const RunContext& context) {
    return synthesize_frame(source, Image(), frame, options, frame_index, context);
}

Result<Image> synthesize_frame(const Image& source, const Image& source_orientation,
                               const NoisyFrame& frame, const NoisyOptions& options,
                               std::int64_t frame_index, const RunContext& context) {
    const NoisySource one{source, source_orientation};
    return synthesize_frame(std::span<const NoisySource>(&one, 1), frame, options, frame_index,
                            context);
}

Status check_source_map(const Image& map, std::size_t sources) {
    if (map.channels() != 1) {
        return invalid_argument("has " + std::to_string(map.channels()) +
                                " channels (must be 1: a source number per pixel)");
    }
    for (int y = 0; y < map.height(); ++y) {
        for (int x = 0; x < map.width(); ++x) {
            const float v = map.at(x, y, 0);
            if (std::isfinite(v) && std::lround(v) >= 0 &&
                static_cast<std::size_t>(std::lround(v)) < sources) {
                continue;
            }
            return invalid_argument("value " + format_option_number(v) + " at (" +
                                    std::to_string(x) + ", " + std::to_string(y) +
                                    ") has no source (" + std::to_string(sources) + " given: 0.." +
                                    std::to_string(sources - 1) + ")");
        }
    }
    return Status::ok();
}

Result<Image> synthesize_frame(std::span<const NoisySource> sources, const NoisyFrame& frame,
                               const NoisyOptions& options, std::int64_t frame_index,
                               const RunContext& context) {
    // Check the inputs.
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (sources.empty()) return invalid_argument("sources: none given (need at least one)");
    const bool several = sources.size() > 1;
    auto source_name = [&](std::size_t k) {
        return several ? "source " + std::to_string(k) : std::string("source");
    };
    const Image& source = sources.front().image;
    for (std::size_t k = 0; k < sources.size(); ++k) {
        const Image& image = sources[k].image;
        if (image.empty()) return invalid_argument(source_name(k) + ": is empty");
        if (image.channels() > 4) {
            return invalid_argument(source_name(k) + ": has " + std::to_string(image.channels()) +
                                    " channels (must be 1..4)");
        }
        if (image.channels() != source.channels()) {
            return invalid_argument(source_name(k) + ": has " + std::to_string(image.channels()) +
                                    " channels but source 0 has " +
                                    std::to_string(source.channels()) +
                                    " (every source needs the same channels)");
        }
        if (!all_finite(image))
            return invalid_argument(source_name(k) + ": contains NaN or infinity");
    }
    if (frame.reference.empty()) return invalid_argument("reference: is empty");
    if (!all_finite(frame.reference)) {
        return invalid_argument("reference: contains NaN or infinity");
    }
    Result<Image> converted = to_channels(frame.reference, source.channels());
    if (!converted.ok()) return converted.status();
    const Image& reference = converted.value();
    const int width = reference.width(), height = reference.height();
    if (!frame.noise_map.empty()) {
        if (frame.noise_map.channels() != 1 || !frame.noise_map.same_size(reference)) {
            return invalid_argument("noise map: is " + size_str(frame.noise_map) + " with " +
                                    std::to_string(frame.noise_map.channels()) +
                                    " channels (must be 1 channel, " + size_str(reference) +
                                    " like the reference)");
        }
        for (float v : frame.noise_map.data()) {
            if (!(v >= 0.0f && v <= 1.0f)) {
                return invalid_argument("noise map: value " + format_option_number(v) +
                                        " is invalid (must be 0..1)");
            }
        }
    }
    if (several && frame.source_map.empty()) {
        return invalid_argument("source map: is required with " + std::to_string(sources.size()) +
                                " sources (it chooses one per pixel)");
    }
    if (!frame.source_map.empty()) {
        if (!frame.source_map.same_size(reference)) {
            return invalid_argument("source map: is " + size_str(frame.source_map) + " (must be " +
                                    size_str(reference) + " like the reference)");
        }
        const Status map_ok = check_source_map(frame.source_map, sources.size());
        if (!map_ok.is_ok()) return Status(map_ok.code(), "source map: " + map_ok.message());
    }
    const bool oriented = !sources.front().orientation.empty();
    if (oriented != !frame.orientation.empty()) {
        return invalid_argument(
            "orientation: give both the source's and the frame's orientation field, or neither");
    }
    for (std::size_t k = 0; k < sources.size(); ++k) {
        const Image& field = sources[k].orientation;
        if (field.empty() == oriented) {
            return invalid_argument(
                source_name(k) + " orientation: " + (oriented ? "is missing" : "is given") +
                " but " + source_name(0) + "'s " + (oriented ? "is given" : "is not") +
                " (give every source's orientation field, or none)");
        }
        if (oriented && (field.channels() != 1 || !field.same_size(sources[k].image))) {
            return invalid_argument(source_name(k) + " orientation: is " + size_str(field) +
                                    " with " + std::to_string(field.channels()) +
                                    " channels (must be 1 channel, " + size_str(sources[k].image) +
                                    " like the source)");
        }
        if (oriented && !all_finite(field)) {
            return invalid_argument("orientation: contains NaN or infinity");
        }
    }
    if (oriented) {
        if (frame.orientation.channels() != 1 || !frame.orientation.same_size(reference)) {
            return invalid_argument("frame orientation: is " + size_str(frame.orientation) +
                                    " with " + std::to_string(frame.orientation.channels()) +
                                    " channels (must be 1 channel, " + size_str(reference) +
                                    " like the reference)");
        }
        if (!all_finite(frame.orientation)) {
            return invalid_argument("orientation: contains NaN or infinity");
        }
    }
    const std::vector<double> strengths = level_strengths(options.noise, options.level_ratio);
    // The smallest source sets the largest strength.
    std::size_t smallest = 0;
    for (std::size_t k = 1; k < sources.size(); ++k) {
        const Image& a = sources[k].image;
        const Image& b = sources[smallest].image;
        if (std::min(a.width(), a.height()) < std::min(b.width(), b.height())) smallest = k;
    }
    const Image& small = sources[smallest].image;
    const int min_side = std::min({width, height, small.width(), small.height()});
    // The coarsest level must hold a (rotated) patch's footprint; with several sources, inside
    // every source's border, or the engine would drop the label groups on that level and mix
    // the media.
    const int radius = options.patch_size / 2;
    const int need = (oriented ? 2 * static_cast<int>(std::ceil(radius * std::sqrt(2.0))) + 1
                               : options.patch_size) +
                     (several ? 2 : 0);
    if (scaled_size(min_side, strengths.front()) < need) {
        return invalid_argument(
            "noise: " + format_option_number(options.noise) + " is too strong for the " +
            size_str(reference) + " reference and the " + size_str(small) + " " +
            source_name(smallest) + " with patch-size " + std::to_string(options.patch_size) +
            (oriented ? " and rotated patches" : "") + " (at most " +
            format_option_number(std::floor(100.0 * min_side / need) / 100.0) + ")");
    }

    // Randomly pre-deform each source (§4.3.2) so features do not fuse between frames.
    const int threads = context.threads;
    const auto index = static_cast<std::uint64_t>(frame_index);
    std::vector<Image> deformed, deformed_orientation;
    for (std::size_t k = 0; k < sources.size(); ++k) {
        const NoisySource& medium = sources[k];
        if (options.max_offset_px > 0.0f) {
            const ControlPoints lattice = jittered_lattice(
                medium.image.width(), medium.image.height(), options.lattice_spacing_px,
                options.min_offset_px, options.max_offset_px, hash_keys(options.seed, index, 1, k));
            const double smoothing = lattice_smoothing_px(options.lattice_spacing_px);
            deformed.push_back(deform_rigid(medium.image, lattice, smoothing, threads));
            if (oriented) {
                deformed_orientation.push_back(
                    deform_rigid_angles(medium.orientation, lattice, smoothing, threads));
            }
        } else {
            deformed.push_back(medium.image);
            if (oriented) deformed_orientation.push_back(medium.orientation);
        }
    }

    SynthesisOptions engine;
    engine.patch_size = options.patch_size;
    engine.levels = 1;
    engine.usage = UsageStrategy::None;
    // A level runs em x search iterations, every search alike.
    auto schedule = [&engine](int em, int search) {
        engine.em_iterations = engine.finest_em_iterations = em;
        engine.second_finest_em_iterations = em;
        engine.search_iterations = engine.warm_search_iterations = search;
        engine.finest_first_round_iterations = search;
    };
    const bool carry = options.warm_search_iterations > 0;
    RunContext inner(threads);
    inner.cancel = context.cancel;

    // The coarse-consistency guide pair: both low-passed at the full strength f.
    std::vector<Image> source_low;
    Image reference_low;
    RegionParts reference_regions;  // with several sources
    if (options.coarse_weight > 0.0f) {
        for (const Image& medium : deformed) {
            source_low.push_back(low_pass(medium, options.noise, options.filter, threads));
        }
        reference_low = low_pass(reference, options.noise, options.filter, threads);
        if (several) {
            reference_regions = region_parts(reference, frame.source_map, sources.size(),
                                             options.noise, options.filter, threads);
        }
    }

    // Coarse to fine; the coarsest target level is the low-passed reference (eq. 4.2).
    const int levels = static_cast<int>(strengths.size());
    Image current;
    Image previous_active;
    // The level before's nearest-neighbour field and its source's size (empty: none).
    Nnf field;
    int field_source_width = 0, field_source_height = 0;
    for (int k = 0; k < levels; ++k) {
        if (context.cancelled()) return cancelled();
        const double strength = strengths[static_cast<std::size_t>(k)];
        const int tw = scaled_size(width, strength), th = scaled_size(height, strength);
        Image start = low_pass(reference, strength, options.filter, threads);
        // With several sources each region starts from its own colours (see region_parts).
        const Image labels =
            several ? resize(frame.source_map, tw, th, ResampleFilter::Nearest, 1) : Image();
        if (several) {
            start = within_regions(region_parts(reference, frame.source_map, sources.size(),
                                                strength, options.filter, threads),
                                   labels, std::move(start));
        }

        // Pixels whose own strength f_p reaches this level's are synthesized (§4.3.3); the
        // others hold the low-passed reference until their level comes.
        Image active;
        bool all_active = true, none_active = true;
        if (!frame.noise_map.empty()) {
            active = resize(frame.noise_map, tw, th, ResampleFilter::Box, threads);
            for (float& v : active.data()) {
                v = (k + 1 == levels || options.noise * v >= strength * (1.0 - 1e-6)) ? 1.0f : 0.0f;
                all_active = all_active && v > 0.5f;
                none_active = none_active && v < 0.5f;
            }
        } else {
            none_active = false;
        }
        // Whether every pixel synthesized here was synthesized on the level before too: then
        // the level continues from that level's field with the warm schedule.
        bool continues = carry && !field.empty();
        if (k > 0) {
            const Image up = resize(current, tw, th, ResampleFilter::Lanczos3, threads);
            const Image was = previous_active.empty()
                                  ? Image()
                                  : resize(previous_active, tw, th, ResampleFilter::Nearest, 1);
            for (int y = 0; y < th; ++y) {
                for (int x = 0; x < tw; ++x) {
                    if (!was.empty() && was.at(x, y, 0) < 0.5f) {
                        if (active.empty() || active.at(x, y, 0) > 0.5f) continues = false;
                        continue;
                    }
                    std::copy_n(up.pixel(x, y), up.channels(), start.pixel(x, y));
                }
            }
        }
        previous_active = active;
        if (none_active) {
            current = std::move(start);
            field = Nnf();
            continue;
        }

        SynthesisInput input;
        // The level's sources side by side, each low-passed on its own, so no filter mixes
        // two media.
        std::vector<Image> media;
        for (const Image& medium : deformed) {
            media.push_back(low_pass(medium, strength, options.filter, threads));
        }
        input.style = side_by_side(media);
        input.target_width = tw;
        input.target_height = th;
        input.initial_target = std::move(start);
        // Patches that reach the source's border (read it repeated) are not used: the source
        // mask leaves out its outermost pixels. Random-search candidates clamped onto the
        // border are then rejected before their (slow, clamped) distance is computed.
        // With several sources each has its own border, so no patch spans two media, and its
        // own label: a pixel takes patches of the source its map value names only.
        input.source_mask = Image(input.style.width(), input.style.height(), 1, 0.0f);
        if (several) {
            input.source_labels = Image(input.style.width(), input.style.height(), 1, -1.0f);
        }
        for (int m = 0, x0 = 0; m < static_cast<int>(media.size()); ++m) {
            const Image& medium = media[static_cast<std::size_t>(m)];
            for (int y = 0; y < medium.height(); ++y) {
                for (int x = 0; x < medium.width(); ++x) {
                    const bool inside =
                        y >= 1 && y + 1 < medium.height() && x >= 1 && x + 1 < medium.width();
                    input.source_mask.at(x0 + x, y, 0) = inside ? 1.0f : 0.0f;
                    if (several) input.source_labels.at(x0 + x, y, 0) = static_cast<float>(m);
                }
            }
            x0 += medium.width();
        }
        if (several) input.target_labels = labels;
        if (!all_active) input.target_mask = std::move(active);
        if (options.coarse_weight > 0.0f) {
            GuidePair coarse;
            coarse.name = "low-passed reference";
            coarse.source =
                side_by_side(resized_like(source_low, media, ResampleFilter::Gaussian, threads));
            coarse.target = resize(reference_low, tw, th, ResampleFilter::Gaussian, threads);
            if (several) {
                RegionParts level;
                for (std::size_t m = 0; m < sources.size(); ++m) {
                    level.weighted.push_back(resize(reference_regions.weighted[m], tw, th,
                                                    ResampleFilter::Gaussian, threads));
                    level.weights.push_back(resize(reference_regions.weights[m], tw, th,
                                                   ResampleFilter::Gaussian, threads));
                }
                coarse.target = within_regions(level, labels, std::move(coarse.target));
            }
            coarse.weight = options.coarse_weight;
            // A pixel of lower noise m(p) < 1 follows h_{f m(p)} * R, which h_f * R would pull
            // towards blur; it starts from the reference on a finer level instead, so the
            // guide weighs it by m(p) (0 = held by that start alone).
            if (!frame.noise_map.empty()) {
                coarse.target_weight_map =
                    resize(frame.noise_map, tw, th, ResampleFilter::Box, threads);
            }
            input.guides.push_back(std::move(coarse));
        }
        if (oriented) {
            input.source_orientation =
                side_by_side(resized_like(deformed_orientation, media, ResampleFilter::Nearest, 1));
            input.target_orientation =
                resize(frame.orientation, tw, th, ResampleFilter::Nearest, 1);
        }
        // Start from the level before's field where there is one (pixels without one start at
        // random); the chapter's schedule unless every pixel continues.
        const int source_width = input.style.width(), source_height = input.style.height();
        if (carry && !field.empty()) {
            input.initial_nnf = upsample_nnf(field, field_source_width, field_source_height, tw, th,
                                             source_width, source_height);
            for (Match& m : input.initial_nnf.matches()) {
                if (m.x < 0) continue;
                m.x = std::clamp(m.x, 0, source_width - 1);
                m.y = std::clamp(m.y, 0, source_height - 1);
            }
        }
        if (continues) {
            schedule(options.warm_em_iterations, options.warm_search_iterations);
        } else {
            schedule(options.em_iterations, options.search_iterations);
        }
        // The engine's seeds are exact in a double (its option table): 53 bits.
        engine.seed = hash_keys(options.seed, index, 2, static_cast<std::uint64_t>(k)) >> 11;
        Result<SynthesisResult> result = synthesize(std::move(input), engine, inner);
        if (!result.ok()) return result.status();
        current = std::move(result.value().image);
        field = std::move(result.value().nnf);
        field_source_width = source_width;
        field_source_height = source_height;
        context.report(ProgressEvent{"level", k, levels, 0, 0, (k + 1.0) / levels});
    }
    return current;
}

}  // namespace exemplar::noisy
