#pragma once
/// \file
/// The line-feature brush of Painting by Feature (Lukáč, Fišer, Bazin, Jamriška, Sorkine-Hornung,
/// Sýkora, ACM TOG 32(4) 2013; chapter 3 of Fišer's thesis, §3.3.1). Any image is a feature
/// palette: the user draws roughly along a line feature in it (an edge, a contour, a textured
/// stroke), the path snaps to the feature (active contours, Kass et al. 1988), and the feature
/// is then painted along new paths of any length without visible repetition:
/// - the selected path is sampled at equal intervals; each sample has a square patch aligned
///   with the path, as wide as the selection;
/// - the feature graph: edge i → j costs w(i, j) = SSD(p(i), p(j − 1)), so stepping along the
///   source (j = i + 1) is free;
/// - the walk: random goal nodes joined by Dijkstra's cheapest paths, extended until it is long
///   enough, a pure function of (seed, segment index): a longer stroke never changes the walk's
///   prefix;
/// - the Voronoi piecewise-rigid mapping: each output pixel within the brush width takes the
///   nearest target sample and the same relative position in its source sample's frame;
/// - blending at the walk's jumps: the palette's base layer (bilateral filter, Durand and Dorsey
///   2002) is extrapolated from both sides of the jump and blended, the detail is kept.
/// Deviations and our choices are listed in docs/feature.md.
///
/// Coordinates are pixels with (0, 0) the top-left corner of the top-left pixel, as in
/// strokes.hpp; paths are `Stroke`s (centre line and width). Everything is deterministic for any
/// thread count.

#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/paint/strokes.hpp"

namespace exemplar::paint {

class PathSampler;
class WalkBuilder;

/// How the walk through the feature graph is made (thesis Fig. 3.3).
enum class WalkMode {
    /// The chapter's randomized low-discontinuity walk: random goal nodes, Dijkstra between them.
    /// Prefix-stable.
    Randomized,
    /// Schödl et al. 2000's best loop: the source from its start to the cheapest backward jump
    /// spanning at least half of it, then that loop forever. Prefix-stable, periodic.
    Looping,
    /// The cheapest walk of exactly the needed length (dynamic programming over the graph). Not
    /// prefix-stable: a longer stroke redraws everything. Degenerates to cycling the cheapest loop.
    DynamicProgramming,
};

/// "randomized", "looping", "dp".
std::string_view to_string(WalkMode mode);
/// Parses the names of to_string; the error names the accepted values.
Result<WalkMode> parse_walk_mode(std::string_view name);

/// Options of the brush. The chapter states no numbers besides "patch size = selection width";
/// every default below is ours unless noted (docs/feature.md).
struct FeatureBrushOptions {
    /// Distance between consecutive samples of the source and target paths, in source pixels
    /// (the target's spacing is scaled by brush width / selection width). Default 2; 0.5..64.
    float sample_spacing_px = 2.0f;
    /// Half-length, in target pixels along the path, of the base-layer blend across each jump of
    /// the walk. 0 turns the blending off. Default 16; 0..256.
    float blend_radius_px = 16.0f;
    /// σ of the bilateral filter's spatial Gaussian that makes the base layer, in palette pixels.
    /// Default 4; 0.5..64.
    float base_sigma_px = 4.0f;
    /// σ of the bilateral filter's range Gaussian, on colour distance (values in [0, 1]).
    /// Default 0.1; 0.01..10.
    float base_range_sigma = 0.1f;
    /// Shortest jump the walk may make, in source pixels: an edge i → j other than the free step
    /// j = i + 1 needs |j − 1 − i| · spacing ≥ this, so the walk cannot stutter by repeating or
    /// skipping a sample or two (capped at a quarter of the source path). Default 8; 0..1000.
    float min_jump_px = 8.0f;
    /// Active contour (greedy, Williams and Shah 1992): weight of the continuity (elasticity)
    /// term. Default 1 (Williams and Shah); 0..100.
    float snap_elasticity = 1.0f;
    /// Active contour: weight of the curvature (rigidity) term. Default 1 (Williams and Shah);
    /// 0..100.
    float snap_rigidity = 1.0f;
    /// Active contour: weight of the image (edge) term. Default 1.2 (Williams and Shah); 0..100.
    float snap_edge_weight = 1.2f;
    /// Active contour: σ of the Gaussian blur before the gradient, in pixels; larger = the rough
    /// path may be farther from the edge (capture range ≈ 3σ), less precise. Default 2; 0..32.
    float snap_sigma_px = 2.0f;
    /// Active contour: spacing of the contour's points in pixels. Default 4; 1..64.
    float snap_spacing_px = 4.0f;
    /// Active contour: most greedy iterations (it stops earlier when fewer than 1% of the points
    /// move). Default 100; 0..10000.
    int snap_iterations = 100;
    WalkMode walk = WalkMode::Randomized;  ///< Default: the chapter's randomized walk.
    /// Random seed: path k's walk is a pure function of (seed, k, segment).
    std::uint64_t seed = 1;
};

/// Description of one numeric option (name, doc, unit, range): the one table that validation,
/// the CLI flags and docs/feature.md use.
struct FeatureBrushOptionSpec {
    std::string_view name;  ///< kebab-case: the CLI flag --name.
    std::string_view doc;
    std::string_view unit;
    double min = 0.0;  ///< Inclusive range.
    double max = 0.0;
    std::variant<int FeatureBrushOptions::*, float FeatureBrushOptions::*> field;
};

/// The table of numeric options.
std::span<const FeatureBrushOptionSpec> feature_brush_option_specs();
/// Reads an option's value as a double.
double get_option(const FeatureBrushOptions& options, const FeatureBrushOptionSpec& spec);
/// Sets an option; rejects values outside the range and non-integers for integer options
/// (`sample-spacing: 0 is invalid (must be 0.5..64)`).
Status set_option(FeatureBrushOptions& options, const FeatureBrushOptionSpec& spec, double value);
/// Checks every option.
Status validate(const FeatureBrushOptions& options);

/// Snaps a rough path drawn along a line feature of `palette` (1, 3 or 4 channels; alpha is
/// ignored) onto the feature's edge: a greedy active contour (Williams and Shah 1992's
/// discretization of Kass et al. 1988) with the elasticity, rigidity and edge terms of
/// `options`, on the points of the rough polyline resampled every `snap_spacing_px`. Open
/// contour: the end points move too. Errors (InvalidArgument): fewer than two points, a point
/// outside the palette (or not finite).
Result<std::vector<StrokePoint>> snap_to_edges(const Image& palette,
                                               std::span<const StrokePoint> rough,
                                               const FeatureBrushOptions& options = {});

/// A point of a sampled path and its unit tangent (the path's direction).
struct PathSample {
    float x = 0.0f, y = 0.0f;
    float tx = 1.0f, ty = 0.0f;
};

/// A selected line feature, ready to paint with: the source samples, their patches' feature
/// graph and the palette's base layer around them. Immutable; share it between strokes.
class LineFeature {
public:
    /// Samples `selection` (its centre line, in palette pixels; its width is the patch size)
    /// every `sample_spacing_px` and builds the feature graph. Errors (InvalidArgument), each
    /// naming the problem: a palette without 1, 3 or 4 channels, invalid options, fewer than two
    /// points or samples (the path is shorter than the spacing), a point outside the palette.
    /// `threads`: 0 = all cores; the result does not depend on it.
    static Result<LineFeature> create(const Image& palette, const Stroke& selection,
                                      const FeatureBrushOptions& options = {}, int threads = 0);

