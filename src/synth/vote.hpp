#pragma once
// Voting (the M-step of Kwatra et al. 2005 / Wexler et al. 2007): every target pixel becomes the
// weighted average of the values that the overlapping patches of the NNF map onto it. Written as
// a gather over the target so that each output pixel is owned by one task (deterministic).

#include <cstdint>
#include <span>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/synth/nnf.hpp"

namespace exemplar::synth {

struct VoteParams {
    int patch_size = 5;
    /// Only the central footprint x footprint pixels of each patch vote (odd; 0 = the whole
    /// patch). A pixel that no patch centre within footprint / 2 covers (near the border, where
    /// pixels are not patch centres) takes the whole patches that overlap it.
    int footprint = 0;
    /// With a footprint narrower than the patch: pixels where the patches centred within the
    /// footprint disagree on their source pixel (a seam between differently mapped pieces) take
    /// the plain, unweighted average of the whole patches over them instead, so seams blend as
    /// in a plain whole-patch vote while the interiors of pieces keep the footprint's grain.
    bool blend_seams = false;
    const std::uint8_t* active = nullptr;  ///< Patches that vote (nullptr = all).
    const std::uint8_t* fixed = nullptr;   ///< Pixels left untouched (nullptr = none).
    /// Optional weight of each target patch's vote (the weighted-vote hook; empty = 1).
    std::span<const float> patch_weights;
    /// Optional weight of each source pixel's value, multiplied into every vote that reads it
    /// (row-major on the source grid; empty = 1): the colour-histogram weight.
    std::span<const float> source_weights;
    /// Clamp source reads to the source bounds (needed when the NNF comes from elsewhere).
    bool clamp_source = false;
};

/// Weights of VoteMode::Weighted: 1 / (0.01 + e / ē) per NNF entry, e its error and ē the mean
/// error over the entries that vote (`active`, nullptr = all entries with a match), times the
/// entry's coherence when `coherence` (σ², px²) is positive: the sum over the entries q of its
/// patch_size x patch_size neighbourhood that vote of exp(-|R_p(q) - R_q(q)|² / 2σ²), R_q(q)
/// the source position q maps to and R_p(q) where p's match (shifted and rotated) puts it
/// (Lukáč et al. 2015, eq. 6.8). Evaluated as the product of the x and y factors, each from the
/// integer difference of the matches' coordinates plus the rotated offset; a term whose
/// coordinates differ by more than r√2 + √(72σ²) (a factor below e^-36) counts 0. The
/// factors are tabulated per distinct angle of the field (up to 256) and patch offset.
std::vector<float> vote_weights(const Nnf& nnf, const std::uint8_t* active, int patch_size,
                                float coherence, int threads);

/// The same weights, every factor computed where it is used: the definition, and the oracle of
/// the tests (vote_weights looks the same factors up: the same bytes).
std::vector<float> vote_weights_reference(const Nnf& nnf, const std::uint8_t* active,
                                          int patch_size, float coherence, int threads);

/// Colour-histogram weights (Kopf et al. 2007, the w_h of Lukáč et al. 2015 eq. 7), one per
/// source pixel: 1 / (1 + strength * Σ_c max(0, H_t,c(v_c) − H_s,c(v_c))) for the pixel's value
/// v, where H_s,c and H_t,c are channel c's histograms of `source` and of the `target` pixels
/// marked in `target_pixels` (nullptr = all), with kHistogramBins bins spanning the source's
/// range of the channel (values beyond it fall into the end bins), as densities (count / total
/// * bins: 1 for a uniform spread). Deterministic; the same for any thread count.
std::vector<float> histogram_weights(const Image& source, const Image& target,
                                     const std::uint8_t* target_pixels, float strength,
                                     int threads);
inline constexpr int kHistogramBins = 32;

/// The source's side of histogram_weights, which does not change between the votes of a level:
/// its bins, each pixel's bin per channel and the densities, made once; `weights` then counts
/// only the target. Keeps a pointer to `source`, which must outlive it.
class SourceHistogram {
public:
    explicit SourceHistogram(const Image& source);
    /// histogram_weights(source, target, target_pixels, strength, threads).
    std::vector<float> weights(const Image& target, const std::uint8_t* target_pixels,
                               float strength, int threads) const;

private:
    int bin(float value, int channel) const;

    const Image* source_;
    std::vector<float> lo_, scale_;   // per channel: the range's start, bins per unit
    std::vector<std::uint8_t> bins_;  // per pixel and channel
    std::vector<double> density_;     // per channel and bin: share of the source's pixels
};

/// Writes the vote into `out`, which must already have the NNF's size and the source's channel
/// count. Pixels that receive no vote (or are fixed) keep their value.
void vote(const Nnf& nnf, const Image& source, const VoteParams& params, Image& out, int threads);

/// The same vote, each pixel gathering its patches on its own: the definition, and the oracle of
/// the tests (vote accumulates row by row where it can, in the same order: the same bytes).
void vote_reference(const Nnf& nnf, const Image& source, const VoteParams& params, Image& out,
                    int threads);

}  // namespace exemplar::synth
