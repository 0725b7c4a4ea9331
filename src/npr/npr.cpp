// The styles of image-space NPR: tone, orientation, thresholding with tone correction and line
// inking around the coordinate synthesis ("Image Space Texture Synthesis for 3D NPR Animation"
// §6: halftoning, §6.0.1 tone correction, the paper layer, §6.0.2 boundary erosion and
// silhouettes). Deviations: the silhouettes are the renderer's `lines` buffer inked as it is;
// the media simulation of Kalnins et al. 2002 is reduced to the paper's grain shading the
// result.

#include "exemplar/npr/npr.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>

#include "exemplar/core/option_table.hpp"
#include "exemplar/core/parallel.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/render/render.hpp"

namespace exemplar::npr {

namespace {

using O = NprOptions;

const std::array<NprOptionSpec, 6> kSpecs{{
    {"levels",
     "Pyramid levels of the coordinate synthesis (the paper's L + 1). The pattern needs "
     "patch-size x 2^(levels-1) pixels on a side.",
     "", 1, 6, &O::levels},
    {"patch-size",
     "Initialization patch in coarsest-level pixels (the paper's 10-14); larger keeps longer "
     "stretches of the pattern together.",
     "px", 3, 32, &O::patch_size},
    {"coherence-weight",
     "beta: weight of the temporal coherence term against the texture term (weight 1). Higher "
     "= steadier elements, which then grow and shrink with a camera zoom.",
     "", 0, 100, &O::coherence_weight},
    {"motion-levels",
     "Pyramid levels, from the coarsest, whose correction also tries the previous frame's "
     "coordinate at each pixel's advected position. 0 = the previous frame enters through the "
     "coarsest level's patches and the coherence term: the pattern keeps its size under a "
     "camera zoom. More = steadier on rotations, but the pattern grows with a zoom (all levels: "
     "2x under a 2x zoom, as texture mapping).",
     "", 0, 6, &O::motion_levels},
    {"paper-grain",
     "With --paper: how much the paper texture's dark parts darken the white (0 = no grain).", "",
     0, 1, &O::paper_grain},
    {"erosion",
     "With --paper: width of the shape boundary's erosion by the paper noise (the blur of the "
     "alpha mask).",
     "px", 0.5, 20, &O::erosion_px},
}};

std::string size_text(const Image& image) {
    return std::to_string(image.width()) + "x" + std::to_string(image.height());
}

// How many channels a style reads from a buffer.
int channels_used(BufferRole role) {
    return role == BufferRole::BackwardFlow ? 2 : 1;
}

bool thresholded(Style style) {
    return style != Style::Pattern;
}

// §6.0.2: outside the shape (mask ≤ 0.5) and where the mask blurred by erosion_px falls to
// 0.5 + 0.45·paper or below (a band along the boundary, uneven with the paper's noise) the
// image becomes paper; everything is then shaded by the paper's grain.
void on_paper(Image& image, const Image& mask, const Image& paper, const NprOptions& options,
              int threads) {
    const Image shape = extract_channels(mask, 0, 1);
    const Image soft = gaussian_blur(shape, options.erosion_px, threads);
    parallel_for(0, image.height(), threads, [&](int y) {
        for (int x = 0; x < image.width(); ++x) {
            const float grain = paper.at(x, y, 0);
            const bool kept = shape.at(x, y, 0) > 0.5f && soft.at(x, y, 0) > 0.5f + 0.45f * grain;
            const float value = kept ? image.at(x, y, 0) : 1.0f;
            image.at(x, y, 0) = value * (1.0f - options.paper_grain * (1.0f - grain));
        }
    });
}

}  // namespace

std::string_view to_string(Style style) {
    switch (style) {
        case Style::Stipple: return "stipple";
        case Style::Halftone: return "halftone";
        case Style::Hatch: return "hatch";
        case Style::Pattern: return "pattern";
    }
    return "stipple";
}

Result<Style> parse_style(std::string_view name) {
    for (Style style : {Style::Stipple, Style::Halftone, Style::Hatch, Style::Pattern})
        if (name == to_string(style)) return style;
    return invalid_argument("style: '" + std::string(name) +
                            "' is invalid (must be one of stipple, hatch, halftone, pattern)");
}

std::span<const NprOptionSpec> npr_option_specs() {
    return kSpecs;
}

double get_option(const NprOptions& options, const NprOptionSpec& spec) {
    return get_table_option(options, spec);
}

Status set_option(NprOptions& options, const NprOptionSpec& spec, double value) {
    return set_table_option(options, spec, value);
}

Status validate(const NprOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(
        validate_table_options(options, std::span<const NprOptionSpec>(kSpecs)));
    if (options.style == Style::Pattern && options.tone)
        return invalid_argument("tone: not used by style pattern (it shows no tone)");
    if (options.tone && options.tone->empty())
        return invalid_argument("tone: the buffer name is empty");
    if (options.orientation && options.orientation->empty())
        return invalid_argument("orientation: the buffer name is empty (none = no orientation)");
    return Status::ok();
}

Result<Pattern> prepare_pattern(const Image& pattern, const NprOptions& options,
                                const RunContext& context) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    PatternOptions pattern_options;
    pattern_options.levels = options.levels;
    // The coarsest level's patches span patch-size x 2^(levels-1) pattern pixels
    const int min_size = options.patch_size << (options.levels - 1);
    return prepare_pattern(pattern, pattern_options, min_size, context.threads);
}

