#pragma once
/// \file
/// Reading and writing images through OpenImageIO: PNG, JPEG, TIFF, OpenEXR (multi-channel,
/// named layers), PPM/PGM and anything else OIIO reads. 8/16-bit data is normalized to [0, 1];
/// float data is kept as is. Alpha is preserved as an ordinary channel. Every write goes to a
/// temporary file in the destination folder and is renamed into place, so a destination is never
/// half-written. Errors name the file and the problem in one line.

#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar {

/// Sample format of a written file.
enum class PixelFormat {
    Auto,     ///< Format's natural choice: 8-bit for PNG/JPEG/PPM, half for EXR, 16-bit TIFF.
    UInt8,
    UInt16,
    Half,
    Float,
};

struct SaveOptions {
    PixelFormat format = PixelFormat::Auto;
    int jpeg_quality = 95;  ///< 1..100.
};

/// Loads every channel of the first subimage. Fails with the path and the reason
/// (missing, unreadable, corrupt, unknown format).
Result<Image> load_image(const std::string& path);

/// Loads the channels of one layer of a multi-layer file (EXR): channels named
/// `layer.X` (or exactly `layer` for a single-channel layer). The channel names of the result are
/// the part after the dot. If the layer is missing, the error lists the layers the file has.
Result<Image> load_image_layer(const std::string& path, const std::string& layer);

/// Channel names stored in a file (of the first subimage), without reading the pixels.
Result<std::vector<std::string>> read_channel_names(const std::string& path);

/// Layer names of a file: the distinct prefixes before the last '.' of channel names; channels
/// without a dot form the layer "" (listed first if present).
Result<std::vector<std::string>> read_layer_names(const std::string& path);

/// Writes an image atomically (temp file + rename); the format follows the extension.
/// Channel names are written where the format supports them (EXR, TIFF).
/// Values are clamped to [0, 1] for integer formats. Fails if the format cannot hold the
/// channel count (e.g. 5 channels to PNG) with a message saying so.
Status save_image(const Image& image, const std::string& path, const SaveOptions& options = {});

/// Writes several named layers into one multi-layer EXR: channel `c` of layer `name` is stored as
/// `name.C` where C is the layer image's channel name. Atomic like save_image.
Status save_exr_layers(const std::vector<std::pair<std::string, const Image*>>& layers,
                       const std::string& path, const SaveOptions& options = {});

}  // namespace exemplar
