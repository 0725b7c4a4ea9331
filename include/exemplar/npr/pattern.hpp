#pragma once
/// \file
/// Example pattern preprocessing for image-space NPR texture synthesis (issue 20; §4.5 of
/// "Image Space Texture Synthesis for 3D NPR Animation", after Lefebvre and Hoppe 2006).
///
/// A grey pattern P (a halftone screen, hatching, stipples) becomes:
/// - `screen`: P after contrast-limited adaptive histogram equalization (CLAHE, Zuiderveld
///   1994), so that thresholding it at t inks about a fraction t of the pixels;
/// - optional feature channels (distance to Canny edges, Sobel gradients, structure tensor);
/// - an appearance space: PCA of the Gaussian-weighted 5x5 neighbourhoods of the pattern and
///   its features, keeping `appearance_dims` (5-8) components;
/// - a Gaussian stack of that appearance image (same size at every level, level l blurred at
///   the scale 2^l), the exemplar of the coarse-to-fine coordinate synthesis.
/// Coordinates into the pattern wrap around (the pattern is treated as tileable).
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::npr {

/// How to prepare a pattern. Defaults follow the paper.
struct PatternOptions {
    /// Equalize the pattern's histogram with CLAHE (the paper always does). Default true.
    bool equalize = true;
    /// CLAHE clip limit (OpenCV's `clipLimit`: multiples of the mean histogram bin). The paper
    /// gives no value and wants a flat histogram; default 40 (OpenCV's default, close to plain
    /// adaptive equalization); range (0, 40]. Small values (2) keep more of the original tones.
    float clahe_clip_limit = 40.0f;
    /// CLAHE tiles per side (OpenCV's `tileGridSize`). Default 8 (OpenCV's); range 1..64.
    int clahe_tiles = 8;
    /// Add the Euclidean distance to Canny edges (1 channel, scaled to [0, 1]). Default false.
    bool edge_distance = false;
    /// Add the Sobel gradients dP/dx, dP/dy (2 channels). Default false.
    bool gradients = false;
    /// Add the structure tensor (dP/dx)², dP/dx·dP/dy, (dP/dy)² (3 channels). Default false.
    bool structure_tensor = false;
    /// Dimensions kept by the PCA of the 5x5 neighbourhoods. Default 6; range 1..8 (the paper
    /// uses 5-8).
    int appearance_dims = 6;
    /// Levels of the Gaussian stack (= synthesis pyramid levels). Default 3 (the paper's L = 2);
    /// range 1..6.
    int levels = 3;
};

/// Checks every option; InvalidArgument naming the first bad one and its range.
Status validate(const PatternOptions& options);

/// A prepared pattern.
struct Pattern {
    Image screen;    ///< 1 channel, the equalized grey pattern in [0, 1] (what the output shows).
    Image features;  ///< The stacked pattern + feature channels the PCA saw.
    /// Appearance-space Gaussian stack: `levels` images of the pattern's size with
    /// `appearance_dims` channels; level 0 is sharp, level l is blurred at the scale 2^l.
    std::vector<Image> stack;
    /// Fraction of the neighbourhood variance the kept components explain, in [0, 1].
    float explained_variance = 0.0f;
};

/// Prepares `pattern` (any channel count; 3+ channels are converted to Rec. 709 luma, 2 use
/// channel 0). InvalidArgument if the options are invalid or the pattern is smaller than
/// `min_size` pixels on a side (the synthesis needs a few patches of room; 0 = no check).
/// Deterministic; `threads`: 0 = all cores, 1 = inline.
Result<Pattern> prepare_pattern(const Image& pattern, const PatternOptions& options,
                                int min_size = 0, int threads = 0);

/// The grey version of `image` used by `prepare_pattern` (1 channel).
Image to_grey(const Image& image);

/// CLAHE of a grey image in [0, 1] (8-bit quantized for OpenCV, result in [0, 1]). Unsupported
/// if OpenCV's plugin (libexemplar_opencv.so) cannot be loaded.
Result<Image> equalize_clahe(const Image& grey, float clip_limit, int tiles);

}  // namespace exemplar::npr
