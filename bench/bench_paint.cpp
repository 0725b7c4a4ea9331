// Brushables painting time (docs/paint.md, docs/PERFORMANCE.md "Brushables painting"): the
// issue's budgets are 0.5 s for a 0.25 MPix painted region (interactive) and 2 s per MPix, both
// with 2 threads (the paper reports about 5 s per MPix).
// Timed, wall and process CPU (the host is shared: compare CPU time, or A/B with
// scripts/ab_bench.sh): `PaintCanvas::add_stroke` (region and direction diffusion)
// and `paint` of one wide wavy stroke covering about 0.25 MPix; `repaint` after
// a 48 px stroke across it (what an interactive front end runs per stroke); `paint` of about
// 1 MPix (five overlapping strokes). Each case best of the repeats.
// The exemplar: an RGBA blob of stripes and grain (synthetic, the default), or a file (RGB or
// RGBA) given as the third argument; its directions are analysed once, outside the timing.
// Usage: bench_paint [threads] [repeats] [exemplar.png | -] [one | all] [PREFIX]  ("one": the
// 0.25 MPix paint alone, for profiling; PREFIX: also save the paintings as PREFIXone.png,
// PREFIXrepaint.png and PREFIXfive.png, to compare the bytes and look at them before and after
// a change)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "exemplar/core/rng.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/directions.hpp"
#include "exemplar/paint/paint.hpp"

using namespace exemplar;
using namespace exemplar::paint;

namespace {

float grain(int x, int y) {
    return static_cast<float>(
               hash_keys(11, static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y)) >> 40) /
           16777216.0f;
}

// Diagonal stripes with grain inside a soft-edged disc, transparent outside.
Image blob(int size) {
    Image im(size, size, 4);
    const float c = 0.5f * static_cast<float>(size - 1);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float stripe = 0.5f + 0.4f * std::sin(0.5f * static_cast<float>(x + 2 * y));
            const float g = 0.15f * (grain(x, y) - 0.5f);
            const float r = std::hypot(static_cast<float>(x) - c, static_cast<float>(y) - c);
            float* p = im.pixel(x, y);
            p[0] = std::clamp(0.3f + 0.5f * stripe + g, 0.0f, 1.0f);
            p[1] = std::clamp(0.5f * stripe + g, 0.0f, 1.0f);
            p[2] = std::clamp(0.2f + 0.2f * stripe + g, 0.0f, 1.0f);
            p[3] = std::clamp((0.45f * static_cast<float>(size) - r) / 3.0f, 0.0f, 1.0f);
        }
    }
    return im;
}

// A wave from x0 to x1 around height y, amplitude a.
Stroke wave(float x0, float x1, float y, float a, float width) {
    Stroke s;
    s.width_px = width;
    for (float x = x0; x <= x1; x += 4.0f) s.points.push_back({x, y + a * std::sin(x / 90.0f)});
    return s;
}

double painted_mpix(const PaintCanvas& canvas) {
    double n = 0.0;
    for (float v : canvas.coverage().data()) n += v > 0.5f ? 1.0 : 0.0;
    return n * 1e-6;
}

// Mean final patch distance over the painted pixels: how closely the painting's patches match
// the exemplar's, a proxy for quality when options change.
double mean_match_error(const PaintCanvas& canvas, const Nnf& nnf) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < canvas.height(); ++y) {
        for (int x = 0; x < canvas.width(); ++x) {
            if (canvas.coverage().at(x, y, 0) < 0.5f || nnf.at(x, y).x < 0) continue;
            sum += nnf.at(x, y).error;
            ++n;
        }
    }
    return n > 0 ? sum / n : 0.0;
}

struct Timing {
    double wall_s = 1e30, cpu_s = 1e30;
};

