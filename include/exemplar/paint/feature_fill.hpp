#pragma once
/// \file
/// The area-feature fill of Painting by Feature (Lukáč et al. 2013; chapter 3 of Fišer's thesis,
/// §3.3.2): a region of the canvas is filled with the texture of a region selected in the
/// palette, by content-aware synthesis (Wexler et al. 2007 with PatchMatch) with the engine:
/// - the palette region's bounding box is copied at a few angles over a limited range
///   ("pre-rotating the source selection and performing the nearest-neighbor search using only
///   translations"), side by side in one exemplar whose mask keeps only pixels read from inside
///   the region;
/// - the engine synthesizes the target region only (target mask), starting from the canvas:
///   the pixels outside the region are fixed and the patches that straddle the border match
///   them, so the fill meets what is already painted (line features) without a seam.
/// Deviations and measured defaults in docs/feature.md.
///
/// Region images: a pixel is inside where the mean of its colour channels (alpha ignored) is
/// above 0.5 (white on black). Deterministic for any thread count.

#include <cstdint>
#include <span>
#include <string_view>
#include <variant>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/synth/options.hpp"

namespace exemplar::paint {

/// Options of the fill. The chapter states no numbers; defaults are ours, measured
/// (docs/feature.md).
struct FeatureFillOptions {
    /// Patch width in pixels, odd. Default 5 (the engine's); 3..31.
    int patch_size = 5;
    /// Number of pre-rotated copies of the palette region, at equal steps over
    /// [−rotation_range_deg, +rotation_range_deg]; 1 = the region as it is. Default 5; 1..36.
    int rotations = 5;
    /// Half-range of the rotations in degrees. Default 30; 0..180.
    float rotation_range_deg = 30.0f;
    /// The engine's colour-histogram weight of the vote (SynthesisOptions::vote_histogram):
    /// favours colours the fill holds less of than the region. Default 0 (off): with the uniform
    /// usage it overshoots (twice the region's share of sparse colours, soft halos); without it,
    /// it keeps fewer of them than the uniform usage (docs/feature.md). 0..100.
    float vote_histogram = 0.0f;
    /// How often a source patch may be used. Default Uniform: the chapter's plain EM (None)
    /// washes a texture of sparse features out to its dominant colour (docs/feature.md).
    UsageStrategy usage = UsageStrategy::Uniform;
    /// EM iterations of plain nearest-neighbour search on the finest level, from the layout the
    /// usage strategy made on the coarser levels (SynthesisOptions::budget_polish_iterations),
    /// instead of the strategy's own iterations there: the coarse levels decide which features
    /// go where, the finest level only refines them. 0 = the usage strategy on the finest level
    /// too. Default 2: half the CPU time of 0 at 1 MPix, a lower seam step, as many sparse
    /// features (docs/feature.md). 0..100.
    int polish_iterations = 2;
    /// Random seed: same seed, same fill, for any thread count.
    std::uint64_t seed = 1;
};

/// Description of one numeric option (name, doc, unit, range): the one table that validation,
/// the CLI flags and docs/feature.md use.
struct FeatureFillOptionSpec {
    std::string_view name;  ///< kebab-case: the CLI flag --name.
    std::string_view doc;
    std::string_view unit;
    double min = 0.0;  ///< Inclusive range.
    double max = 0.0;
    std::variant<int FeatureFillOptions::*, float FeatureFillOptions::*> field;
};

/// The table of numeric options.
std::span<const FeatureFillOptionSpec> feature_fill_option_specs();
/// Reads an option's value as a double.
double get_option(const FeatureFillOptions& options, const FeatureFillOptionSpec& spec);
/// Sets an option; rejects values outside the range, non-integers for integer options and even
/// patch sizes (`patch-size: 4 is invalid (must be odd, 3..31)`).
Status set_option(FeatureFillOptions& options, const FeatureFillOptionSpec& spec, double value);
/// Checks every option.
Status validate(const FeatureFillOptions& options);

/// The inside of a region image (1 channel, 0 or 1): mean colour channel > 0.5.
Image region_mask(const Image& region);

/// The pre-rotated exemplar: the bounding box of `source_mask`'s inside, grown by half a patch,
/// copied at options.rotations angles side by side. Returns the exemplar (palette channels) and
/// writes its mask (1 channel: 1 where every bilinear tap of the pixel lies inside the region).
Image rotated_exemplar(const Image& palette, const Image& source_mask,
                       const FeatureFillOptions& options, Image& exemplar_mask);

/// Fills the inside of `target_region` on `canvas` with the texture of the inside of
/// `source_region` in `palette`. `palette` and `source_region` have one size, `canvas` and
/// `target_region` another; `canvas` has the palette's channel count. Every pixel outside the
/// target region is the canvas's, bit for bit. Errors (one line): sizes, channel counts, empty
/// regions, a source region with no patch entirely inside it, options.
Result<Image> fill_area(const Image& palette, const Image& source_region, const Image& canvas,
                        const Image& target_region, const FeatureFillOptions& options = {},
                        const RunContext& context = {});

/// `image` with `channels` channels (1, 3 or 4): grey spread to RGB, RGB to grey as the mean,
/// an opaque alpha added, or the alpha dropped.
Image with_channels(const Image& image, int channels);

/// fill_area with a palette of any channel count (grey, RGB or RGBA), as `exemplar fill` and
/// exemplar.fill do it: the palette is brought to the canvas's channels (with_channels), or
/// without a canvas to RGBA, so the fill stands free on a transparent image. Errors: a palette or
/// canvas without 1, 3 or 4 channels (`palette: has 2 channels (must be grey, RGB or RGBA)`),
/// then fill_area's.
Result<Image> fill_with_palette(const Image& palette, const Image& source_region,
                                const Image& canvas, const Image& target_region,
                                const FeatureFillOptions& options = {},
                                const RunContext& context = {});

}  // namespace exemplar::paint
