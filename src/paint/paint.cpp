// Brushables synthesis (Lukáč et al. 2015 §3.3) on the engine's public API.
//
// Where this deviates from the paper: the colours are synthesized premultiplied by alpha (the
// paper does not say; premultiplying makes every fully transparent pixel the same colour, so the
// transparent surroundings of a boundary patch compare equal in the exemplar and on the canvas);
// the exemplar patches are those centred on the shape mask (the engine's source mask is the
// mask grown by the patch radius, so a boundary patch may reach into the transparent outside).
// Several segmented textures (§4, Fig. 9) are the engine's label groups: a painted pixel takes
// only patches of its stroke's segment, and segment boundaries are Shape Hint edges on both sides.

#include "exemplar/paint/paint.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>
#include <string>
#include <utility>

#include "exemplar/filters/resample.hpp"
#include "exemplar/paint/directions.hpp"
#include "exemplar/paint/shape_hint.hpp"
#include "exemplar/synth/synthesize.hpp"

namespace exemplar::paint {

namespace {

constexpr int kOrientationSteps = 32;

// What `run` reads of a canvas: a PaintCanvas, or its images at a reduced scale (the preview).
class CanvasView {
public:
    explicit CanvasView(const PaintCanvas& canvas)
        : coverage_(&canvas.coverage()),
          directions_(&canvas.directions()),
          labels_(&canvas.labels()) {}
    CanvasView(const Image& coverage, const Image& directions, const Image& labels)
        : coverage_(&coverage), directions_(&directions), labels_(&labels) {}
    int width() const { return coverage_->width(); }
    int height() const { return coverage_->height(); }
    const Image& coverage() const { return *coverage_; }
    const Image& directions() const { return *directions_; }
    const Image& labels() const { return *labels_; }

private:
    const Image* coverage_;
    const Image* directions_;
    const Image* labels_;
};

std::string size_of(const Image& image) {
    return std::to_string(image.width()) + "x" + std::to_string(image.height());
}

// An optional per-pixel map of the exemplar: 1 channel (`what`), the exemplar's size.
Status check_exemplar_map(const Image& map, const Image& exemplar, const std::string& name,
                          const std::string& what) {
    if (map.same_size(exemplar) && map.channels() == 1) return Status::ok();
    return invalid_argument(name + ": " + size_of(map) + " with " + std::to_string(map.channels()) +
                            " channels (must be " + what + ", " + size_of(exemplar) +
                            " like the exemplar)");
}

// The exemplar as the engine sees it: premultiplied RGBA, its shape mask and its angles.
struct Exemplar {
    Image style;
    Image mask;
    Image angles;
    Image labels;               // empty, or the segmentation (rounded)
    std::set<long> segments;    // the labels that occur inside the shape
    bool has_boundary = false;  // some pixel outside the shape (else nothing to learn there)
};

Result<Exemplar> prepare(const PaintSource& source, int threads) {
    const Image& in = source.image;
    if (in.empty()) return invalid_argument("source: the exemplar is empty");
    if (in.channels() != 3 && in.channels() != 4) {
        return invalid_argument("source: the exemplar has " + std::to_string(in.channels()) +
                                " channels (must be 3, RGB, or 4, RGBA)");
    }
    Exemplar e;
    e.style = Image(in.width(), in.height(), 4);
    e.style.set_channel_names({"R", "G", "B", "A"});
    for (int y = 0; y < in.height(); ++y) {
        for (int x = 0; x < in.width(); ++x) {
            const float* p = in.pixel(x, y);
            const float a = in.channels() == 4 ? std::clamp(p[3], 0.0f, 1.0f) : 1.0f;
            float* o = e.style.pixel(x, y);
            for (int c = 0; c < 3; ++c) o[c] = p[c] * a;
            o[3] = a;
        }
    }

    if (!source.mask.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_exemplar_map(source.mask, in, "source mask", "1 channel"));
        e.mask = source.mask;
    } else {
        e.mask = Image(in.width(), in.height(), 1);
        for (int y = 0; y < in.height(); ++y) {
            for (int x = 0; x < in.width(); ++x) {
                e.mask.at(x, y, 0) = e.style.at(x, y, 3) > 0.0f ? 1.0f : 0.0f;
            }
        }
    }
    bool any = false;
    for (float v : e.mask.data()) {
        any = any || v > 0.5f;
        e.has_boundary = e.has_boundary || v <= 0.5f;
    }
    if (!any) return invalid_argument("source mask: empty (no pixel with alpha > 0 or mask > 0.5)");

