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

Result<paint::PixelRect> PaintSession::stroke(const paint::Stroke& stroke,
                                              const RunContext& context) {
    State next = history_.current();
    auto changed = next.canvas.add_stroke(stroke, context.threads);
    if (!changed.ok()) return changed.status();
    auto painted = paint::repaint(source_, next.canvas, next.image, *changed, options_, context);
    if (!painted.ok()) return painted.status();
    next.image = std::move(painted->image);
    history_.push(std::move(next));
    return *changed;
}

Result<PaintSession::Preview> PaintSession::preview(const paint::Stroke& stroke, int reduction,
                                                    const RunContext& context) const {
    paint::PaintCanvas canvas = history_.current().canvas;
    auto changed = canvas.add_stroke(stroke, context.threads);
    if (!changed.ok()) return changed.status();
    auto previewed =
        paint::preview_repaint(source_, canvas, image(), *changed, options_, reduction, context);
    if (!previewed.ok()) return previewed.status();
    return Preview{std::move(previewed->image), *changed};
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
    auto changed = stroke.add_points(path.points);
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

}  // namespace exemplar::studio
