// StyLit (Fišer et al. 2016, thesis chapter 8): buffer pairs become weighted guides (Eq. 8.1
// with µ split over the buffers), then the engine runs with the error-budget strategy (§8.3.3).
// Deviation: the paper weighs every buffer channel by µ; like the ebsynth StyLit example we
// split µ over the buffers (0.5 each for four), which keeps the balance between the style term
// and the guides independent of the number of buffers.

#include "exemplar/stylit/stylit.hpp"

#include <cmath>
#include <string>

#include "exemplar/stylit/preview.hpp"

namespace exemplar {

namespace {

Status check_stylit(const Image& exemplar, const std::vector<LpeBuffer>& source,
                    const std::vector<LpeBuffer>& target, const StylitOptions& options) {
    if (!(options.guidance_weight >= 0.0f && options.guidance_weight <= 100.0f)) {
        return invalid_argument("guidance weight: " + std::to_string(options.guidance_weight) +
                                " is invalid (must be 0..100; StyLit uses 2)");
    }
    if (options.preview_components < 1 || options.preview_components > 16) {
        return invalid_argument(
            "preview components: " + std::to_string(options.preview_components) +
            " is invalid (must be 1..16)");
    }
    if (exemplar.empty()) return invalid_argument("the exemplar painting is empty");
    return check_buffer_pairs(source, target, exemplar.width(), exemplar.height());
}

// Weight of every buffer pair: µ split equally.
float guide_weight(const std::vector<LpeBuffer>& source, const StylitOptions& options) {
    return options.guidance_weight / static_cast<float>(source.size());
}

}  // namespace

Result<SynthesisInput> stylit_input(const Image& exemplar, const std::vector<LpeBuffer>& source,
                                    const std::vector<LpeBuffer>& target,
                                    const StylitOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(check_stylit(exemplar, source, target, options));
    SynthesisInput input;
    input.style = exemplar;
    const float weight = guide_weight(source, options);
    for (std::size_t i = 0; i < source.size(); ++i) {
        input.guides.push_back({source[i].origin + " / " + target[i].origin,
                                source[i].image,
                                target[i].image,
                                weight,
                                {}});
    }
    return input;
}

Result<StylitResult> stylize_render(const Image& exemplar, const std::vector<LpeBuffer>& source,
                                    const std::vector<LpeBuffer>& target,
                                    const StylitOptions& options, const RunContext& context) {
    StylitResult result;
    SynthesisInput input;
    SynthesisOptions synthesis_options = options.synthesis;
    if (options.preview) {
        // Straight from the buffers: the full-size copies of stylit_input would only be halved.
        EXEMPLAR_RETURN_IF_ERROR(check_stylit(exemplar, source, target, options));
        synthesis_options =
            options.preview_synthesis.value_or(preview_synthesis_options(options.synthesis));
        std::vector<PreviewGuide> guides;
        for (std::size_t i = 0; i < source.size(); ++i)
            guides.push_back({&source[i].image, &target[i].image, guide_weight(source, options)});
        auto preview = make_preview(exemplar, guides, options.preview_components, context.threads);
        if (!preview.ok()) return preview.status();
        input = std::move(preview->input);
        result.guide_channels = preview->channels_after;
        result.explained_variance = preview->explained_variance;
    } else {
        auto full = stylit_input(exemplar, source, target, options);
        if (!full.ok()) return full.status();
        input = std::move(full).value();
        for (const GuidePair& guide : input.guides)
            result.guide_channels += guide.source.channels();
    }
    auto synthesis = synthesize(std::move(input), synthesis_options, context);
    if (!synthesis.ok()) return synthesis.status();
    result.synthesis = std::move(synthesis).value();
    return result;
}

}  // namespace exemplar
