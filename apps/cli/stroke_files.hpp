#pragma once
// Inputs of `exemplar paint` and `exemplar brush`: stroke files (the strokes JSON of
// docs/paint.md and SVG drawings, through the sketch module's SVG reader, in canvas pixels) and
// the canvas (its size and optional background).

#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/paint/strokes.hpp"

namespace exemplar::cli {

/// Checks that `path` names a .json or .svg file (before any file is read); the message names
/// `flag`.
Status check_stroke_file(const std::string& flag, const std::string& path);

/// Reads strokes: `.json` as `[{"points": [[x, y], ...], "width": 40, "comb": false}, ...]` in
/// canvas pixels; `.svg` as one painting stroke per (sub)path, its centre line sampled every
/// ~1 px and its stroke-width, the viewBox (if any) mapped onto `width` × `height`. With
/// `labels` (paint's --source-labels), each stroke's segment label (`parse_label`): JSON
/// `"label"`, an SVG path's stroke colour (none: 0); without, a JSON `"label"` is an error. Every
/// stroke is validated; messages name `flag`, the file and the stroke or path index.
Result<std::vector<paint::Stroke>> read_strokes(const std::string& flag, const std::string& path,
                                                int width, int height, bool labels = false);

/// A segment label as written in a stroke file: a grey level 0..255 (the label map's colour
/// (N, N, N)) or a colour `#rrggbb` / `#rgb`: the 24-bit colour 0xrrggbb.
Result<int> parse_label(const std::string& text);
/// The label as `#rrggbb`, for messages.
std::string label_colour(int label);

/// Checks --width/--height before any file is read: both > 0 unless a --canvas is given (whose
/// size is then the default), at most 32768.
Status check_canvas_size(const std::string& canvas, int width, int height);

/// The canvas: the --canvas background (RGB or RGBA; none if `canvas` is empty) and the size,
/// the background's (which --width/--height must match if given) or width × height.
struct Canvas {
    Image background;
    int width = 0;
    int height = 0;
};
Result<Canvas> load_canvas(const std::string& canvas, int width, int height);

}  // namespace exemplar::cli