    if (!source.labels.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(
            check_exemplar_map(source.labels, in, "source labels", "1 channel"));
        e.labels = source.labels;
        for (std::size_t i = 0; i < e.labels.pixel_count(); ++i) {
            float& v = e.labels.data()[i];
            if (!std::isfinite(v)) return invalid_argument("source labels: NaN or infinity");
            v = std::round(v);
            if (e.mask.data()[i] > 0.5f) e.segments.insert(std::lround(v));
        }
    }

    if (!source.directions.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(
            check_exemplar_map(source.directions, in, "source directions", "1 channel of angles"));
        e.angles = source.directions;
    } else {
        auto field = analyze_directions(in, {}, threads);
        if (!field.ok()) return field.status();
        e.angles = direction_angles(*field);
    }
    return e;
}

// Binary mask grown by `radius` pixels (square structuring element).
Image grow(const Image& mask, int radius) {
    const int w = mask.width(), h = mask.height();
    Image rows(w, h, 1), out(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            bool on = false;
            for (int u = std::max(x - radius, 0); u <= std::min(x + radius, w - 1) && !on; ++u) {
                on = mask.at(u, y, 0) > 0.5f;
            }
            rows.at(x, y, 0) = on ? 1.0f : 0.0f;
        }
    }
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            bool on = false;
            for (int v = std::max(y - radius, 0); v <= std::min(y + radius, h - 1) && !on; ++v) {
                on = rows.at(x, v, 0) > 0.5f;
            }
            out.at(x, y, 0) = on ? 1.0f : 0.0f;
        }
    }
    return out;
}

// Every pixel outside the painted region takes the label of the nearest painted pixel (4-connected
// breadth-first, in raster order, so ties are deterministic).
Image spread_labels(const Image& labels, const Image& coverage) {
    const int w = labels.width(), h = labels.height();
    Image out = labels;
    std::vector<char> done(static_cast<std::size_t>(w) * h, 0);
    std::deque<int> queue;
    for (int i = 0; i < w * h; ++i) {
        if (coverage.data()[static_cast<std::size_t>(i)] > 0.5f) {
            done[static_cast<std::size_t>(i)] = 1;
            queue.push_back(i);
        }
    }
    while (!queue.empty()) {
        const int i = queue.front();
        queue.pop_front();
        const int x = i % w, y = i / w;
        const int next[4] = {x > 0 ? i - 1 : -1, x + 1 < w ? i + 1 : -1, y > 0 ? i - w : -1,
                             y + 1 < h ? i + w : -1};
        for (int n : next) {
            if (n < 0 || done[static_cast<std::size_t>(n)]) continue;
            done[static_cast<std::size_t>(n)] = 1;
            out.data()[static_cast<std::size_t>(n)] = out.data()[static_cast<std::size_t>(i)];
            queue.push_back(n);
        }
    }
    return out;
}

// Every painted label must name a segment of the exemplar (inside its shape); without a
// segmentation, every label must be 0.
Status check_painted_labels(const Exemplar& exemplar, const CanvasView& canvas) {
    std::set<long> painted;
    for (std::size_t i = 0; i < canvas.labels().pixel_count(); ++i) {
        if (canvas.coverage().data()[i] > 0.5f)
            painted.insert(std::lround(canvas.labels().data()[i]));
    }
    for (long label : painted) {
        if (exemplar.labels.empty() && label != 0) {
            return invalid_argument("labels: label " + std::to_string(label) +
                                    " is painted but the source has no labels");
        }
        if (!exemplar.labels.empty() && exemplar.segments.count(label) == 0) {
            return invalid_argument("labels: label " + std::to_string(label) +
                                    " is painted but the source labels have no such segment "
                                    "inside the exemplar's shape");
        }
    }
    return Status::ok();
}

// A premultiplied RGBA pixel to straight alpha (`out` may be `in`); transparent (all 0) where
// the canvas is not `painted` or alpha is 0.
void straighten(const float* in, bool painted, float* out) {
    const float a = std::clamp(in[3], 0.0f, 1.0f);
    if (!painted || a <= 0.0f) {
        out[0] = out[1] = out[2] = out[3] = 0.0f;
        return;
    }
    for (int c = 0; c < 3; ++c) out[c] = std::clamp(in[c] / a, 0.0f, 1.0f);
    out[3] = a;
}

Image premultiplied(const Image& rgba) {
    Image out = rgba;
    for (int y = 0; y < out.height(); ++y) {
        for (int x = 0; x < out.width(); ++x) {
            float* p = out.pixel(x, y);
            for (int c = 0; c < 3; ++c) p[c] *= p[3];
        }
    }
    return out;
}

