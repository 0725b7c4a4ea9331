#pragma once
/// \file
/// SVG import and export of stroke drawings. Import reads `<path>` (all commands M L H V C S Q T
/// A Z, absolute and relative), `<line>`, `<polyline>`, `<polygon>`, `<circle>`, `<ellipse>` and
/// `<rect>` (with rounded corners) in document order; quadratic segments, arcs and lines become
/// cubics, and every `transform` (matrix, translate, scale, rotate, skewX, skewY) of the element
/// and its ancestors is applied, so the paths are in the root's user space (viewBox units).
/// Every subpath (each `M`) is one stroke. `<defs>`, `<symbol>`, `<clipPath>`, `<mask>`,
/// `<pattern>` and `<marker>` contents are skipped. XML parsing: tinyxml2.

#include <array>
#include <string>
#include <vector>

#include "exemplar/core/status.hpp"
#include "exemplar/sketch/path.hpp"

namespace exemplar::sketch {

/// A drawing: strokes in document (drawing) order and the canvas they live on.
struct Drawing {
    /// The root's viewBox (x, y, width, height); width and height 0 if it has none.
    double view_x = 0.0, view_y = 0.0, view_width = 0.0, view_height = 0.0;
    /// View-space pixels per user unit, from the root's width/height against its viewBox
    /// (1 when either is missing). Distances the rules compare with thresholds are in view pixels.
    double pixels_per_unit = 1.0;
    std::vector<Path> paths;
    /// Per path: the id of the element it came from ("" if none), with "#k" appended for the
    /// k-th subpath (k ≥ 1) of an element holding several.
    std::vector<std::string> ids;
    /// Per path: its stroke-width (the element's `stroke-width` attribute or `style` property,
    /// else its ancestors', else 1, SVG's default) in root user units: scaled by the square root
    /// of the transform's determinant.
    std::vector<double> stroke_widths;
    /// Per path: its `stroke` colour (the element's, else its ancestors', else "none", SVG's
    /// default), through normalize_colour: "#rrggbb", "none", or the text as written (lower case)
    /// for what it does not know (gradients, currentColor).
    std::vector<std::string> strokes;
    /// Per path: its `fill` colour, the same way (SVG's default: black, "#000000").
    std::vector<std::string> fills;
    /// Per path: the `class` attributes of its ancestors and of the element, outermost first,
    /// separated by spaces ("" if none), so that a group's class applies to its paths.
    std::vector<std::string> classes;
    /// Per path: the index of the element it came from (subpaths of one element share it, as
    /// they share one fill: holes are subpaths), counting drawable elements from 0.
    std::vector<int> elements;
    /// Per path: 1 if its `fill-rule` is evenodd, 0 for nonzero (SVG's default).
    std::vector<unsigned char> even_odd;
    /// Number of drawable elements read.
    int element_count = 0;
};

/// An SVG colour as "#rrggbb" (from "#rgb", "#rrggbb", "rgb(r, g, b)" or one of CSS's basic
/// colour keywords, any case), "none" (also for "transparent"), or else the text in lower case
/// without spaces.
std::string normalize_colour(const std::string& colour);

/// Parses SVG text. `name` is used in messages. Errors (InvalidArgument): not XML, no `<svg>`
/// root, a malformed number or path command (the message names the element and its id).
Result<Drawing> parse_svg(const std::string& text, const std::string& name = "SVG");
/// Reads and parses an SVG file; IoError if it cannot be read.
Result<Drawing> load_svg(const std::string& path);

/// One group of paths drawn with the same style.
struct SvgLayer {
    std::vector<Path> paths;
    std::vector<std::string> ids;  ///< Optional, one per path.
    std::string stroke = "black";  ///< Any SVG colour.
    double stroke_width = 1.5;     ///< In user units.
    double opacity = 1.0;
    std::string name;  ///< `id` of the `<g>`, if not empty.
};

/// The canvas rectangle (x, y, width, height): the drawing's viewBox, or the layers' bounds
/// with a 5% margin when it has none.
std::array<double, 4> canvas_bounds(const Drawing& canvas, const std::vector<SvgLayer>& layers);

/// SVG text with the canvas of `canvas` (its viewBox, or the paths' bounds if it has none) and
/// the layers in order, each a `<g>` of round-capped `<path>` elements with absolute M/C/Z data.
std::string to_svg(const Drawing& canvas, const std::vector<SvgLayer>& layers);
/// Path data ("M x y C ... Z") of one path.
std::string path_data(const Path& path);
/// Writes `to_svg` to `path` atomically (temporary file + rename).
Status save_svg(const Drawing& canvas, const std::vector<SvgLayer>& layers,
                const std::string& path);

/// Renders layers on a white background to a PNG with Cairo: the canvas's viewBox (or the
/// paths' bounds) scaled to `width_px` wide. Written atomically.
Status save_png(const Drawing& canvas, const std::vector<SvgLayer>& layers, const std::string& path,
                int width_px = 512);

/// Writes text to `path` atomically (temporary file + rename); IoError names the file.
Status save_text(const std::string& text, const std::string& path);

}  // namespace exemplar::sketch
