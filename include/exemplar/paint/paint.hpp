#pragma once
/// \file
/// Example-based edge- and direction-aware texture painting (Brushables, Lukáč et al. 2015
/// §3.3): fills the region painted on a `PaintCanvas` with the texture of an RGBA exemplar so that
/// its features follow the canvas' direction field, through the engine (`synthesize`):
/// - direction awareness: the exemplar's and the canvas' direction fields are the engine's
///   source and target orientations, so each target patch is rotated by α = d_t(q) − d_s(p)
///   before it is compared (eq. 5);
/// - alpha as a synthesized channel with weight `alpha_weight` (3 in the paper); the colours are
///   synthesized premultiplied by alpha, so fully transparent pixels compare equal whatever RGB
///   the file stores there, and un-premultiplied in the output;
/// - edge awareness: Shape Hints (shape_hint.hpp) of the exemplar's mask and of the painted
///   region, each in its own direction's frame, as a guide weighted λ / patch_size² (the guide's
///   squared differences are summed over the patch, ≈ patch_size² times the centre's, so the
///   total is ≈ λ·D_shape of eq. 4);
/// - the coherence-weighted vote (eq. 8, σ_c² = `vote_coherence`) and its colour-histogram
///   weight (eq. 7, `vote_histogram`);
/// - only exemplar patches centred on the exemplar's shape (alpha > 0 or the given mask) are used;
/// - with a segmented exemplar (`PaintSource::labels`), only patches of the stroke's segment, the
///   engine's label groups; segment boundaries are Shape Hint edges (§4).
/// An exemplar without a boundary (RGB, opaque, or a mask covering all of it) has no boundary
/// effects to transfer: the whole canvas (on a repaint, the whole changed rectangle) is then
/// synthesized and cut to the strokes, and the Shape Hint is off.
/// The output is RGBA, transparent outside the painted region.

#include <cstdint>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/paint/strokes.hpp"
#include "exemplar/synth/nnf.hpp"
#include "exemplar/synth/options.hpp"

