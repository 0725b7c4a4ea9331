#pragma once
// Per-client tool state of the studio: a ShipShape sketch and a Brushables painting, each with
// undo/redo. Both only call the library (sketch::suggest/accept, paint::PaintCanvas/repaint).

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
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
/// synthesized again (paint::repaint). Undo/redo step over strokes by snapshots. Not
/// thread-safe: PaintPipeline orders the calls of a client's requests.
class PaintSession {
public:
    /// Most strokes that can be undone.
    static constexpr std::size_t kHistory = 16;

    /// A blank `width` × `height` canvas painted with `exemplar` (3 or 4 channels); its direction
    /// field is analysed once here rather than on every stroke.
    static Result<PaintSession> start(Image exemplar, int width, int height,
                                      const paint::PaintOptions& options, int threads);

    /// The final pixels of `canvas` (the current canvas with strokes added, which changed
    /// `changed`): paint::repaint from the current painting. Changes nothing; `push` keeps it.
    Result<Image> repaint(const paint::PaintCanvas& canvas, const paint::PixelRect& changed,
                          const RunContext& context) const;
    /// A quick look at the same (paint::preview_repaint, reduced `reduction` times) over
    /// `previous`, the image the page shows. Changes nothing (undo/redo never see a preview).
    Result<Image> preview(const paint::PaintCanvas& canvas, const Image& previous,
                          const paint::PixelRect& changed, int reduction,
                          const RunContext& context) const;
    /// Makes a repainted canvas and its painting the current state (one undo step).
    void push(paint::PaintCanvas canvas, Image image) {
        history_.push(State{std::move(canvas), std::move(image)});
    }
    bool undo() { return history_.undo(); }
    bool redo() { return history_.redo(); }
    /// The painting: RGBA, straight alpha, transparent where nothing is painted.
    const Image& image() const { return history_.current().image; }
    const paint::PaintCanvas& canvas() const { return history_.current().canvas; }
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

/// A client's painting as a pipeline (docs/studio.md, "The paint pipeline"): strokes are
/// applied in the order they arrive, each final repaint from the previous stroke's final, so
/// the painting is the one paint::repaint gives applying the strokes one by one, however
/// quickly they come; a preview does not wait for the finals in flight and is composed over the
/// newest image the page was sent (a final, or the preview of a stroke still pending), so it
/// never shows older pixels than the page displays. Undo drops the newest pending stroke and
/// stops its repaint; `cancel` stops them all (a new painting, shutdown). Thread-safe.
class PaintPipeline {
public:
    /// What a request answers: a rectangle of an image (RGBA), called under the pipeline's lock
    /// (may be empty).
    using Answer = std::function<void(const Image& image, const paint::PixelRect& rect)>;

    explicit PaintPipeline(PaintSession session);

    /// Queues a painting or combing stroke, waits for the strokes queued before it, repaints
    /// and answers the rectangle it changed. Cancelled when undone or cancelled meanwhile (the
    /// painting is then as if it had not been sent); a stroke that fails takes the strokes
    /// queued after it along (their canvases hold it). `context`: threads and progress.
    Status stroke(const paint::Stroke& stroke, const RunContext& context, const Answer& answer);
    /// Answers the stroke's coarse preview (PaintSession::preview) over the newest state: every
    /// stroke queued so far, over the image last answered. Changes no painting.
    Status preview(const paint::Stroke& stroke, int reduction, const RunContext& context,
                   const Answer& answer);
    /// Drops the newest pending stroke (stopping its repaint), or else steps back; then, once
    /// the strokes before it are final, answers the whole painting.
    void undo(const Answer& answer);
    /// Once no stroke is pending, steps forward and answers the whole painting.
    void redo(const Answer& answer);
    /// Once no stroke is pending, answers the whole painting (save).
    void settled(const Answer& answer);
    /// Stops every pending stroke (their requests answer Cancelled) and refuses new ones.
    void cancel();
    /// Strokes queued since the start, and those of them neither final nor dropped yet.
    struct Counts {
        std::uint64_t strokes = 0;
        std::size_t pending = 0;
    };
    Counts counts() const;
    int width() const { return width_; }
    int height() const { return height_; }

private:
    struct Pending {
        explicit Pending(paint::PaintCanvas c) : canvas(std::move(c)) {}
        paint::PaintCanvas canvas;  ///< The previous stroke's canvas with this one added.
        paint::PixelRect changed;
        CancelToken cancel;
        bool dropped = false;  ///< Undone or cancelled: nothing of it is kept.
    };
    /// Drops `pending_` from `from` on (under mutex_): cancels them and makes tip_ the canvas
    /// of the last one kept.
    void drop_from(std::size_t from);
    /// The whole painting after the pending strokes are final (under `lock`).
    void answer_settled(std::unique_lock<std::mutex>& lock, const Answer& answer);

    const int width_, height_;
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    /// The finals. Only the front pending stroke changes it (after its repaint); undo, redo and
    /// save wait until nothing is pending.
    PaintSession session_;
    /// Queued strokes in order; the front one is repainting.
    std::deque<std::shared_ptr<Pending>> pending_;
    /// The canvas with every queued stroke: where the next one is added.
    paint::PaintCanvas tip_;
    /// The newest image the page was sent: finals and previews, in the order answered.
    Image shown_;
    std::uint64_t strokes_ = 0;
    bool cancelled_ = false;
};

/// The steps of a tool that runs them one at a time under the client's lock (a brush stroke, a
/// fill), each with its own cancel token, so undo and a new start stop the newest running or
/// waiting step instead of waiting behind it. Thread-safe.
class StepSlot {
public:
    /// The token of a new step, taken before the client's lock.
    std::shared_ptr<CancelToken> begin();
    /// Ends the step of `token`: true when its result stays (it was not cancelled meanwhile).
    bool finish(const std::shared_ptr<CancelToken>& token);
    /// Cancels the newest step not cancelled yet; false when there is none.
    bool cancel_newest();
    /// Cancels every step (a new start, shutdown).
    void cancel_all();

private:
    std::mutex mutex_;
    std::vector<std::shared_ptr<CancelToken>> running_;
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
    /// returns the rectangle it changed. The painting is unchanged on error (Cancelled when the
    /// context's token is set). The library's brush reports no progress.
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
