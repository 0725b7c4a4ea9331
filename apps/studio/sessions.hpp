#pragma once
// Per-client tool state of the studio: a ShipShape sketch and a Brushables painting, each with
// undo/redo. Both only call the library (sketch::suggest/accept, paint::PaintCanvas/repaint).

#include <cstddef>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/paint/feature_brush.hpp"
#include "exemplar/paint/feature_fill.hpp"
#include "exemplar/paint/paint.hpp"
#include "exemplar/paint/strokes.hpp"
#include "exemplar/sketch/beautify.hpp"

namespace exemplar::studio {

/// Undo/redo over snapshots: the states after each step, the current one, and at most `limit`
/// steps back.
template <class State>
class History {
public:
    explicit History(State first, std::size_t limit = static_cast<std::size_t>(-1))
        : limit_(limit) {
        states_.push_back(std::move(first));
    }
    const State& current() const { return states_[current_]; }
    /// Makes `next` current, dropping the redo steps and the oldest beyond the limit.
    void push(State next) {
        states_.erase(states_.begin() + static_cast<std::ptrdiff_t>(current_) + 1, states_.end());
        states_.push_back(std::move(next));
        if (states_.size() - 1 > limit_) states_.erase(states_.begin());
        current_ = states_.size() - 1;
    }
    bool can_undo() const { return current_ > 0; }
    bool can_redo() const { return current_ + 1 < states_.size(); }
    bool undo() { return can_undo() && (--current_, true); }
    bool redo() { return can_redo() && (++current_, true); }

private:
    std::vector<State> states_;
    std::size_t current_ = 0;
    std::size_t limit_;
};

/// A sketch beautified stroke by stroke (ShipShape): each pen-up gives ranked suggestions, one of
/// which the user accepts. Undo/redo step over accepted strokes.
class SketchSession {
public:
    /// Suggestions for a new stroke through `points` (canvas pixels) against the accepted
    /// drawing; they stay pending until `accept`. InvalidArgument for a degenerate stroke.
    Result<std::vector<sketch::Suggestion>> stroke(const std::vector<sketch::Vec2>& points);
    /// Accepts pending suggestion `index` as the next stroke (and clears the redo steps).
    Status accept(int index);
    bool undo();
    bool redo();
    void reset();
    bool can_undo() const { return history_.can_undo(); }
    bool can_redo() const { return history_.can_redo(); }
    /// The accepted drawing.
    const sketch::ResolvedDrawing& drawing() const { return history_.current(); }

private:
    History<sketch::ResolvedDrawing> history_{sketch::ResolvedDrawing{}};
    std::vector<sketch::Suggestion> pending_;
};

/// A Brushables painting: strokes add to a PaintCanvas and only the touched rectangle is
/// synthesized again (paint::repaint). Undo/redo step over strokes by snapshots.
class PaintSession {
public:
    /// Most strokes that can be undone.
    static constexpr std::size_t kHistory = 16;

    /// A blank `width` × `height` canvas painted with `exemplar` (3 or 4 channels); its direction
    /// field is analysed once here rather than on every stroke.
    static Result<PaintSession> start(Image exemplar, int width, int height,
                                      const paint::PaintOptions& options, int threads);

    /// Applies a painting or combing stroke and repaints what it touched; returns that
    /// rectangle. The painting is unchanged on error.
    Result<paint::PixelRect> stroke(const paint::Stroke& stroke, const RunContext& context);
    /// What `stroke` would give, quickly (paint::preview_repaint, reduced `reduction` times):
    /// the painting with the stroke previewed and the rectangle it touched. The session is
    /// unchanged, so undo/redo never see a preview; `stroke` paints the final pixels after.
    struct Preview {
        Image image;
        paint::PixelRect changed;
    };
    Result<Preview> preview(const paint::Stroke& stroke, int reduction,
                            const RunContext& context) const;
    bool undo() { return history_.undo(); }
    bool redo() { return history_.redo(); }
    /// The painting: RGBA, straight alpha, transparent where nothing is painted.
    const Image& image() const { return history_.current().image; }
    int width() const { return image().width(); }
    int height() const { return image().height(); }

private:
    struct State {
        paint::PaintCanvas canvas;
        Image image;
    };
    PaintSession(paint::PaintSource source, const paint::PaintOptions& options, State blank);

    paint::PaintSource source_;
    paint::PaintOptions options_;
    History<State> history_;
};

/// Painting by Feature's line-feature brush and area fill: a feature picked once in a palette,
/// then strokes painted with it one over the other, as `exemplar brush` paints its paths
/// (paint_feature: path k keyed by k, each layer composited over the ones before), and regions
/// filled with the texture of regions of the palette, as `exemplar fill` fills them with the
/// painting as its canvas. Undo/redo by snapshots.
class BrushSession {
public:
    static constexpr std::size_t kHistory = 16;

    /// Picks the feature along `selection` in `palette` (snapped to its edge unless `snap` is
    /// false; paint::pick_line_feature) for a blank `width` × `height` painting.
    static Result<BrushSession> start(const Image& palette, const paint::Stroke& selection,
                                      int width, int height,
                                      const paint::FeatureBrushOptions& options, bool snap,
                                      int threads);

    /// Paints one stroke along `path` (its width_px is the brush width) over the painting;
    /// returns the rectangle it changed. The painting is unchanged on error. Only the context's
    /// thread count is used: the library's brush reports no progress and cannot be cancelled.
    Result<paint::PixelRect> stroke(const paint::Stroke& path, const RunContext& context);
    /// Fills the inside of `target_region` (a region image of the painting's size) with the
    /// texture of the inside of `source_region` (the palette's size) by the content-aware fill
    /// (paint::fill_with_palette, the painting as the canvas: what is painted around the region
    /// is continued into it); returns the bounding box of the region, the only pixels that
    /// change. The painting is unchanged on error (empty regions, options; Cancelled).
    Result<paint::PixelRect> fill(const Image& source_region, const Image& target_region,
                                  const paint::FeatureFillOptions& options,
                                  const RunContext& context);
    bool undo() { return history_.undo(); }
    bool redo() { return history_.redo(); }
    const Image& image() const { return history_.current().image; }
    int width() const { return image().width(); }
    int height() const { return image().height(); }
    const Image& palette() const { return palette_; }
    /// The feature's centre line in the palette (after snapping), for display.
    std::vector<paint::StrokePoint> feature_line() const;

private:
    struct State {
        Image image;
        std::uint64_t strokes = 0;  ///< Paths painted: the next one's key (paint_feature's k).
    };
    BrushSession(Image palette, paint::LineFeature feature, State blank)
        : palette_(std::move(palette)),
          feature_(std::move(feature)),
          history_(std::move(blank), kHistory) {}

    Image palette_;
    paint::LineFeature feature_;
    History<State> history_;
};

}  // namespace exemplar::studio