template <class Run>
bool time_best(int repeats, Timing& best, Run run) {
    for (int r = 0; r < repeats; ++r) {
        const double cpu0 = bench::cpu_seconds();
        const auto t0 = std::chrono::steady_clock::now();
        if (!run()) return false;
        best.wall_s =
            std::min(best.wall_s,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        best.cpu_s = std::min(best.cpu_s, bench::cpu_seconds() - cpu0);
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
    const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
    PaintSource source;
    source.image = blob(160);
    const bool only_one = argc > 4 && std::string(argv[4]) == "one";
    const std::string prefix = argc > 5 ? argv[5] : "";
    if (argc > 3 && std::string(argv[3]) != "-") {
        auto loaded = load_image(argv[3]);
        if (!loaded.ok()) {
            std::fprintf(stderr, "%s\n", loaded.status().message().c_str());
            return 1;
        }
        source.image = std::move(loaded).value();
    }
    auto field = analyze_directions(source.image, {}, threads);
    if (!field.ok()) return 1;
    source.directions = direction_angles(*field);

    const PaintOptions options;
    const RunContext context(threads);
    std::printf("bench_paint: %dx%d exemplar, %d threads, best of %d\n", source.image.width(),
                source.image.height(), threads, repeats);
    auto report = [](const char* name, double mpix, const Timing& t) {
        std::printf("%-34s %.3f MPix  wall %6.3f s  cpu %6.3f s  (%5.2f s/MPix wall, %5.2f cpu)\n",
                    name, mpix, t.wall_s, t.cpu_s, t.wall_s / mpix, t.cpu_s / mpix);
    };
    auto failed = [](const Status& status) {
        std::fprintf(stderr, "%s\n", status.message().c_str());
        return 1;
    };
    // Saves a painting as PREFIX + name + ".png" when a prefix is given.
    auto save = [&](const char* name, const Image& image) {
        return prefix.empty() ? Status::ok() : save_image(image, prefix + name + ".png");
    };
    // The best of the repeats of `run` (a paint or repaint call) and its last result.
    auto best_of = [&](Timing& timing, const auto& run) {
        Result<PaintResult> result = PaintResult{};
        time_best(repeats, timing, [&] {
            result = run();
            return result.ok();
        });
        return result;
    };

    // Interactive: one wide stroke of about 0.25 MPix, then one more stroke repainted.
    PaintCanvas quarter(1000, 500);
    Timing stroke_setup;
    if (!time_best(repeats, stroke_setup, [&] {
            quarter = PaintCanvas(1000, 500);
            return quarter.add_stroke(wave(40.0f, 960.0f, 250.0f, 80.0f, 270.0f), threads).ok();
        })) {
        return 1;
    }
    report("add_stroke (region, directions)", painted_mpix(quarter), stroke_setup);
    Timing paint_quarter;
    const auto first =
        best_of(paint_quarter, [&] { return paint::paint(source, quarter, options, context); });
    if (!first.ok()) return failed(first.status());
    report("paint, one stroke", painted_mpix(quarter), paint_quarter);
    std::printf("  (mean patch error of the painted pixels' matches: %.4f)\n",
                mean_match_error(quarter, first->nnf));
    if (const Status saved = save("one", first->image); !saved.is_ok()) return failed(saved);
    if (only_one) return 0;

    const auto changed = quarter.add_stroke(wave(100.0f, 900.0f, 300.0f, -60.0f, 48.0f));
    if (!changed.ok()) return failed(changed.status());
    Timing repaint_stroke;
    const auto second = best_of(repaint_stroke, [&] {
        return paint::repaint(source, quarter, first->image, *changed, options, context);
    });
    if (!second.ok()) return failed(second.status());
    if (const Status saved = save("repaint", second->image); !saved.is_ok()) return failed(saved);
    const double changed_mpix =
        static_cast<double>(changed->x1 - changed->x0) * (changed->y1 - changed->y0) * 1e-6;
    report("repaint, a 48 px stroke (its box)", changed_mpix, repaint_stroke);

    // About 1 MPix: five overlapping waves on 1400x900.
    PaintCanvas mega(1400, 900);
    for (int k = 0; k < 5; ++k) {
        const float y = 110.0f + 170.0f * static_cast<float>(k);
        if (!mega.add_stroke(wave(30.0f, 1370.0f, y, 40.0f, 200.0f)).ok()) return 1;
    }
    Timing paint_mega;
    const auto big =
        best_of(paint_mega, [&] { return paint::paint(source, mega, options, context); });
    if (!big.ok()) return failed(big.status());
    if (const Status saved = save("five", big->image); !saved.is_ok()) return failed(saved);
    report("paint, five strokes", painted_mpix(mega), paint_mega);
    return 0;
}
