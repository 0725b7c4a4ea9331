#pragma once
/// \file
/// Reading and writing motion (optical flow) fields.
///
/// A flow field is a 2-channel Image with channels named "u" and "v": the displacement in
/// pixels along x (right) and y (down) of each pixel. Forward flow f from frame t to frame t+1
/// maps pixel x of frame t to x + f(x) in frame t+1 (Middlebury convention, also OpenCV's);
/// see docs/video.md.
///
/// Formats: Middlebury `.flo` (little-endian: float 202021.25 "PIEH", int32 width, int32 height,
/// then width * height (u, v) float pairs row by row) and any multi-channel image format, in
/// practice OpenEXR written as 32-bit float. Middlebury marks unknown flow with values above
/// 1e9; they are kept as read (callers test with `all_finite` / magnitude as they need).
/// Writes are atomic (temporary file + rename), like `save_image`. Errors are one line naming
/// the file: IoError for missing, truncated or corrupt files, Unsupported for unknown
/// extensions, InvalidArgument for images that are not 2-channel flow.

#include <string>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar {

/// Reads a Middlebury `.flo` file into a 2-channel ("u", "v") image. Fails (IoError) on a bad
/// magic number, a non-positive or implausible size (either side above 65536), a file shorter
/// or longer than its header announces.
Result<Image> load_flo(const std::string& path);

/// Writes a 2-channel image as Middlebury `.flo`, atomically. InvalidArgument unless the image
/// is non-empty with exactly 2 channels.
Status save_flo(const Image& flow, const std::string& path);

/// Reads a flow field: `.flo` files with `load_flo`; other files (EXR) through
/// `load_image_layer(path, layer)`, which must have exactly 2 channels (taken as u, v in file
/// order; the result is renamed "u", "v"). `layer` is ignored for `.flo` (must be "").
Result<Image> load_flow(const std::string& path, const std::string& layer = "");

/// Writes a flow field by extension: `.flo` (Middlebury) or `.exr` (32-bit float, channels
/// "u", "v"). Other extensions are Unsupported. Atomic.
Status save_flow(const Image& flow, const std::string& path);

/// `image` with its two channels renamed "u", "v" (the names flow images carry).
Image as_flow(Image image);

}  // namespace exemplar