// The pixels a repaint of `changed` synthesizes (and its preview redraws): the rectangle grown
// by a patch, clipped to the w x h canvas.
PixelRect repainted_area(const PixelRect& changed, int patch_size, int w, int h) {
    return {std::max(changed.x0 - patch_size, 0), std::max(changed.y0 - patch_size, 0),
            std::min(changed.x1 + patch_size, w), std::min(changed.y1 + patch_size, h)};
}

Status check_previous(const Image* previous, int w, int h) {
    if (previous != nullptr &&
        (previous->width() != w || previous->height() != h || previous->channels() != 4)) {
        return invalid_argument("previous: " + size_of(*previous) + " with " +
                                std::to_string(previous->channels()) +
                                " channels (must be RGBA, the canvas' size)");
    }
    return Status::ok();
}

Result<PaintResult> run(const PaintSource& source, const CanvasView& canvas,
                        const PaintOptions& options, const RunContext& context,
                        const Image* previous, const PixelRect* changed) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    auto exemplar = prepare(source, context.threads);
    if (!exemplar.ok()) return exemplar.status();
    EXEMPLAR_RETURN_IF_ERROR(check_painted_labels(*exemplar, canvas));
    const int w = canvas.width(), h = canvas.height();
    EXEMPLAR_RETURN_IF_ERROR(check_previous(previous, w, h));

    // The region to synthesize: the painted pixels (within the changed rectangle on a repaint).
    // An exemplar without a boundary (opaque, or a mask covering it) has no boundary effects to
    // transfer, and transparent surroundings would pull the region's rim towards its darkest
    // patches (the closest to premultiplied transparent black, at every pyramid level), so the
    // whole canvas (on a repaint, the whole changed rectangle) is synthesized and cut to the
    // strokes after.
    Image region = exemplar->has_boundary ? canvas.coverage() : Image(w, h, 1, 1.0f);
    if (changed != nullptr) {
        const PixelRect area = repainted_area(*changed, options.patch_size, w, h);
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const bool near = x >= area.x0 && x < area.x1 && y >= area.y0 && y < area.y1;
                if (!near) region.at(x, y, 0) = 0.0f;
            }
        }
    }
    bool any = false;
    for (float v : region.data()) any = any || v > 0.5f;
    PaintResult result;
    if (!any) {
        result.image = previous != nullptr ? *previous : Image(w, h, 4);
        return result;
    }

    // The engine's input: premultiplied RGBA with alpha weighted, orientations, masks.
    SynthesisInput in;
    in.style = std::move(exemplar->style);
    in.style_channel_weights = {1.0f, 1.0f, 1.0f, options.alpha_weight};
    in.target_width = w;
    in.target_height = h;
    in.source_mask = grow(exemplar->mask, options.patch_size / 2);
    in.target_mask = std::move(region);
    in.initial_target = previous != nullptr ? premultiplied(*previous) : Image(w, h, 4);
    in.source_orientation = std::move(exemplar->angles);
    in.target_orientation = direction_angles(canvas.directions());
    // Rotations rounded to 32 steps (11.25°, a patch corner off by at most 0.28 px): every
    // level precomputes the 32 rotated patch layouts, as the paper's pre-rotated exemplars
    // (LazyFluids §5.4.5 and Brushables pre-rotate too), instead of a cosine, a sine and 25
    // rounded offsets per patch distance. A fifth less time; the tested quality holds
    // (docs/PERFORMANCE.md "Brushables painting").
    in.orientation_steps = kOrientationSteps;
    // Rotated pairs compare the plain exemplar patch with the target patch turned back, gathered
    // once per target pixel and step for all of its candidates: 12% less time, the tested
    // quality holds or improves (docs/paint.md "Synthesis", docs/PERFORMANCE.md). Not with
    // patch-usage control: uniform usage then over-represents sparse details (the yellow flecks
    // of Paint.UniformUsageKeepsSparseFlecksThatPlainEmWashesOut: 0.12-0.17 of the painted
    // pixels against the exemplar's 0.10), so it keeps the exemplar patches turned.
    in.rotate_target_patches = options.usage == UsageStrategy::None;
    if (!exemplar->labels.empty()) {
        in.source_labels = exemplar->labels;
        // Outside the strokes the nearest stroke's segment: the engine matches every pixel
        // within a patch radius of the region (and an opaque exemplar's whole canvas), and drops
        // the labels on a level where one of them has no source patch.
        in.target_labels = spread_labels(canvas.labels(), canvas.coverage());
    }

    // The Shape Hint: edges of the shape and between segments (an opaque exemplar's whole canvas
    // has no shape edge, only segment boundaries, if it is segmented at all).
    const bool segmented = exemplar->segments.size() > 1;
    if (options.shape_weight > 0.0f && (exemplar->has_boundary || segmented)) {
        const ShapeHintOptions hint{options.edge_extent_px, options.shape_bins};
        const float area = static_cast<float>(options.patch_size * options.patch_size);
        const Image target_shape =
            exemplar->has_boundary ? canvas.coverage() : Image(w, h, 1, 1.0f);
        in.guides.push_back({"shape hint",
                             shape_hint(shape_edges(exemplar->mask, exemplar->labels),
                                        in.source_orientation, hint, context.threads),
                             shape_hint(shape_edges(target_shape, in.target_labels),
                                        in.target_orientation, hint, context.threads),
                             options.shape_weight / area,
                             {}});
    }

    SynthesisOptions so;
    so.patch_size = options.patch_size;
    so.seed = options.seed;
    so.vote_coherence = options.vote_coherence;
    so.vote_histogram = options.vote_histogram;
    so.usage = options.usage;  // default None: Wexler et al.'s EM, as in the paper
    // Two PatchMatch iterations for a level's first search (the engine's default is 6, for a
    // cold start): every level but the coarsest starts from the upsampled field of the level
    // before, and the coarsest runs 6 EM iterations. A third of the time; the tested quality
    // holds (docs/PERFORMANCE.md "Brushables painting").
    so.search_iterations = 2;
    // Random-search windows of at most 8 px on the finest level (the `fast` preset's cap): it
    // starts from the upsampled field of the level before, whose wide windows rarely win but
    // miss the caches. 7% less time; the coherent regions grow, the patch error rises 2%
    // (docs/PERFORMANCE.md "Brushables painting").
    so.finest_search_radius = 8;
    auto synthesized = synthesize(std::move(in), so, context);
    if (!synthesized.ok()) return synthesized.status();

    // Back to straight alpha; nothing outside the painted region.
    result.image = std::move(synthesized->image);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            float* p = result.image.pixel(x, y);
            straighten(p, canvas.coverage().at(x, y, 0) != 0.0f, p);
        }
    }
    result.image.set_channel_names({"R", "G", "B", "A"});
    result.nnf = std::move(synthesized->nnf);
    return result;
}

}  // namespace

