#pragma once
/// \file
/// Inpainting (Wexler, Shechtman, Irani 2007; the `--inpaint` of EmbarkStudios'
/// texture-synthesis): fill a hole of an image with patches of the rest of it, keeping the rest
/// as it is.

#include <string>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/synth/synthesize.hpp"

namespace exemplar {

/// The "known" map of an inpainting mask: 1 channel, 1 where `mask` is > 0.5 (known: kept, and
/// the source of patches), 0 where it is ≤ 0.5 (the hole to fill; black in texture-synthesis'
/// masks). `mask` is grey or colour: with 2 or 4 channels the last one is alpha and must be
/// opaque; the colour channels are averaged first, so that a black-and-white mask saved as JPEG
/// (whose chroma noise makes its channels differ by up to ~100/255 along the edges) reads as
/// drawn. Errors name `what`: a partly transparent mask, a mask without a hole.
Result<Image> inpainting_known(const Image& mask, const std::string& what = "inpaint mask");

/// The synthesis input that fills the hole of `image` (where `known`, from inpainting_known, is
/// 0) from the rest of it: style = image; initial target = image; target mask = the hole (every
/// other pixel is kept byte for byte); source mask = the known pixels (only patches entirely
/// inside them are copied, so nothing that the hole covers, such as a painted mark, comes back);
/// inside the hole the initial target is the mean colour of the known pixels (the covered
/// content is not information: the painted mark's colour would pull the first matches). Guide
/// pairs may be added (both on the image's grid). Errors, naming `what` (the mask): sizes that
/// differ, `known` of more than 1 channel.
Result<SynthesisInput> inpainting_input(const Image& image, const Image& known,
                                        const std::string& what = "inpaint mask");

}  // namespace exemplar
