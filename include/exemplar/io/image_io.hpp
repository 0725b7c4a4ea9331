#pragma once
/// \file
/// Reading and writing images: PNG (libpng), JPEG (libjpeg-turbo), TIFF (libtiff), OpenEXR
/// (multi-channel, named layers; OpenEXR) and PBM/PGM/PPM. The format is recognized from the
/// file's content on reading and chosen by the extension on writing. Readers take the layouts
/// other tools write (tiled, planar, compressed, ASCII PNM, EXR data windows; palette, CMYK and
/// other TIFF/JPEG colour models are converted to RGB). 8/16-bit data is normalized to [0, 1];
/// float data is kept as is (including NaN and infinity: callers that need finite values check
/// with `all_finite`). Alpha is preserved as an ordinary, unassociated channel: colour values are
/// never multiplied or divided by alpha, on reading or writing. Every write goes to a temporary
/// file in the destination folder (".<name>.tmp-XXXXXX.<ext>") and is renamed into place, so a
/// destination is never half-written and an existing file survives a failed write (a symbolic
/// link at the destination is replaced by the file, not written through).
///
/// Errors are returned, never thrown or printed: one line naming the file and the problem, e.g.
/// `in.png: no such file`, `out.png: PNG cannot store 5 channels (only 1, 2, 3 or 4); ...`.
/// Codes: `IoError` for missing, unreadable, corrupt or unwritable files and missing layers;
/// `Unsupported` for unknown formats and channel counts or sample formats a format cannot store;
/// `InvalidArgument` for bad options or inconsistent inputs. All functions are thread-safe.

#include <string>
#include <utility>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar {

/// Sample format of a written file. What each format can store (anything else is rejected with
/// `Unsupported`, never converted silently):
/// PNG 8/16-bit, 1-4 channels (gray, gray+alpha, RGB, RGBA); JPEG 8-bit, 1 or 3 channels;
/// PPM 8-bit, 3 channels; PGM 8-bit, 1 channel (16-bit PNM files are read); TIFF 8/16-bit or
/// float, any channel count; EXR half or float, any channel count.
enum class PixelFormat {
    Auto,    ///< Format's natural choice: 8-bit for PNG/JPEG/PPM, half for EXR, 16-bit TIFF.
    UInt8,   ///< 8-bit unsigned, values clamped to [0, 1] and scaled by 255.
    UInt16,  ///< 16-bit unsigned, values clamped to [0, 1] and scaled by 65535.
    Half,    ///< 16-bit float (EXR): about 3 significant digits, |values| up to 65504.
    Float,   ///< 32-bit float, stored exactly.
};

/// Lower-case extension of `path` with the dot (".png"), or "".
std::string lowercase_extension(const std::string& path);

/// Options of `save_image` and `save_exr_layers`.
struct SaveOptions {
    PixelFormat format = PixelFormat::Auto;  ///< Sample format; see PixelFormat. Default Auto.
    /// JPEG quality, 1 (smallest) ..100 (best). Default 95. Out-of-range values are rejected
    /// with `InvalidArgument` for every format.
    int jpeg_quality = 95;
};

/// Loads every channel of the first subimage (its data window, at full resolution). Channel names
/// come from the file (e.g. "R", "G", "B", "A", "Y", "diffuse.R"); formats without names get
/// Y, Y A, R G B, R G B A and "channel4", ... for extra channels. EXR channels come in the order
/// OpenImageIO gives them (R G B A Z first within a layer, X Y Z W in a vector layer, the others
/// by name). Fails with the path and the
/// reason: `<path>: no such file`, unreadable, corrupt or truncated (IoError), unknown format
/// (Unsupported).
Result<Image> load_image(const std::string& path);

/// Loads the channels of one layer of a multi-layer file (EXR): channels named
/// `layer.X` (or exactly `layer` for a single-channel layer). The channel names of the result are
/// the part after the dot. `layer` "" selects the channels without a dot. If the layer is
/// missing, the error (IoError) lists the layers the file has.
Result<Image> load_image_layer(const std::string& path, const std::string& layer);

/// Channel names stored in a file (of the first subimage), without reading the pixels.
Result<std::vector<std::string>> read_channel_names(const std::string& path);

/// Layer names of a file: the distinct prefixes before the last '.' of channel names; channels
/// without a dot form the layer "" (listed first if present). The others follow in file order.
Result<std::vector<std::string>> read_layer_names(const std::string& path);

/// Writes an image atomically (temp file + rename); the format follows the extension
/// (case-insensitive; .png, .jpg/.jpeg, .tif/.tiff, .exr, .ppm, .pgm, .pnm). Channel names are
/// written where the format stores them (EXR, where they must be unique and non-empty); other
/// formats store channels by position. A channel named "A" is marked as alpha. Values are clamped
/// to [0, 1] for integer formats (NaN becomes 0). Fails if the format cannot hold the channel count
/// (e.g. 5 channels to PNG) or the sample format, with a message saying so; fails on an empty image
/// or a missing folder.
Status save_image(const Image& image, const std::string& path, const SaveOptions& options = {});

/// Writes several named layers into one multi-layer EXR: channel `c` of layer `name` is stored as
/// `name.C` where C is the layer image's channel name (layer "" stores the names unchanged).
/// All layers must have the same size (InvalidArgument otherwise); `path` must end in .exr
/// (Unsupported otherwise). Atomic like save_image.
Status save_exr_layers(const std::vector<std::pair<std::string, const Image*>>& layers,
                       const std::string& path, const SaveOptions& options = {});

}  // namespace exemplar
