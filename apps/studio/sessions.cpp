#include "sessions.hpp"

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
    history_.resize(current_ + 1);
    history_.push_back(std::move(next));
    ++current_;
    pending_.clear();
    return Status::ok();
}

bool SketchSession::undo() {
    pending_.clear();
    if (!can_undo()) return false;
    --current_;
    return true;
}

bool SketchSession::redo() {
    pending_.clear();
    if (!can_redo()) return false;
    ++current_;
    return true;
}

void SketchSession::reset() {
    history_.assign(1, sketch::ResolvedDrawing{});
    current_ = 0;
    pending_.clear();
}

PaintSession::PaintSession(paint::PaintSource source, const paint::PaintOptions& options,
                           State blank)
    : source_(std::move(source)), options_(options) {
    history_.push_back(std::move(blank));
}

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
    paint::PaintSource source{std::move(exemplar), Image(), paint::direction_angles(*field)};
    return PaintSession(std::move(source), options,
                        State{paint::PaintCanvas(width, height), Image(width, height, 4)});
}

Result<paint::PixelRect> PaintSession::stroke(const paint::Stroke& stroke,
                                              const RunContext& context) {
    State next = history_[current_];
    auto changed = next.canvas.add_stroke(stroke);
    if (!changed.ok()) return changed.status();
    auto painted = paint::repaint(source_, next.canvas, next.image, *changed, options_, context);
    if (!painted.ok()) return painted.status();
    next.image = std::move(painted->image);
    history_.erase(history_.begin() + static_cast<std::ptrdiff_t>(current_) + 1, history_.end());
    history_.push_back(std::move(next));
    if (history_.size() > kHistory + 1) history_.erase(history_.begin());
    current_ = history_.size() - 1;
    return *changed;
}

bool PaintSession::undo() {
    if (current_ == 0) return false;
    --current_;
    return true;
}

bool PaintSession::redo() {
    if (current_ + 1 >= history_.size()) return false;
    ++current_;
    return true;
}

}  // namespace exemplar::studio
