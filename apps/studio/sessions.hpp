#pragma once
// Per-client tool state of the studio: a ShipShape sketch and a Brushables painting, each with
// undo/redo. Both only call the library (sketch::suggest/accept, paint::PaintCanvas/repaint).

#include <cstddef>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/paint/paint.hpp"
#include "exemplar/paint/strokes.hpp"
#include "exemplar/sketch/beautify.hpp"

namespace exemplar::studio {

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
    bool can_undo() const { return current_ > 0; }
    bool can_redo() const { return current_ + 1 < history_.size(); }
    /// The accepted drawing.
    const sketch::ResolvedDrawing& drawing() const { return history_[current_]; }

private:
    std::vector<sketch::ResolvedDrawing> history_{sketch::ResolvedDrawing{}};
    std::size_t current_ = 0;
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
    bool undo();
    bool redo();
    /// The painting: RGBA, straight alpha, transparent where nothing is painted.
    const Image& image() const { return history_[current_].image; }
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
    std::vector<State> history_;
    std::size_t current_ = 0;
};

}  // namespace exemplar::studio
