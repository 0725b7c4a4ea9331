#pragma once
/// \file
/// Shape Hints (Brushables, Lukáč et al. 2015 §3.3): a local shape descriptor, a single ring of
/// circular bins counting the shape's edge pixels, oriented by the direction field.
///
/// Each bin is a disc of radius ρ·sin(π/N) (neighbouring bins touch) centred on a ring of radius ρ
/// = `radius_px` (the *edge extent*) around the pixel, the first bin in the pixel's own direction
/// and the others counter-clockwise at 2π/N steps. A disc is rotation invariant, so the value of a
/// bin anywhere is one lookup into the edge map convolved with the disc (precomputed once, then
/// sampled bilinearly): constant cost per evaluation and any rotation for free.
///
/// Because every descriptor is expressed in its own pixel's frame, comparing the descriptor of
/// exemplar pixel p with that of canvas pixel q bin by bin is exactly comparing H_p with H_q
/// rotated by α_pq = d_t(q) − d_s(p) (eq. 6): the rotation needs no work at match time, and the
/// descriptors can be handed to the engine as ordinary guide channels. The engine compares guides
/// by weighted squared differences, not χ², so each bin holds the square root of its edge-pixel
/// fraction: Σ (√h − √g)² (the squared Hellinger distance) approximates χ²(h, g) = ½ Σ
/// (h − g)² / (h + g) closely where h ≈ g (equal to first order) and stays bounded elsewhere.

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::paint {

/// Options of the Shape Hint.
struct ShapeHintOptions {
    /// Ring radius ρ in pixels: the edge extent, how deep the boundary effects reach into the
    /// texture. Brushables leaves it to the user ("roughly the width of the boundary effects").
    /// Default 16; range 1..256.
    float radius_px = 16.0f;
    /// Number of bins on the ring (N). Default 8; range 4..32.
    int bins = 8;
};

/// Checks the options; the message names the option, its value and the valid range.
Status validate(const ShapeHintOptions& options);

/// Edge map of a shape mask (1 channel, inside where > 0.5): 1 at inside pixels with a
/// 4-neighbour outside (the image border does not count as an edge), 0 elsewhere. With `labels`
/// (1 channel, same size, compared after rounding), label boundaries are edges too.
Image shape_edges(const Image& mask, const Image& labels = {});

/// Shape Hint descriptors of every pixel: `bins` channels "hint0".. with √(fraction of the bin's
/// disc covered by edge pixels), in [0, 1]. `edges` from `shape_edges`; `angles` the direction
/// field as angles (1 channel, same size; radians counter-clockwise on screen). Deterministic;
/// `threads`: 0 = all, 1 = inline. Invalid options or sizes are programming errors (checked).
/// Pixels whose ring lies where no edge is near are all 0 without being computed.
Image shape_hint(const Image& edges, const Image& angles, const ShapeHintOptions& options = {},
                 int threads = 0);

/// The same descriptors, every pixel computed: the oracle of the tests (the same bytes).
Image shape_hint_reference(const Image& edges, const Image& angles,
                           const ShapeHintOptions& options = {}, int threads = 0);

}  // namespace exemplar::paint
