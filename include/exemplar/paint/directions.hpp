#pragma once
/// \file
/// Signed direction fields of exemplars (Brushables, Lukáč et al. 2015 §3.1): edge tangent flow
/// (Kang et al. 2007) started from tangents whose signs were harmonized beforehand, so that
/// asymmetric structures (hair growing one way, grass blades) get one consistent direction.
///
/// A direction field is a 2-channel image "x", "y" of unit vectors in image coordinates (x
/// right, y down), zero where no direction is known. `direction_angles` turns it into the angle
/// fields the engine takes (`SynthesisInput::source_orientation` / `target_orientation`):
/// radians in (−π, π], counter-clockwise as seen on screen (exemplar/core/image.hpp).

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::paint {

/// Options of `analyze_directions`.
struct DirectionAnalysisOptions {
    /// Radius of the edge tangent flow filter's disc, in pixels (Kang et al.'s r). Brushables
    /// §3.4: 10 px by default, about 35 px for noisy textures. Range 1..100.
    float radius_px = 10.0f;
    /// Edge tangent flow iterations (Kang et al. 2007: 2-3). Default 3; range 0..10 (0 gives the
    /// harmonized initial tangents).
    int iterations = 3;
    /// Gaussian blur of the grey image before the Sobel gradients, in pixels. Default 1; 0..10.
    float gradient_sigma_px = 1.0f;
    /// Harmonize the tangents' signs before filtering (the Brushables initialization: the sign
    /// fixed at the strongest gradient and propagated breadth-first). Default true; false gives
    /// plain ETF, whose signs flip by 180° between neighbouring stripes (Brushables Fig. 3c).
    bool harmonize_signs = true;
};

/// Checks the options; the message names the option, its value and the valid range.
Status validate(const DirectionAnalysisOptions& options);

/// The signed direction field of `image` (2 channels "x", "y"; see the file comment). The image
/// is reduced to grey as in `structure_tensor` (Rec. 709 luma of channels 0..2, or channel 0).
/// Flat regions take the directions of their surroundings (within the filter radius); an image
/// without any gradient gives zeros. Deterministic for any `threads` (0 = all, 1 = inline).
/// Invalid options are rejected (InvalidArgument); an empty image gives an empty field.
Result<Image> analyze_directions(const Image& image, const DirectionAnalysisOptions& options = {},
                                 int threads = 0);

/// Angles of a direction field (2 channels): 1 channel "angle", atan2(−y, x) in (−π, π]
/// (counter-clockwise on screen), 0 where the vector is zero.
Image direction_angles(const Image& directions);

/// The direction field (unit vectors, 2 channels "x", "y") of an angle field (1 channel).
Image directions_from_angles(const Image& angles);

/// Direction-wheel colours of a direction field (2 channels) for previews: RGB with the hue
/// given by the angle (0 = right = red, π/2 = up = yellow-green, π = left = cyan, −π/2 = down
/// = violet), full saturation, value scaled by the vector's length (black where zero).
Image direction_wheel(const Image& directions);

}  // namespace exemplar::paint
