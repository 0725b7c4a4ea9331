#include "sessions.hpp"

#include <algorithm>
#include <utility>

#include "exemplar/paint/directions.hpp"

namespace exemplar::studio {

Result<std::vector<sketch::Suggestion>> SketchSession::stroke(
    const std::vector<sketch::Vec2>& points) {
    auto suggestions = sketch::suggest(drawing(), sketch::polyline_path(points));
    if (!suggestions.ok()) return suggestions.status();
    pending_ = *suggestions;
    return suggestions;
}

Status SketchSession::accept(int index) {
    if (pending_.empty()) return invalid_argument("accept: no stroke is waiting for a choice");
    if (index < 0 || index >= static_cast<int>(pending_.size())) {
        return invalid_argument("index: " + std::to_string(index) + " is invalid (must be 0.." +
                                std::to_string(pending_.size() - 1) + ")");
    }
    sketch::ResolvedDrawing next = drawing();
    sketch::accept(next, pending_[static_cast<std::size_t>(index)]);
    history_.push(std::move(next));
    pending_.clear();
    return Status::ok();
}

bool SketchSession::undo() {
    pending_.clear();
    return history_.undo();
}

bool SketchSession::redo() {
    pending_.clear();
    return history_.redo();
}

void SketchSession::reset() {
    history_ = History<sketch::ResolvedDrawing>(sketch::ResolvedDrawing{});
    pending_.clear();
}

PaintSession::PaintSession(paint::PaintSource source, const paint::PaintOptions& options,
                           State blank)
    : source_(std::move(source)), options_(options), history_(std::move(blank), kHistory) {}

Result<PaintSession> PaintSession::start(Image exemplar, int width, int height,
                                         const paint::PaintOptions& options, int threads) {
    EXEMPLAR_RETURN_IF_ERROR(paint::validate(options));
    if (exemplar.channels() != 3 && exemplar.channels() != 4) {
        return invalid_argument("exemplar: " + std::to_string(exemplar.channels()) +
                                " channels (must be 3 or 4)");
    }
    // The default direction field of paint(), made once for the session's strokes.
    auto field = paint::analyze_directions(exemplar, {}, threads);
    if (!field.ok()) return field.status();
    paint::PaintSource source;
    source.image = std::move(exemplar);
    source.directions = paint::direction_angles(*field);
    return PaintSession(std::move(source), options,
                        State{paint::PaintCanvas(width, height), Image(width, height, 4)});
}

Result<Image> PaintSession::repaint(const paint::PaintCanvas& canvas,
                                    const paint::PixelRect& changed,
                                    const RunContext& context) const {
    auto painted = paint::repaint(source_, canvas, image(), changed, options_, context);
    if (!painted.ok()) return painted.status();
    return std::move(painted->image);
}

Result<Image> PaintSession::preview(const paint::PaintCanvas& canvas, const Image& previous,
                                    const paint::PixelRect& changed, int reduction,
                                    const RunContext& context) const {
    auto previewed =
        paint::preview_repaint(source_, canvas, previous, changed, options_, reduction, context);
    if (!previewed.ok()) return previewed.status();
    return std::move(previewed->image);
}

namespace {

// Copies `rect` of `from` into `to` (the same size and channels).
void copy_rect(const Image& from, const paint::PixelRect& rect, Image& to) {
    const auto row = static_cast<std::size_t>(rect.x1 - rect.x0) * from.channels();
    for (int y = rect.y0; y < rect.y1; ++y) {
        std::copy_n(from.pixel(rect.x0, y), row, to.pixel(rect.x0, y));
    }
}

Status cancelled_stroke() {
    return {ErrorCode::Cancelled, "stroke: cancelled (undone, or the painting was replaced)"};
}

}  // namespace

PaintPipeline::PaintPipeline(PaintSession session)
    : width_(session.width()),
      height_(session.height()),
      session_(std::move(session)),
      tip_(session_.canvas()),
      shown_(session_.image()) {}

Status PaintPipeline::stroke(const paint::Stroke& stroke, const RunContext& context,
                             const Answer& answer) {
    std::unique_lock lock(mutex_);
    if (cancelled_) return cancelled_stroke();
    auto mine = std::make_shared<Pending>(tip_);
    auto changed = mine->canvas.add_stroke(stroke, context.threads);
    if (!changed.ok()) return changed.status();
    mine->changed = *changed;
    tip_ = mine->canvas;
    pending_.push_back(mine);
    ++strokes_;
    // The strokes queued before this one first.
    changed_.wait(lock, [&] { return mine->dropped || pending_.front() == mine; });
    if (mine->dropped) {
        if (!pending_.empty() && pending_.front() == mine) pending_.pop_front();  // not begun
        changed_.notify_all();
        return cancelled_stroke();
    }

    // Only the front stroke changes the session, so it repaints without the lock (previews,
    // new strokes and undo go on meanwhile; undo cancels it through its token).
    lock.unlock();
    RunContext run(context.threads);
    run.progress = context.progress;
    run.cancel = &mine->cancel;
    auto painted = session_.repaint(mine->canvas, mine->changed, run);
    lock.lock();
    pending_.pop_front();
    Status status = Status::ok();
    if (mine->dropped) {
        status = cancelled_stroke();
    } else if (!painted.ok()) {
        status = painted.status();
        drop_from(0);  // the strokes after it were added to a canvas holding it
    } else {
        session_.push(mine->canvas, std::move(*painted));
        copy_rect(session_.image(), mine->changed, shown_);
        if (answer) answer(session_.image(), mine->changed);
    }
    changed_.notify_all();
    return status;
}

Status PaintPipeline::preview(const paint::Stroke& stroke, int reduction, const RunContext& context,
                              const Answer& answer) {
    // Under the lock throughout (a few tens of ms): a final answered meanwhile would otherwise
    // be overdrawn by a preview composed before it.
    std::lock_guard lock(mutex_);
    if (cancelled_) return cancelled_stroke();
    paint::PaintCanvas canvas = tip_;
    auto changed = canvas.add_stroke(stroke, context.threads);
    if (!changed.ok()) return changed.status();
    auto previewed = session_.preview(canvas, shown_, *changed, reduction, context);
    if (!previewed.ok()) return previewed.status();
    copy_rect(*previewed, *changed, shown_);
    if (answer) answer(*previewed, *changed);
    return Status::ok();
}

void PaintPipeline::drop_from(std::size_t from) {
    for (std::size_t k = from; k < pending_.size(); ++k) {
        pending_[k]->dropped = true;
        pending_[k]->cancel.cancel();
    }
    // The front one, repainting, takes itself off when its repaint returns.
    const std::size_t keep = std::max<std::size_t>(from, 1);
    if (pending_.size() > keep) {
        pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(keep), pending_.end());
    }
    tip_ = from > 0 ? pending_[from - 1]->canvas : session_.canvas();
    changed_.notify_all();
}

