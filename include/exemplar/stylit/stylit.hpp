#pragma once
/// \file
/// StyLit (Fišer et al. 2016, thesis chapter 8): transfers an artist's painting of an exemplar
/// render onto a new render, guided by the light-path buffers of both renders.
///
/// The guides are the buffer pairs (exemplar render buffer A_i, target render buffer B_i); their
/// weights share the guidance influence µ = 2 of §8.3.4 equally (0.5 each for four buffers, as
/// the ebsynth example does), against weight 1 for the style term. Synthesis uses the engine's
/// error-budget strategy (§8.3.3) by default. The preview mode (§8.3.4) runs at half resolution
/// on PCA-compressed buffers; see preview.hpp.

#include <optional>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/stylit/lpe_buffers.hpp"
#include "exemplar/synth/synthesize.hpp"

namespace exemplar {

/// Options of a StyLit run.
struct StylitOptions {
    /// Engine options; the defaults are StyLit's (patch 5, error budget, ratio 1/2).
    SynthesisOptions synthesis;
    /// µ of Eq. 8.1: total weight of the buffers, split equally among them. Range 0..100,
    /// default 2.
    float guidance_weight = 2.0f;
    /// Preview mode: half resolution, buffers compressed by PCA (output at half size).
    bool preview = false;
    /// Preview: number of principal components kept (1..16, default 5; 3 lose the shading
    /// that tells the figure's lit side from its shadowed back, see docs/stylit.md).
    int preview_components = 5;
    /// Preview: engine options; unset = preview_synthesis_options(synthesis) (fewer iterations,
    /// see preview.hpp).
    std::optional<SynthesisOptions> preview_synthesis;
};

/// The synthesis input StyLit builds: the exemplar painting as style, one guide per buffer pair
/// with weight guidance_weight / count. Checks sizes and pairing (check_buffer_pairs) and the
/// options' ranges; messages name the buffers.
Result<SynthesisInput> stylit_input(const Image& exemplar, const std::vector<LpeBuffer>& source,
                                    const std::vector<LpeBuffer>& target,
                                    const StylitOptions& options);

/// What a run produced.
struct StylitResult {
    SynthesisResult synthesis;  ///< Output image (target size, or half of it in preview).
    int guide_channels = 0;     ///< Channels the patch distance compared on the buffers.
    /// Preview only: fraction of the weighted buffer variance the kept components explain.
    double explained_variance = 1.0;
};

/// Runs StyLit: stylit_input, then (preview) make_preview, then synthesize.
Result<StylitResult> stylize_render(const Image& exemplar, const std::vector<LpeBuffer>& source,
                                    const std::vector<LpeBuffer>& target,
                                    const StylitOptions& options, const RunContext& context = {});

}  // namespace exemplar
