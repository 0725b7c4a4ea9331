#pragma once
// Stroke files of `exemplar paint` and `exemplar brush`: the strokes JSON of docs/paint.md and
// SVG drawings (through the sketch module's SVG reader), in canvas pixels.

#include <string>
#include <vector>

#include "exemplar/core/status.hpp"
#include "exemplar/paint/strokes.hpp"

namespace exemplar::cli {

/// Checks that `path` names a .json or .svg file (before any file is read); the message names
/// `flag`.
Status check_stroke_file(const std::string& flag, const std::string& path);

/// Reads strokes: `.json` as `[{"points": [[x, y], ...], "width": 40, "comb": false}, ...]` in
/// canvas pixels; `.svg` as one painting stroke per (sub)path, its centre line sampled every
/// ~1 px and its stroke-width, the viewBox (if any) mapped onto `width` × `height`. Every stroke
/// is validated; messages name `flag`, the file and the stroke or path index.
Result<std::vector<paint::Stroke>> read_strokes(const std::string& flag, const std::string& path,
                                                int width, int height);

}  // namespace exemplar::cli
