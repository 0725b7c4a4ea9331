#pragma once
/// \file
/// Light-path-expression (LPE) buffers of a render, the guides of StyLit (Fišer et al. 2016,
/// §8.3.2): the full global-illumination image plus buffers that isolate lighting effects
/// (direct diffuse LDE, direct specular LSE, indirect diffuse L.*DDE, ...).
///
/// A buffer set comes from a list of image files (one buffer per file, any format), from one
/// multi-layer EXR whose layers are picked by name, or from a folder of one file per buffer
/// (`exemplar render --output DIR`) whose files are picked by name. Names follow a preset (our
/// renderer's names, Blender Cycles' pass names, Arnold's AOV names) or an explicit list; the
/// mapping of each preset to the four StyLit guides is documented in docs/stylit.md.

#include <string>
#include <string_view>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar {

/// One buffer of a render.
struct LpeBuffer {
    std::string name;    ///< Role or layer name ("full", "DiffDir", ...), for messages.
    std::string origin;  ///< Where it came from: "file.png" or "scene.exr (layer DiffDir)".
    Image image;         ///< Colour channels (an "A" channel is dropped; see load_lpe_buffers).
};

/// Named lists of EXR layer names, one entry per guide, in StyLit's order: full render, direct
/// diffuse, direct specular, indirect diffuse. Each entry lists accepted spellings, first match
/// wins; "" stands for the channels without a layer prefix (R, G, B of a plain beauty EXR).
struct LayerPreset {
    std::string_view name;  ///< "exemplar", "cycles", "arnold".
    std::vector<std::vector<std::string>> layers;
};

/// The presets: "exemplar" (the buffer names of `exemplar render`: fullgi, direct_diffuse,
/// direct_specular, indirect_diffuse; "full" and "indirect" are accepted too), "cycles"
/// (Combined, DiffDir, GlossDir, DiffInd) and "arnold" (RGBA or beauty, diffuse_direct,
/// specular_direct, diffuse_indirect).
const std::vector<LayerPreset>& layer_presets();

/// Finds a preset by name; the error lists the known names.
Result<LayerPreset> find_layer_preset(std::string_view name);

/// A preset made of an explicit comma-separated list of layer names ("a,b,c"), one per guide.
/// Fails on an empty list or an empty name.
Result<LayerPreset> custom_layer_preset(std::string_view comma_separated);

/// Loads a render's buffers.
/// - One `.exr` path whose file has more than one layer: the layers named by `preset`, in the
///   preset's order. A layer matches a name if it is the name or ends in ".name" (Blender
///   prefixes the view layer: "ViewLayer.DiffDir"). A missing layer fails with IoError naming
///   the file, the wanted layer and the layers the file has; two matches fail as ambiguous.
/// - One path that is a folder: per guide, the file `<name>.png` or `<name>.exr` for the first
///   name of the preset entry that has one (as `exemplar render --output DIR` writes them). A
///   missing file fails with IoError naming the folder and the files looked for; both a .png
///   and an .exr of one name fail as ambiguous.
/// - Otherwise: one buffer per path, in the given order (`preset` is not used).
/// A channel named "A" (alpha) is dropped from buffers that have other channels: coverage is
/// not lighting. Every buffer must have the size of the first (InvalidArgument naming both).
Result<std::vector<LpeBuffer>> load_lpe_buffers(const std::vector<std::string>& paths,
                                                const LayerPreset& preset);

/// Checks that `source` and `target` pair up: same count, same channel count per pair, every
/// source buffer of `exemplar_width` x `exemplar_height`. The first problem is returned as one
/// line naming the buffers (InvalidArgument).
Status check_buffer_pairs(const std::vector<LpeBuffer>& source,
                          const std::vector<LpeBuffer>& target, int exemplar_width,
                          int exemplar_height);

}  // namespace exemplar