Status validate(const PaintOptions& o) {
    if (!(o.shape_weight >= 0.0f && o.shape_weight <= 1000.0f)) {
        return invalid_argument("shape-weight: " + std::to_string(o.shape_weight) +
                                " is invalid (must be 0..1000)");
    }
    EXEMPLAR_RETURN_IF_ERROR(validate(ShapeHintOptions{o.edge_extent_px, o.shape_bins}));
    if (!(o.alpha_weight >= 0.0f && o.alpha_weight <= 100.0f)) {
        return invalid_argument("alpha-weight: " + std::to_string(o.alpha_weight) +
                                " is invalid (must be 0..100)");
    }
    if (!(o.vote_coherence >= 0.0f && o.vote_coherence <= 100.0f)) {
        return invalid_argument("vote-coherence: " + std::to_string(o.vote_coherence) +
                                " is invalid (must be 0..100 px^2)");
    }
    if (!(o.vote_histogram >= 0.0f && o.vote_histogram <= 100.0f)) {
        return invalid_argument("vote-histogram: " + std::to_string(o.vote_histogram) +
                                " is invalid (must be 0..100)");
    }
    if (o.patch_size < 3 || o.patch_size > 15 || o.patch_size % 2 == 0) {
        return invalid_argument("patch-size: " + std::to_string(o.patch_size) +
                                " is invalid (must be odd, 3..15)");
    }
    return Status::ok();
}

Result<PaintResult> paint(const PaintSource& source, const PaintCanvas& canvas,
                          const PaintOptions& options, const RunContext& context) {
    return run(source, CanvasView(canvas), options, context, nullptr, nullptr);
}

Result<PaintResult> repaint(const PaintSource& source, const PaintCanvas& canvas,
                            const Image& previous, const PixelRect& changed,
                            const PaintOptions& options, const RunContext& context) {
    return run(source, CanvasView(canvas), options, context, &previous, &changed);
}

