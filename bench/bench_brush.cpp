// Interactive latency of the line-feature brush (Painting by Feature, docs/feature.md; the
// issue's budget: a 1000 px stroke within 16 ms, one frame at 60 Hz, with 2 threads).
// The palette is synthetic (a 400x64 dark band of random thickness on a grainy ground, as in
// tests/paint/feature_brush_test.cpp), or the image given with its feature as "x0,y0,x1,y1,w".
// Timed: snapping a rough path onto the feature (active contour, one thread), the feature's
// preparation (once per selection: samples, patches, graph, base layer),
// a 1000 px wave-shaped stroke drawn at once (best of the repeats), and the same stroke grown
// 4 px at a time as a front end would (quantiles over every addition of every repeat; on a
// loaded machine the maximum is a preemption by the scheduler, not the brush).
// Usage: bench_brush [threads] [repeats] [palette.png x0,y0,x1,y1,width]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "exemplar/core/rng.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/feature_brush.hpp"

using namespace exemplar;
using namespace exemplar::paint;

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

float grain(int x, int y) {
    return static_cast<float>(
               hash_keys(7, static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y)) >> 40) /
           16777216.0f;
}

Image band_palette() {
    Image image(400, 64, 3);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 400; ++x) {
            const float half = 3.0f + 6.0f * grain(x / 24, 1000) + 3.0f * grain(x / 7, 2000);
            const float inside = std::clamp(
                half + 0.5f - std::abs(static_cast<float>(y) + 0.5f - 32.0f), 0.0f, 1.0f);
            const float v = 0.85f + 0.15f * (grain(x, y) - 0.5f) - 0.6f * inside;
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = v;
        }
    }
    return image;
}

}  // namespace

int main(int argc, char** argv) {
    const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
    const int repeats = argc > 2 ? std::atoi(argv[2]) : 20;
    Image palette = band_palette();
    Stroke selection{{{8.0f, 32.0f}, {392.0f, 32.0f}}, 32.0f, false};
    if (argc > 4) {
        auto loaded = load_image(argv[3]);
        if (!loaded.ok()) {
            std::fprintf(stderr, "%s\n", loaded.status().message().c_str());
            return 1;
        }
        palette = std::move(loaded).value();
        float x0 = 0, y0 = 0, x1 = 0, y1 = 0, w = 0;
        if (std::sscanf(argv[4], "%f,%f,%f,%f,%f", &x0, &y0, &x1, &y1, &w) != 5) return 1;
        selection = Stroke{{{x0, y0}, {x1, y1}}, w, false};
    }

    // 1000 px of arc length: a wave across a 900x200 canvas.
    std::vector<StrokePoint> path;
    double length = 0.0;
    for (float x = 20.0f; length < 1000.0; x += 1.0f) {
        const StrokePoint p{x, 100.0f + 40.0f * std::sin(x / 60.0f)};
        if (!path.empty()) length += std::hypot(p.x - path.back().x, p.y - path.back().y);
        path.push_back(p);
    }
    const int canvas_w = static_cast<int>(path.back().x) + 40, canvas_h = 200;

    // The selection: a rough path 3 px off the feature, snapped (best of the repeats).
    std::vector<StrokePoint> rough;
    for (int i = 0; i <= 8; ++i) {
        const float t = static_cast<float>(i) / 8.0f;
        rough.push_back(
            {selection.points[0].x + t * (selection.points[1].x - selection.points[0].x),
             selection.points[0].y + t * (selection.points[1].y - selection.points[0].y) +
                 (i % 2 == 0 ? 3.0f : -3.0f)});
    }
    double snap = 1e9;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        auto snapped = snap_to_edges(palette, rough);
        snap = std::min(snap, ms_since(t0));
        if (!snapped.ok()) return 1;
    }

    double prepare = 1e9, at_once = 1e9;
    std::vector<double> adds;  // every addition of every repeat
    int samples = 0, nodes = 0;
    for (int r = 0; r < repeats; ++r) {
        auto t0 = std::chrono::steady_clock::now();
        auto feature = LineFeature::create(palette, selection, {}, threads);
        prepare = std::min(prepare, ms_since(t0));
        if (!feature.ok()) {
            std::fprintf(stderr, "%s\n", feature.status().message().c_str());
            return 1;
        }
        nodes = feature->size();

        BrushStroke whole(*feature, canvas_w, canvas_h, selection.width_px, 0, threads);
        t0 = std::chrono::steady_clock::now();
        if (!whole.add_points(path).ok()) return 1;
        at_once = std::min(at_once, ms_since(t0));
        samples = whole.samples();

        BrushStroke grown(*feature, canvas_w, canvas_h, selection.width_px, 0, threads);
        for (std::size_t i = 0; i < path.size(); i += 4) {
            const std::size_t end = std::min(path.size(), i + 4);
            t0 = std::chrono::steady_clock::now();
            if (!grown.add_points({path.data() + i, end - i}).ok()) return 1;
            adds.push_back(ms_since(t0));
        }
    }
    std::sort(adds.begin(), adds.end());
    const auto quantile = [&](double q) {
        return adds[std::min(adds.size() - 1, static_cast<std::size_t>(q * adds.size()))];
    };
    std::printf(
        "threads %d, best of %d: rough path snapped in %.1f ms, feature of %d samples "
        "prepared in %.1f ms\n",
        threads, repeats, snap, nodes, prepare);
    std::printf("1000 px stroke (%d samples, width %.0f px) drawn at once: %.2f ms\n", samples,
                static_cast<double>(selection.width_px), at_once);
    std::printf("grown 4 px at a time (%zu additions): median %.3f ms, 99%% %.3f ms, max %.2f ms\n",
                adds.size(), quantile(0.5), quantile(0.99), adds.back());
    return 0;
}