namespace exemplar::paint {

/// The exemplar and what was derived from it (Brushables' analysis phase).
struct PaintSource {
    /// The exemplar: 3 channels (opaque) or 4 (RGBA, straight alpha), values in [0, 1].
    Image image;
    /// Optional shape mask M_s (1 channel, inside where > 0.5); default: alpha > 0 (all pixels of
    /// an RGB exemplar).
    Image mask;
    /// Optional direction field d_s as angles (1 channel, radians, counter-clockwise on screen;
    /// `exemplar directions` writes it); default: `analyze_directions` with its defaults.
    Image directions;
    /// Optional segmentation of the exemplar into several textures (Brushables §4, Fig. 9): 1
    /// channel, the exemplar's size, one integer label per pixel (compared after rounding). A
    /// painted pixel then takes only exemplar patches centred on its stroke's segment
    /// (`Stroke::label`), and segment boundaries count as edges for the Shape Hint, on the
    /// exemplar and between differently labelled strokes on the canvas. Without it every stroke
    /// label must be 0.
    Image labels;
};

/// Options of `paint`. Defaults are the paper's (§3.3-3.4) unless noted.
struct PaintOptions {
    /// λ of eq. 4: weight of the Shape Hint distance against the colour patch distance. Default
    /// 25 (the paper: the number of pixels in a patch); 0 turns the Shape Hint off; 0..1000.
    float shape_weight = 25.0f;
    /// Edge extent in pixels: the Shape Hint's ring radius, how deep boundary effects reach
    /// into the texture (the paper leaves it to the user). Default 16; 1..256.
    float edge_extent_px = 16.0f;
    /// Bins on the Shape Hint's ring. Default 8; 4..32.
    int shape_bins = 8;
    /// Weight of the alpha channel's squared differences relative to each colour channel.
    /// Default 3 (the paper); range 0..100.
    float alpha_weight = 3.0f;
    /// σ_c², the coherence range of the coherence-weighted vote (eq. 8): default 2 (the paper);
    /// 0 turns the coherence weight off; range 0..100.
    float vote_coherence = 2.0f;
    /// Strength k of the colour-histogram weight of the vote (eq. 7's w_h, after Kopf et al.
    /// 2007; SynthesisOptions::vote_histogram): candidate colours the painting already holds more
    /// of than the exemplar lose weight, so the exemplar's rarer colours are not averaged into
    /// one mean tone. Default 1; 0 turns it off; range 0..100.
    float vote_histogram = 1.0f;
    /// Patch usage of the search. Default None: the paper's plain EM (Wexler et al. 2007),
    /// which keeps textures whose colours are spread throughout (a painting's strokes) but
    /// washes a texture of sparse flecks on a flat ground out to the ground, whatever the vote.
    /// Uniform (LazyFluids) uses every exemplar patch about equally often in the painted region,
    /// which keeps the flecks, and also places every part of the exemplar somewhere (a moon in
    /// a sky). ErrorBudget and OccurrencePenalty are accepted as the engine's.
    UsageStrategy usage = UsageStrategy::None;
    /// Patch width in pixels, odd, 3..15. Default 5 (the paper's 25-pixel patches).
    int patch_size = 5;
    /// Random seed; the same seed gives the same bytes for any thread count.
    std::uint64_t seed = 1;
};

/// Checks the options; the message names the option, its value and the valid range.
Status validate(const PaintOptions& options);

/// The result of `paint`.
struct PaintResult {
    /// RGBA (straight alpha), the canvas' size; transparent (all 0) outside the painted region.
    Image image;
    /// The engine's final correspondence field (target → exemplar), for inspection and tests.
    Nnf nnf;
};

/// Synthesizes the painted region of `canvas` from `source`. An empty painted region gives a
/// transparent image. Errors (InvalidArgument) name the input: an exemplar without 3 or 4
/// channels, a mask, direction field or label map of another size, an empty shape mask, a
/// painted label with no segment in the exemplar (inside its shape), a label ≠ 0 painted without
/// source labels, invalid options.
/// `context`: threads (the result does not depend on them), progress and cancellation.
Result<PaintResult> paint(const PaintSource& source, const PaintCanvas& canvas,
                          const PaintOptions& options = {}, const RunContext& context = {});

/// Repaints after strokes changed `changed` (what `PaintCanvas::add_stroke` returned): only the
/// painted pixels within `changed`, grown by the patch size, are synthesized again; the others
/// keep `previous` (an earlier result of `paint` or `repaint` for this canvas, RGBA).
Result<PaintResult> repaint(const PaintSource& source, const PaintCanvas& canvas,
                            const Image& previous, const PixelRect& changed,
                            const PaintOptions& options = {}, const RunContext& context = {});

/// A quick preview of `repaint` for interactive painting (the studio shows it at pen-up, then
/// the repaint): the same synthesis run on the canvas and the exemplar reduced `reduction`
/// times per side (box filter; labels nearest; the edge extent scaled alike) — what the
/// engine's coarse pyramid levels see, about reduction² times less work — and enlarged
/// (Gaussian, premultiplied) into the pixels `repaint` would synthesize; the others keep
/// `previous`. The texture is blurred at the full scale; its colours and layout follow the
/// repaint's coarse levels (tests/paint: the mean colour difference to the repaint at 1/8 scale).
/// Deterministic for any thread count. The factor is lowered while the reduced exemplar would
/// have fewer than 3 patches across its shorter side; at 1 this is `repaint`. `reduction`:
/// 1..16. The result's `nnf` is the reduced run's. Errors as `repaint`'s.
Result<PaintResult> preview_repaint(const PaintSource& source, const PaintCanvas& canvas,
                                    const Image& previous, const PixelRect& changed,
                                    const PaintOptions& options = {}, int reduction = 4,
                                    const RunContext& context = {});

/// Composites a painting result (RGBA, straight alpha) over a background (3 or 4 channels, the
/// same size): RGBA, straight alpha, "over" operator.
Image composite_over(const Image& painting, const Image& background);

}  // namespace exemplar::paint