    /// Number of samples (graph nodes), ≥ 2.
    int size() const { return static_cast<int>(samples_.size()); }
    /// The samples in the palette, in path order.
    std::span<const PathSample> samples() const { return samples_; }
    /// The selection width: the patch size and the brush width at scale 1.
    float width_px() const { return width_px_; }
    /// The options it was made with.
    const FeatureBrushOptions& options() const { return options_; }
    /// Edge weight w(i, j) = SSD(p(i), p(j − 1)) as the mean squared difference per patch
    /// point and channel; 0 for the free step j = i + 1; +∞ for edges into node 0 and for jumps
    /// shorter than the minimum jump. Any other jump costs at least 1e-6, so that among equally
    /// cheap routes the walk keeps the source's order.
    float cost(int from, int to) const {
        return costs_[static_cast<std::size_t>(from) * size() + to];
    }

    /// The palette colour (its channels) at palette position (x, y), bilinear, clamped to the
    /// region kept around the selection.
    void colour(float x, float y, float* out) const;
    /// The base layer (bilateral filter) at (x, y), bilinear; the palette's colour channels only.
    void base(float x, float y, float* out) const;
    /// Channels of the palette (1, 3 or 4); 4 means RGBA with straight alpha.
    int channels() const { return crop_.channels(); }

private:
    LineFeature() = default;
    std::vector<PathSample> samples_;
    std::vector<float> costs_;
    Image crop_;  // the palette around the selection
    Image base_;  // its base layer
    int crop_x_ = 0, crop_y_ = 0;
    float width_px_ = 0.0f;
    FeatureBrushOptions options_;
};

/// The walk: `length` source sample indices (graph nodes) for a stroke, made as `mode` says
/// with randomness keyed by (`seed`, `path_index`) (Randomized only), the walk `BrushStroke`
/// uses. Randomized and Looping walks of length L are the prefixes of longer ones.
std::vector<int> feature_walk(const LineFeature& feature, WalkMode mode, int length,
                              std::uint64_t seed, std::uint64_t path_index = 0);
/// Total discontinuity cost of a walk: the sum of w(walk[k − 1], walk[k]).
double walk_cost(const LineFeature& feature, std::span<const int> walk);

/// One stroke painted with a line feature, grown point by point as the user draws: the target
/// path is sampled every spacing (scaled by width / selection width) from its start, the walk
/// extended as far as needed, and only the pixels that can change are drawn again. With a
/// prefix-stable walk mode, pixels whose nearest sample is settled (`settled_samples`) never
/// change again unless the path comes back over them.
class BrushStroke {
public:
    /// An empty stroke on a `canvas_width` × `canvas_height` layer, `width_px` wide (> 0,
    /// checked), painted with `feature` (which must outlive the stroke) and its options' walk
    /// mode and seed; `path_index` keys its randomness with the seed. `threads`: 0 = all cores;
    /// the result does not depend on it.
    BrushStroke(const LineFeature& feature, int canvas_width, int canvas_height, float width_px,
                std::uint64_t path_index = 0, int threads = 0);

