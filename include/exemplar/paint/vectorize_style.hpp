#pragma once
/// \file
/// Vector image stylization, the primary application of Painting by Feature (Lukáč et al. 2013;
/// chapter 3 of Fišer's thesis, §3.4): line features picked in a palette image are assigned to
/// the stroked paths of an SVG drawing and area features to its filled shapes, by stroke and fill
/// colour (or class); the drawing is then rendered with the two tools: the fills first (the
/// engine fill of feature_fill.hpp), then every stroked path with its line feature (the brush of
/// feature_brush.hpp), in document order. The style palette file (JSON) is described in
/// docs/feature.md. Everything is deterministic for any thread count.

#include <string>
#include <utility>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/paint/feature_brush.hpp"
#include "exemplar/paint/feature_fill.hpp"
#include "exemplar/paint/strokes.hpp"
#include "exemplar/sketch/svg.hpp"

namespace exemplar::paint {

/// The paths of an SVG drawing as strokes in canvas pixels: path k is stroke k, its centre line
/// sampled about every pixel and its width the path's stroke-width, the drawing's viewBox (if it
/// has one) mapped onto `width` × `height`. Empty paths give strokes without points. The strokes
/// are not validated (callers name the file and the path when they reject one).
std::vector<Stroke> drawing_strokes(const sketch::Drawing& drawing, int width, int height);

/// The inside of closed polygons (1 channel, 0 or 1 at pixel centres) on a `width` × `height`
/// grid: nonzero winding over all the polygons together (even-odd with `even_odd`), so a polygon
/// inside another one and wound the other way is a hole. Polygons are closed implicitly.
Image polygon_mask(std::span<const std::vector<StrokePoint>> polygons, int width, int height,
                   bool even_odd = false);

/// The canvas size of a drawing: its viewBox times its pixels per unit, or the paths' bounds
/// (from 0, 0) when it has no viewBox; with `width` > 0, that width and the height in
/// proportion. At least 1 × 1.
std::pair<int, int> drawing_canvas_size(const sketch::Drawing& drawing, int width = 0);

/// A line feature of the style palette: a rough path along it in the palette.
struct StyleLineFeature {
    std::string name;
    Stroke selection;  ///< Palette pixels; its width is the selection width (the patch size).
    /// Snap the path onto the palette's edge first (snap_to_edges). Default true.
    bool snap = true;
    /// Width of the painted strokes in canvas pixels; 0 = each path's stroke-width.
    float brush_width_px = 0.0f;
};

/// An area feature of the style palette: a region of the palette.
struct StyleAreaFeature {
    std::string name;
    Image region;  ///< Palette size, white (mean colour > 0.5) inside, as feature_fill.hpp's.
};

/// A style palette: a palette image, the features picked in it and their assignment to a
/// drawing's paths. Assignment keys: ".name" (a class of the element's `class` attribute),
/// a colour ("#rrggbb", or any SVG colour: keys go through sketch::normalize_colour) and
/// "default"; a path takes the first of its classes that has a key, else its colour's, else the
/// default's.
struct StylePalette {
    Image palette;
    std::vector<StyleLineFeature> line_features;
    std::vector<StyleAreaFeature> area_features;
    /// Stroke key → line feature name, for every path with a stroke.
    std::vector<std::pair<std::string, std::string>> strokes;
    /// Fill key → area feature name, for every element with a fill.
    std::vector<std::pair<std::string, std::string>> fills;
    /// The area feature that fills the whole canvas first; "" = none (transparent background).
    std::string background;
};

/// Checks a style palette: the palette's channels (1, 3 or 4), unique feature names, regions of
/// the palette's size, and that every assignment and the background name a feature of their kind
/// (`strokes: "#000000" names line feature "rail", which is not defined (defined: ink)`).
Status validate(const StylePalette& palette);

/// Reads a style palette file (JSON, docs/feature.md); the palette image and region images are
/// read relative to the file's folder. Errors (one line naming the file and, where it applies,
/// the key): unreadable file, malformed JSON, unknown keys, malformed paths or polygons,
/// unreadable images, then validate's.
Result<StylePalette> load_style_palette(const std::string& path);

/// Options of vectorize_style: the brush's and the fill's (their option tables).
struct VectorizeStyleOptions {
    FeatureBrushOptions brush;
    FeatureFillOptions fill;
};

/// Renders `drawing` on a `width` × `height` canvas (the viewBox mapped onto it) in the style of
/// `palette`: the background area feature (if any) over the whole canvas, then each filled
/// element's area feature inside its shape (continuing the background across its border when
/// there is one), then each stroked path with its line feature, "over", in document order.
/// Returns RGBA (straight alpha), transparent where nothing is painted. Errors (InvalidArgument,
/// one line): a drawing without paths, a path or fill without an assigned feature, a feature
/// that cannot be selected (named), a stroke too short to paint (named by path index), the
/// fill's and brush's option errors; Cancelled.
Result<Image> vectorize_style(const sketch::Drawing& drawing, const StylePalette& palette,
                              int width, int height, const VectorizeStyleOptions& options = {},
                              const RunContext& context = {});

}  // namespace exemplar::paint
