// Painting by Feature (Lukáč et al. 2013, thesis §3.3.1): the brush's options, and a stroke
// painted with a line feature. The target path is sampled at equal intervals, each sample takes
// the walk's source sample, and every pixel within the brush width takes the nearest target
// sample (its Voronoi cell) and the same relative position in that source sample's frame
// (Fig. 3.5). Around a jump of the walk the base layers of both sides' continuations are
// blended and the pixel's own detail is kept (Durand and Dorsey 2002's base/detail split).
//
// Growing a stroke redraws only what can change: the pixels whose nearest sample is not yet
// settled, i.e. whose tangent window or blend window reaches past the stroke's end.

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <string>
#include <utility>

#include "exemplar/core/check.hpp"
#include "exemplar/core/option_table.hpp"
#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"
#include "exemplar/paint/paint.hpp"
#include "feature_internal.hpp"

namespace exemplar::paint {

namespace {

using O = FeatureBrushOptions;

const std::array<FeatureBrushOptionSpec, 11> kSpecs{{
    {"sample-spacing",
     "Distance between consecutive samples of the feature's and the target's paths, in source "
     "pixels (ours).",
     "px", 0.5, 64, &O::sample_spacing_px},
    {"blend-radius",
     "Half-length along the path of the base-layer blend across each jump of the walk, in "
     "target pixels; 0 = no blending (ours).",
     "px", 0, 256, &O::blend_radius_px},
    {"base-sigma",
     "Spatial sigma of the bilateral filter that makes the base layer (ours; Durand and Dorsey: "
     "2% of the image).",
     "px", 0.5, 64, &O::base_sigma_px},
    {"base-range-sigma",
     "Range sigma of the bilateral filter, on colour distance with values in [0, 1] (ours).", "",
     0.01, 10, &O::base_range_sigma},
    {"min-jump",
     "Shortest jump of the walk along the source, in source pixels: no stutter of repeated or "
     "skipped samples (ours).",
     "px", 0, 1000, &O::min_jump_px},
    {"snap-elasticity", "Active contour: weight of the continuity term (Williams and Shah: 1).", "",
     0, 100, &O::snap_elasticity},
    {"snap-rigidity", "Active contour: weight of the curvature term (Williams and Shah: 1).", "", 0,
     100, &O::snap_rigidity},
    {"snap-edge-weight", "Active contour: weight of the edge term (Williams and Shah: 1.2).", "", 0,
     100, &O::snap_edge_weight},
    {"snap-sigma",
     "Active contour: blur before the gradient; the rough path may be about 3 sigma off the "
     "edge (ours).",
     "px", 0, 32, &O::snap_sigma_px},
    {"snap-spacing", "Active contour: spacing of its points (ours).", "px", 1, 64,
     &O::snap_spacing_px},
    {"snap-iterations",
     "Active contour: most greedy iterations; stops when under 1% of the points move (ours).",
     "iterations", 0, 10000, &O::snap_iterations},
}};

void include(PixelRect& rect, const PixelRect& other) {
    if (other.empty()) return;
    if (rect.empty()) {
        rect = other;
        return;
    }
    rect = {std::min(rect.x0, other.x0), std::min(rect.y0, other.y0), std::max(rect.x1, other.x1),
            std::max(rect.y1, other.y1)};
}

float smoothstep(float x) {
    x = std::clamp(x, 0.0f, 1.0f);
    return x * x * (3.0f - 2.0f * x);
}

}  // namespace

std::string_view to_string(WalkMode mode) {
    switch (mode) {
        case WalkMode::Randomized: return "randomized";
        case WalkMode::Looping: return "looping";
        case WalkMode::DynamicProgramming: return "dp";
    }
    return "randomized";
}

Result<WalkMode> parse_walk_mode(std::string_view name) {
    for (WalkMode mode : {WalkMode::Randomized, WalkMode::Looping, WalkMode::DynamicProgramming}) {
        if (name == to_string(mode)) return mode;
    }
    return invalid_argument("walk: '" + std::string(name) +
                            "' is invalid (must be one of randomized, looping, dp)");
}

std::span<const FeatureBrushOptionSpec> feature_brush_option_specs() {
    return kSpecs;
}

double get_option(const FeatureBrushOptions& options, const FeatureBrushOptionSpec& spec) {
    return get_table_option(options, spec);
}

Status set_option(FeatureBrushOptions& options, const FeatureBrushOptionSpec& spec, double value) {
    return set_table_option(options, spec, value);
}

Status validate(const FeatureBrushOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(
        validate_table_options(options, std::span<const FeatureBrushOptionSpec>(kSpecs)));
    return parse_walk_mode(to_string(options.walk)).status();
}

BrushStroke::BrushStroke(const LineFeature& feature, int canvas_width, int canvas_height,
                         float width_px, std::uint64_t path_index, int threads)
    : feature_(&feature),
      width_px_(width_px),
      scale_(width_px / feature.width_px()),
      spacing_(feature.options().sample_spacing_px * width_px / feature.width_px()),
      key_(hash_keys(feature.options().seed, path_index)),
      threads_(threads),
      layer_(canvas_width, canvas_height, 4),
      owner_(static_cast<std::size_t>(canvas_width) * canvas_height, -1),
      dist2_(static_cast<std::size_t>(canvas_width) * canvas_height, 0.0f),
      sampler_(std::make_unique<PathSampler>(spacing_)),
      walker_(std::make_unique<WalkBuilder>(feature, feature.options().walk, key_)) {
    EXEMPLAR_CHECK(width_px > 0.0f && std::isfinite(width_px));
}

BrushStroke::BrushStroke(BrushStroke&&) noexcept = default;
BrushStroke& BrushStroke::operator=(BrushStroke&&) noexcept = default;
BrushStroke::~BrushStroke() = default;

int BrushStroke::settled_samples() const {
    const int n = samples();
    if (feature_->options().walk == WalkMode::DynamicProgramming || n < 2) return 0;
    const int reach = tangent_reach(width_px_, spacing_);
    const int blend = static_cast<int>(std::ceil(feature_->options().blend_radius_px / spacing_));
    return std::max(0, n - 2 - std::max(reach, blend + 1));
}

int BrushStroke::nearest_sample(int x, int y) const {
    if (x < 0 || y < 0 || x >= layer_.width() || y >= layer_.height()) return -1;
    return owner_[static_cast<std::size_t>(y) * layer_.width() + x];
}

Result<PixelRect> BrushStroke::add_points(std::span<const StrokePoint> points,
                                          const CancelToken* cancel) {
    for (StrokePoint p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
            return invalid_argument("path: a point is not finite");
    }
    const auto stopped = [cancel] { return cancel != nullptr && cancel->cancelled(); };
    if (stopped()) return cancelled();
    const int first_dirty = settled_samples();
    const int before = samples();
    for (StrokePoint p : points) sampler_->add(p, targets_);
    const int n = samples();
    if (n < 2 || n == before) return PixelRect{};

    // Frames whose tangent window reached the old end, and the walk.
    const int reach = tangent_reach(width_px_, spacing_);
    update_frames(targets_, reach, before - reach - 1, frames_);
    walker_->extend(walk_, n);

    // The new samples' Voronoi cells, within the brush's reach: a pixel goes to the nearest
    // sample, the earlier one on a tie (so the cells do not depend on the order of drawing).
    const int w = layer_.width(), h = layer_.height();
    const float radius = 0.5f * width_px_ + 1.0f;
    auto disc = [&](int k) {
        const PathSample& s = frames_[static_cast<std::size_t>(k)];
        return PixelRect{std::max(0, static_cast<int>(std::floor(s.x - radius))),
                         std::max(0, static_cast<int>(std::floor(s.y - radius))),
                         std::min(w, static_cast<int>(std::ceil(s.x + radius)) + 1),
                         std::min(h, static_cast<int>(std::ceil(s.y + radius)) + 1)};
    };
    PixelRect changed;
    for (int k = rasterized_; k < n; ++k) {
        if (stopped()) return cancelled();
        const PathSample& s = frames_[static_cast<std::size_t>(k)];
        const PixelRect r = disc(k);
        for (int y = r.y0; y < r.y1; ++y) {
            for (int x = r.x0; x < r.x1; ++x) {
                const float dx = static_cast<float>(x) + 0.5f - s.x;
                const float dy = static_cast<float>(y) + 0.5f - s.y;
                const float d2 = dx * dx + dy * dy;
                const std::size_t i = static_cast<std::size_t>(y) * w + x;
                if (d2 > radius * radius || (owner_[i] >= 0 && !(d2 < dist2_[i]))) continue;
                if (owner_[i] >= 0 && owner_[i] < first_dirty)
                    include(changed, {x, y, x + 1, y + 1});
                owner_[i] = k;
                dist2_[i] = d2;
            }
        }
    }
    rasterized_ = n;
    for (int k = first_dirty; k < n; ++k) include(changed, disc(k));
    if (!shade(changed, first_dirty, cancel)) return cancelled();
    return changed;
}

bool BrushStroke::shade(const PixelRect& rect, int first_dirty, const CancelToken* cancel) {
    const LineFeature& f = *feature_;
    const int n = samples();
    const int source_n = f.size();
    const int channels = f.channels();
    const int colours = channels == 4 ? 3 : channels;
    const float half_width = 0.5f * width_px_;
    const float blend = f.options().blend_radius_px / spacing_;  // in samples
    const int blend_reach = static_cast<int>(std::ceil(blend)) + 1;
    const float source_spacing = f.options().sample_spacing_px;
    const std::span<const PathSample> sources = f.samples();
    const int w = layer_.width();

    // Where position (u, v) of target sample frame maps in the source sample `a`'s frame; `a`
    // beyond the source's ends continues its end straight on (the blend's extrapolation).
    auto source_point = [&](int a, float u, float v, float& x, float& y) {
        const int clamped = std::clamp(a, 0, source_n - 1);
        const PathSample& s = sources[static_cast<std::size_t>(clamped)];
        const float along = static_cast<float>(a - clamped) * source_spacing + u / scale_;
        const float across = v / scale_;
        x = s.x + along * s.tx - across * s.ty;
        y = s.y + along * s.ty + across * s.tx;
    };
    auto jump_at = [&](int b) {
        return walk_[static_cast<std::size_t>(b)] != walk_[static_cast<std::size_t>(b - 1)] + 1;
    };

    std::atomic<bool> stopped{false};
    parallel_for(rect.y0, rect.y1, threads_, [&](int y) {
        if (cancel != nullptr && cancel->cancelled()) stopped = true;
        if (stopped) return;
        std::array<float, 4> colour{}, base{}, base_a{}, base_b{};
        for (int x = rect.x0; x < rect.x1; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            const int k = owner_[i];
            if (k < first_dirty) continue;
            float* out = layer_.pixel(x, y);
            const PathSample& t = frames_[static_cast<std::size_t>(k)];
            const float dx = static_cast<float>(x) + 0.5f - t.x;
            const float dy = static_cast<float>(y) + 0.5f - t.y;
            const float u = dx * t.tx + dy * t.ty;
            const float v = -dx * t.ty + dy * t.tx;
            // Coverage: the brush width, anti-aliased, with flat caps at the ends.
            float alpha = std::clamp(half_width + 0.5f - std::abs(v), 0.0f, 1.0f);
            if (k == 0) alpha *= std::clamp(0.5f * spacing_ + 0.5f + u, 0.0f, 1.0f);
            if (k == n - 1) alpha *= std::clamp(0.5f * spacing_ + 0.5f - u, 0.0f, 1.0f);
            if (alpha <= 0.0f) {
                std::fill(out, out + 4, 0.0f);
                continue;
            }
            const int j = walk_[static_cast<std::size_t>(k)];
            float sx = 0.0f, sy = 0.0f;
            source_point(j, u, v, sx, sy);
            f.colour(sx, sy, colour.data());

            // Blending across the nearest jump within the blend radius: base layers of the
            // runs on both sides, each continued to this pixel, mixed by a smoothstep.
            if (blend > 0.0f) {
                const float position = static_cast<float>(k) + u / spacing_;
                int jump = -1;
                float offset = 0.0f;
                for (int b = std::max(1, k - blend_reach); b <= std::min(n - 1, k + blend_reach);
                     ++b) {
                    if (!jump_at(b)) continue;
                    const float d = position - (static_cast<float>(b) - 0.5f);
                    if (std::abs(d) < blend && (jump < 0 || std::abs(d) < std::abs(offset))) {
                        jump = b;
                        offset = d;
                    }
                }
                if (jump > 0) {
                    float ax = 0.0f, ay = 0.0f, bx = 0.0f, by = 0.0f;
                    source_point(walk_[static_cast<std::size_t>(jump - 1)] + (k - (jump - 1)), u, v,
                                 ax, ay);
                    source_point(walk_[static_cast<std::size_t>(jump)] + (k - jump), u, v, bx, by);
                    f.base(sx, sy, base.data());
                    f.base(ax, ay, base_a.data());
                    f.base(bx, by, base_b.data());
                    const float weight = smoothstep((offset + blend) / (2.0f * blend));
                    for (int c = 0; c < colours; ++c) {
                        colour[static_cast<std::size_t>(c)] +=
                            base_a[static_cast<std::size_t>(c)] +
                            weight * (base_b[static_cast<std::size_t>(c)] -
                                      base_a[static_cast<std::size_t>(c)]) -
                            base[static_cast<std::size_t>(c)];
                    }
                }
            }
            for (int c = 0; c < 3; ++c) {
                out[c] =
                    std::clamp(colour[static_cast<std::size_t>(colours == 1 ? 0 : c)], 0.0f, 1.0f);
            }
            out[3] = channels == 4 ? alpha * std::clamp(colour[3], 0.0f, 1.0f) : alpha;
        }
    });
    return !stopped;
}

Result<LineFeature> pick_line_feature(const Image& palette, Stroke rough,
                                      const FeatureBrushOptions& options, bool snap, int threads) {
    if (snap) {
        auto snapped = snap_to_edges(palette, rough.points, options);
        if (!snapped.ok()) return snapped.status();
        rough.points = std::move(snapped).value();
    }
    return LineFeature::create(palette, rough, options, threads);
}

Result<Image> paint_feature(const LineFeature& feature, std::span<const Stroke> paths, int width,
                            int height, float brush_width_px, int threads) {
    if (paths.empty()) return invalid_argument("paths: none given (must be at least one)");
    if (!(brush_width_px >= 0.0f && brush_width_px <= 4096.0f)) {
        return invalid_argument("brush width: " + std::to_string(brush_width_px) +
                                " is invalid (must be > 0 and at most 4096, or 0 for the paths' "
                                "widths)");
    }
    Image out(width, height, 4);
    for (std::size_t p = 0; p < paths.size(); ++p) {
        const float stroke_width = brush_width_px > 0.0f ? brush_width_px : paths[p].width_px;
        if (Status s = validate(Stroke{paths[p].points, stroke_width, false}); !s.is_ok()) {
            return invalid_argument("path " + std::to_string(p) + ": " + s.message());
        }
        BrushStroke stroke(feature, width, height, stroke_width, p, threads);
        auto changed = stroke.add_points(paths[p].points);
        if (!changed.ok()) return changed.status();
        out = composite_over(stroke.layer(), out);
    }
    return out;
}

}  // namespace exemplar::paint