void PaintPipeline::answer_settled(std::unique_lock<std::mutex>& lock, const Answer& answer) {
    changed_.wait(lock, [&] { return pending_.empty(); });
    shown_ = session_.image();
    if (answer) answer(shown_, {0, 0, width_, height_});
}

void PaintPipeline::undo(const Answer& answer) {
    std::unique_lock lock(mutex_);
    if (pending_.empty()) {
        session_.undo();
        tip_ = session_.canvas();
    } else {
        drop_from(pending_.size() - 1);
    }
    answer_settled(lock, answer);
}

void PaintPipeline::redo(const Answer& answer) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return pending_.empty(); });
    session_.redo();
    tip_ = session_.canvas();
    answer_settled(lock, answer);
}

void PaintPipeline::settled(const Answer& answer) {
    std::unique_lock lock(mutex_);
    answer_settled(lock, answer);
}

void PaintPipeline::cancel() {
    std::lock_guard lock(mutex_);
    cancelled_ = true;
    drop_from(0);
}

PaintPipeline::Counts PaintPipeline::counts() const {
    std::lock_guard lock(mutex_);
    return {strokes_,
            static_cast<std::size_t>(std::count_if(pending_.begin(), pending_.end(),
                                                   [](const auto& p) { return !p->dropped; }))};
}

Result<BrushSession> BrushSession::start(const Image& palette, const paint::Stroke& selection,
                                         int width, int height,
                                         const paint::FeatureBrushOptions& options, bool snap,
                                         int threads) {
    auto feature = paint::pick_line_feature(palette, selection, options, snap, threads);
    if (!feature.ok()) return feature.status();
    return BrushSession(palette, std::move(*feature), State{Image(width, height, 4), 0});
}

Result<paint::PixelRect> BrushSession::stroke(const paint::Stroke& path,
                                              const RunContext& context) {
    EXEMPLAR_RETURN_IF_ERROR(paint::validate(path));
    const State& now = history_.current();
    paint::BrushStroke stroke(feature_, width(), height(), path.width_px, now.strokes,
                              context.threads);
    auto changed = stroke.add_points(path.points, context.cancel);
    if (!changed.ok()) return changed.status();
    history_.push(State{paint::composite_over(stroke.layer(), now.image), now.strokes + 1});
    return *changed;
}

Result<paint::PixelRect> BrushSession::fill(const Image& source_region, const Image& target_region,
                                            const paint::FeatureFillOptions& options,
                                            const RunContext& context) {
    const State& now = history_.current();
    auto filled = paint::fill_with_palette(palette_, source_region, now.image, target_region,
                                           options, context);
    if (!filled.ok()) return filled.status();
    // The region's bounding box: fill_with_palette keeps every pixel outside it.
    const Image inside = paint::region_mask(target_region);
    paint::PixelRect box{width(), height(), 0, 0};
    for (int y = 0; y < height(); ++y) {
        for (int x = 0; x < width(); ++x) {
            if (inside.at(x, y, 0) <= 0.5f) continue;
            box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x + 1),
                   std::max(box.y1, y + 1)};
        }
    }
    history_.push(State{std::move(*filled), now.strokes});
    return box;
}

std::vector<paint::StrokePoint> BrushSession::feature_line() const {
    std::vector<paint::StrokePoint> line;
    for (const paint::PathSample& s : feature_.samples()) line.push_back({s.x, s.y});
    return line;
}

std::shared_ptr<CancelToken> StepSlot::begin() {
    std::lock_guard lock(mutex_);
    running_.push_back(std::make_shared<CancelToken>());
    return running_.back();
}

bool StepSlot::finish(const std::shared_ptr<CancelToken>& token) {
    std::lock_guard lock(mutex_);
    std::erase(running_, token);
    return !token->cancelled();
}

bool StepSlot::cancel_newest() {
    std::lock_guard lock(mutex_);
    for (auto it = running_.rbegin(); it != running_.rend(); ++it) {
        if ((*it)->cancelled()) continue;
        (*it)->cancel();
        return true;
    }
    return false;
}

void StepSlot::cancel_all() {
    std::lock_guard lock(mutex_);
    for (const auto& token : running_) token->cancel();
}

}  // namespace exemplar::studio