    /// Appends points to the target path and draws what they add. Returns the rectangle of
    /// pixels that may have changed (empty if none), or InvalidArgument for a non-finite point
    /// (the stroke is then unchanged). `cancel` (optional) stops the drawing: Cancelled once it
    /// is set, and the stroke, partly drawn, is only good for discarding; unset, the pixels are
    /// those drawn without it.
    Result<PixelRect> add_points(std::span<const StrokePoint> points,
                                 const CancelToken* cancel = nullptr);
    Result<PixelRect> add_point(StrokePoint point) { return add_points({&point, 1}); }

    /// The stroke's layer: RGBA (straight alpha), the canvas size, transparent outside it.
    const Image& layer() const { return layer_; }
    /// Target samples so far.
    int samples() const { return static_cast<int>(targets_.size()); }
    /// Samples whose pixels are final: their frame, walk entry and blending no longer depend on
    /// what is added later (0 for the dynamic-programming walk, which redraws everything).
    int settled_samples() const;
    /// The walk: one source sample index per target sample.
    std::span<const int> walk() const { return walk_; }
    /// The target sample whose Voronoi cell holds pixel (x, y), or −1 where no sample is within
    /// half the brush width + 1 px (pixels beyond the flat end caps keep their sample but stay
    /// transparent).
    int nearest_sample(int x, int y) const;
    /// The target samples (positions and tangents), in path order.
    std::span<const PathSample> target_samples() const { return frames_; }

    BrushStroke(BrushStroke&&) noexcept;
    BrushStroke& operator=(BrushStroke&&) noexcept;
    ~BrushStroke();

private:
    /// Shades `rect`; false when `cancel` stopped it (rows left undrawn).
    bool shade(const PixelRect& rect, int first_dirty, const CancelToken* cancel);

    const LineFeature* feature_;
    float width_px_;
    float scale_;    // target px per source px
    float spacing_;  // target sample spacing
    std::uint64_t key_;
    int threads_;
    Image layer_;
    std::vector<int> owner_;    // nearest sample per pixel, −1 if none within reach
    std::vector<float> dist2_;  // its squared distance
    std::unique_ptr<PathSampler> sampler_;
    std::unique_ptr<WalkBuilder> walker_;
    std::vector<StrokePoint> targets_;
    std::vector<PathSample> frames_;  // targets_ with their tangents
    std::vector<int> walk_;
    int rasterized_ = 0;  // samples already in owner_
};

/// The feature a rough selection picks, as `exemplar brush` and exemplar.brush make it: `rough`'s
/// centre line snapped onto the palette's edge (snap_to_edges) unless `snap` is false, then
/// LineFeature::create. Errors: theirs.
Result<LineFeature> pick_line_feature(const Image& palette, Stroke rough,
                                      const FeatureBrushOptions& options = {}, bool snap = true,
                                      int threads = 0);

/// Paints every path of `paths` with `feature` on a transparent `width` × `height` layer, one
/// `BrushStroke` each (path k keyed by k), later paths over earlier ones. `brush_width_px` > 0
/// overrides the paths' widths (0 keeps them; at most 4096). Errors: InvalidArgument for no
/// path, an invalid brush width or an invalid path (named by index).
Result<Image> paint_feature(const LineFeature& feature, std::span<const Stroke> paths, int width,
                            int height, float brush_width_px = 0.0f, int threads = 0);

}  // namespace exemplar::paint
