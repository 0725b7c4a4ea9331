#pragma once
/// \file
/// Structure tensor and the dominant local orientation of an image (Granlund and Knutsson 1995;
/// the orientation fields O(I_t), O(S) of Bénard et al. 2013 §3.1).
///
/// The image is reduced to grey first: 1-2 channels use channel 0, 3 or more use the Rec. 709
/// luma of channels 0..2 (alpha and extra channels are ignored). Gradients are central
/// differences of the grey image blurred by `gradient_sigma_px`; the tensor
/// J = G_integration * (∇I ∇Iᵀ) is smoothed by `integration_sigma_px`. Borders clamp.
/// Angles follow the image convention (exemplar/core/image.hpp): radians, counter-clockwise as
/// seen on screen (+x towards -y).

#include "exemplar/core/image.hpp"

namespace exemplar {

/// Scales of the structure tensor.
struct StructureTensorOptions {
    /// Blur before differentiation, in pixels (noise scale). Default 1.0; ≥ 0.
    float gradient_sigma_px = 1.0f;
    /// Blur of the tensor components, in pixels (the neighbourhood an orientation summarizes).
    /// Default 3.0; ≥ 0. Larger values give smoother fields and fill flat regions.
    float integration_sigma_px = 3.0f;
};

/// Smoothed structure tensor: 3 channels "xx", "xy", "yy" (J11, J12, J22 with x right and
/// y down, in grey-level² per px²). Negative or non-finite sigmas are programming errors
/// (checked). An empty image gives an empty result. `threads`: 0 = all, 1 = inline.
Image structure_tensor(const Image& image, const StructureTensorOptions& options = {},
                       int threads = 0);

/// Orientation of the dominant structure from a structure tensor (3 channels as above):
/// 1 channel "angle", the direction *along* edges and stripes (the eigenvector of the smaller
/// eigenvalue), in radians in [0, π), counter-clockwise on screen. Horizontal stripes give 0,
/// vertical ones π/2. Where the tensor is isotropic (flat or noisy regions) the angle is 0.
/// Usable as `SynthesisInput::source_orientation` / `target_orientation`.
Image orientation_from_tensor(const Image& tensor, int threads = 0);

/// Coherence (λ1 − λ2) / (λ1 + λ2) in [0, 1] of a structure tensor: 1 channel "coherence",
/// 0 where flat or isotropic, near 1 along clean stripes. Tells how much to trust the angle.
Image coherence_from_tensor(const Image& tensor, int threads = 0);

/// `orientation_from_tensor(structure_tensor(image, options))`.
Image orientation_field(const Image& image, const StructureTensorOptions& options = {},
                        int threads = 0);

}  // namespace exemplar
