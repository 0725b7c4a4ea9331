// Speed of the area-feature fill (Painting by Feature, docs/feature.md; the budget: a
// 1 MPix fill within 3 s with 2 threads). The palette is the bundled crop of The Scream
// (examples/feature/scream_railing.png) with the fjord's water as the source region (the
// polygon of examples/feature/water_region.png); the canvas is 1024 x 1024 paper with a 30 px
// dark diagonal band (a painted line feature) and the target region is all of the paper
// (about 0.97 MPix). Wall time (best of the repeats) and the process's CPU time per fill (the
// machine may be shared: CPU time is what the fill costs).
// Usage: bench_fill [threads] [repeats] [usage] [rotations] [out.png]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/feature_fill.hpp"

using namespace exemplar;
using namespace exemplar::paint;

int main(int argc, char** argv) {
    const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
    const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
    FeatureFillOptions options;
    if (argc > 3) {
        auto usage = parse_usage_strategy(argv[3]);
        if (!usage.ok()) {
            std::fprintf(stderr, "%s\n", usage.status().message().c_str());
            return 1;
        }
        options.usage = *usage;
    }
    if (argc > 4) options.rotations = std::atoi(argv[4]);
    const std::string dir = std::string(EXEMPLAR_SOURCE_DIR) + "/examples/feature/";
    auto palette = load_image(dir + "scream_railing.png");
    auto source_region = load_image(dir + "water_region.png");
    if (!palette.ok() || !source_region.ok()) {
        std::fprintf(stderr, "%s\n",
                     (palette.ok() ? source_region.status() : palette.status()).message().c_str());
        return 1;
    }

    // The canvas: paper with a dark band from (0, 300) to (1024, 700); the paper is the target.
    const int size = 1024;
    Image canvas(size, size, 3), target(size, size, 1);
    const float nx = -400.0f, ny = 1024.0f, norm = std::hypot(nx, ny);
    int target_pixels = 0;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float d = std::abs(((static_cast<float>(x) + 0.5f) * nx +
                                      (static_cast<float>(y) + 0.5f - 300.0f) * ny) /
                                     norm);
            const bool band = d < 15.0f;
            float* p = canvas.pixel(x, y);
            p[0] = band ? 0.25f : 0.95f;
            p[1] = band ? 0.13f : 0.92f;
            p[2] = band ? 0.06f : 0.85f;
            target.at(x, y, 0) = band ? 0.0f : 1.0f;
            target_pixels += band ? 0 : 1;
        }
    }

    double best_ms = 1e30, cpu_s = 0.0;
    for (int r = 0; r < repeats; ++r) {
        const std::clock_t c0 = std::clock();
        const auto t0 = std::chrono::steady_clock::now();
        auto filled =
            fill_area(*palette, *source_region, canvas, target, options, RunContext(threads));
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        cpu_s += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC / repeats;
        if (!filled.ok()) {
            std::fprintf(stderr, "%s\n", filled.status().message().c_str());
            return 1;
        }
        best_ms = std::min(best_ms, ms);
        if (r == 0 && argc > 5) (void)save_image(*filled, argv[5]);
    }
    std::printf(
        "fill of %d px (%dx%d canvas), usage %s, %d rotations, %d threads: best %.0f ms wall, "
        "%.1f CPU-s per fill (mean of %d)\n",
        target_pixels, size, size, std::string(to_string(options.usage)).c_str(), options.rotations,
        threads, best_ms, cpu_s, repeats);
    return 0;
}