std::string frame_buffer_file(const std::string& folder, const std::string& name) {
    for (const char* extension : {".exr", ".png"}) {
        const std::filesystem::path path = std::filesystem::path(folder) / (name + extension);
        std::error_code ec;
        if (std::filesystem::is_regular_file(path, ec)) return path.string();
    }
    return "";
}

std::vector<BufferNeed> needed_buffers(const NprOptions& options, bool continues) {
    std::vector<BufferNeed> needs;
    if (thresholded(options.style))
        needs.push_back({BufferRole::Tone, options.tone.value_or("direct_diffuse")});
    const std::string orientation =
        options.orientation.value_or(options.style == Style::Hatch ? "orientation" : "none");
    if (orientation != "none") needs.push_back({BufferRole::Orientation, orientation});
    if (continues) {
        needs.push_back({BufferRole::BackwardFlow, "backward_flow"});
        needs.push_back({BufferRole::Disocclusion, "disocclusion"});
    }
    if (options.paper) needs.push_back({BufferRole::Mask, "alpha"});
    // Without other buffers `lines` gives the frame's size (the renderer always writes it)
    if (options.lines || needs.empty()) needs.push_back({BufferRole::Lines, "lines"});
    return needs;
}

Image& NprFrame::operator[](BufferRole role) {
    return const_cast<Image&>(std::as_const(*this)[role]);
}

const Image& NprFrame::operator[](BufferRole role) const {
    switch (role) {
        case BufferRole::Tone: return tone;
        case BufferRole::Orientation: return orientation;
        case BufferRole::BackwardFlow: return backward_flow;
        case BufferRole::Disocclusion: return disocclusion;
        case BufferRole::Lines: return lines;
        case BufferRole::Mask: return mask;
    }
    return tone;
}

Result<Image> delayed_visibility(const Image& previous, const Image& disocclusion,
                                 const Image& backward_flow) {
    const int width = disocclusion.width(), height = disocclusion.height();
    if (backward_flow.width() != width || backward_flow.height() != height ||
        backward_flow.channels() < 2 ||
        (!previous.empty() && (previous.width() != width || previous.height() != height)))
        return invalid_argument("delayed visibility: the disocclusion (" + size_text(disocclusion) +
                                "), backward flow (" + size_text(backward_flow) +
                                ") and previous visibility differ in size");
    Image visible(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (disocclusion.at(x, y, 0) > 0.5f) continue;
            const int px = static_cast<int>(std::lround(x + backward_flow.at(x, y, 0)));
            const int py = static_cast<int>(std::lround(y + backward_flow.at(x, y, 1)));
            if (px < 0 || py < 0 || px >= width || py >= height) continue;
            visible.at(x, y, 0) = previous.empty() || previous.at(px, py, 0) > 0.5f ? 1.0f : 0.0f;
        }
    return visible;
}