Result<PaintResult> preview_repaint(const PaintSource& source, const PaintCanvas& canvas,
                                    const Image& previous, const PixelRect& changed,
                                    const PaintOptions& options, int reduction,
                                    const RunContext& context) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (reduction < 1 || reduction > 16) {
        return invalid_argument("reduction: " + std::to_string(reduction) +
                                " is invalid (must be 1..16)");
    }
    const int w = canvas.width(), h = canvas.height();
    EXEMPLAR_RETURN_IF_ERROR(check_previous(&previous, w, h));
    if (source.image.empty()) return invalid_argument("source: the exemplar is empty");
    // The reduced exemplar keeps at least 3 patches across its shorter side (the engine's
    // coarsest level needs room); a factor that leaves less is lowered, down to the full repaint.
    const int shorter = std::min(source.image.width(), source.image.height());
    int r = reduction;
    while (r > 1 && shorter / r < 3 * options.patch_size) --r;
    if (r == 1) return repaint(source, canvas, previous, changed, options, context);

    const int t = context.threads;
    const auto reduced = [r](int size) { return std::max(1, (size + r - 1) / r); };
    const auto shrink = [&](const Image& image, ResampleFilter filter) {
        if (image.empty()) return Image();
        const bool canvas_sized = image.width() == w && image.height() == h;
        const int sw = canvas_sized ? reduced(w) : reduced(image.width());
        const int sh = canvas_sized ? reduced(h) : reduced(image.height());
        return resize(image, sw, sh, filter, t);
    };

    // The exemplar at 1/r: what the engine's coarse pyramid levels see of it.
    PaintSource small;
    small.image = shrink(source.image, ResampleFilter::Box);
    small.mask = shrink(source.mask, ResampleFilter::Box);
    small.labels = shrink(source.labels, ResampleFilter::Nearest);
    if (!source.directions.empty()) {
        if (!source.directions.same_size(source.image) || source.directions.channels() != 1) {
            return repaint(source, canvas, previous, changed, options, context);  // its error
        }
        small.directions = direction_angles(
            shrink(directions_from_angles(source.directions), ResampleFilter::Box));
    }
    // The canvas at 1/r: a pixel is painted where at least half of it was.
    Image coverage = shrink(canvas.coverage(), ResampleFilter::Box);
    for (float& v : coverage.data()) v = v >= 0.5f ? 1.0f : 0.0f;
    const Image directions = shrink(canvas.directions(), ResampleFilter::Box);
    const Image labels = shrink(canvas.labels(), ResampleFilter::Nearest);
    const Image small_previous = shrink(premultiplied(previous), ResampleFilter::Box);
    Image straight_previous = small_previous;
    for (std::size_t i = 0; i < straight_previous.pixel_count(); ++i) {
        float* p = straight_previous.data().data() + 4 * i;
        straighten(p, true, p);
    }
    PaintOptions small_options = options;
    small_options.edge_extent_px = std::max(1.0f, options.edge_extent_px / static_cast<float>(r));
    const PixelRect small_changed{changed.x0 / r, changed.y0 / r, (changed.x1 + r - 1) / r,
                                  (changed.y1 + r - 1) / r};
    auto coarse = run(small, CanvasView(coverage, directions, labels), small_options, context,
                      &straight_previous, &small_changed);
    if (!coarse.ok()) return coarse.status();

    // Up to the canvas' size (premultiplied, so the transparent outside does not darken the
    // rim), into the pixels a repaint would synthesize; the others keep `previous`.
    const Image up = resize(premultiplied(coarse->image), w, h, ResampleFilter::Gaussian, t);
    PaintResult result;
    result.image = previous;
    result.image.set_channel_names({"R", "G", "B", "A"});
    const PixelRect area = repainted_area(changed, options.patch_size, w, h);
    for (int y = area.y0; y < area.y1; ++y) {
        for (int x = area.x0; x < area.x1; ++x) {
            straighten(up.pixel(x, y), canvas.coverage().at(x, y, 0) != 0.0f,
                       result.image.pixel(x, y));
        }
    }
    result.nnf = std::move(coarse->nnf);
    return result;
}

Image composite_over(const Image& painting, const Image& background) {
    Image out(painting.width(), painting.height(), 4);
    out.set_channel_names({"R", "G", "B", "A"});
    for (int y = 0; y < painting.height(); ++y) {
        for (int x = 0; x < painting.width(); ++x) {
            const float* f = painting.pixel(x, y);
            const float* b = background.pixel(x, y);
            const float fa = f[3];
            const float ba = background.channels() == 4 ? b[3] : 1.0f;
            const float a = fa + ba * (1.0f - fa);
            float* o = out.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                o[c] = a > 0.0f ? (f[c] * fa + b[c] * ba * (1.0f - fa)) / a : 0.0f;
            }
            o[3] = a;
        }
    }
    return out;
}

}  // namespace exemplar::paint