Result<NprFrameResult> stylize_frame(const Pattern& pattern, const NprFrame& frame,
                                     const FrameState* previous, int frame_index,
                                     const NprOptions& options, const RunContext& context,
                                     const NprPaper& paper) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    for (const Pattern* p : {&pattern, paper.pattern})
        if (p != nullptr && static_cast<int>(p->stack.size()) != options.levels)
            return invalid_argument(std::string(p == &pattern ? "pattern" : "paper") +
                                    ": prepared with " + std::to_string(p->stack.size()) +
                                    " levels but levels is " + std::to_string(options.levels));
    if (options.paper != (paper.pattern != nullptr))
        return invalid_argument(options.paper ? "paper: the paper layer needs a paper pattern"
                                              : "paper: a paper pattern is given but the paper "
                                                "layer is off");

    // The buffers: each needed one given, with its channels, all of the first one's size
    const std::vector<BufferNeed> needs = needed_buffers(options, previous != nullptr);
    FrameInput input;
    for (const BufferNeed& need : needs) {
        const Image& image = frame[need.role];
        if (image.empty()) return invalid_argument("missing buffer '" + need.name + "'");
        if (image.channels() < channels_used(need.role))
            return invalid_argument("buffer '" + need.name + "' has " +
                                    std::to_string(image.channels()) + " channels (needs " +
                                    std::to_string(channels_used(need.role)) + ")");
        if (input.width == 0) {
            input.width = image.width();
            input.height = image.height();
        } else if (image.width() != input.width || image.height() != input.height) {
            return invalid_argument("buffer '" + need.name + "' is " + size_text(image) +
                                    " but the frames are " + std::to_string(input.width) + "x" +
                                    std::to_string(input.height));
        }
        if (need.role == BufferRole::Orientation)
            input.orientation = extract_channels(image, 0, 1);
        else if (need.role == BufferRole::BackwardFlow)
            input.backward_flow = extract_channels(image, 0, 2);
        else if (need.role == BufferRole::Disocclusion)
            input.disocclusion = extract_channels(image, 0, 1);
    }
    if (!frame.hold.empty()) {
        input.hold = extract_channels(frame.hold, 0, 1);
        input.held = frame.held;
    }
    if (previous != nullptr && !previous->coords.empty() &&
        (previous->coords[0].width() != input.width ||
         previous->coords[0].height() != input.height))
        return invalid_argument("frame size differs from the previous frame's (" +
                                size_text(previous->coords[0]) + ")");

    // Synthesize the screen
    SynthesisOptions synthesis;
    synthesis.init_patch_size = options.patch_size;
    synthesis.coherence_weight = options.coherence_weight;
    synthesis.motion_levels = options.motion_levels;
    synthesis.seed = options.seed;
    // With the paper, each synthesis reports its share of the frame (the pattern's first half)
    const auto share = [&](double start) {
        return options.paper ? context.part(start, 0.5, 1.0) : context;
    };
    auto state = synthesize_frame(pattern, input, previous, frame_index, synthesis, share(0.0));
    if (!state.ok()) return state.status();
    // and the paper, the same way along the same motion, unoriented and with its own randomness
    Result<FrameState> paper_state = FrameState{};
    if (options.paper) {
        FrameInput paper_input = input;
        paper_input.orientation = Image();
        paper_input.held = paper.held;
        SynthesisOptions paper_synthesis = synthesis;
        paper_synthesis.seed = options.seed ^ 0x7061706572ull;  // "paper"
        paper_state = synthesize_frame(*paper.pattern, paper_input, paper.previous, frame_index,
                                       paper_synthesis, share(0.5));
        if (!paper_state.ok()) return paper_state.status();
    }

    // Threshold it against the tone (luma of the sRGB-encoded buffer, in [0, 1])
    NprFrameResult result;
    if (thresholded(options.style)) {
        Image tone = to_grey(frame.tone_linear ? render::encode_srgb(frame.tone) : frame.tone);
        for (float& v : tone.data()) v = std::clamp(v, 0.0f, 1.0f);
        HalftoneOptions halftone_options;
        halftone_options.tone_correction = options.tone_correction;
        result.image = halftone(state->screen, tone, halftone_options, context.threads);
    } else {
        result.image = state->screen;
    }
    // Lay it on the paper, eroding the shape's boundary by the paper's noise
    if (options.paper)
        on_paper(result.image, frame.mask, paper_state->screen, options, context.threads);
    // Ink the lines
    if (options.lines) {
        for (int y = 0; y < result.image.height(); ++y)
            for (int x = 0; x < result.image.width(); ++x)
                if (frame.lines.at(x, y, 0) > 0.5f) result.image.at(x, y, 0) = 0.0f;
    }
    result.state = std::move(state).value();
    result.paper_state = std::move(paper_state).value();
    return result;
}

}  // namespace exemplar::npr
