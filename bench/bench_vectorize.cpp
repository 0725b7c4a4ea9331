// Speed of vector image stylization (Painting by Feature, docs/feature.md; the budget: a
// TU-Berlin drawing stylized within 5 s with 2 threads). The drawing is a TU-Berlin sketch from
// tests/data (CC BY 4.0, Eitz, Hays and Alexa 2012; airplane/2.svg unless given), the style the
// bundled examples/feature/scream_style.json (the railing along every stroke, the fjord's water
// as background), at the drawing's size (800 x 800). Wall time (best of the repeats) and the
// process's CPU time per run (the machine may be shared: CPU time is what the run costs).
// Usage: bench_vectorize [threads] [repeats] [drawing.svg] [out.png]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/vectorize_style.hpp"

using namespace exemplar;

int main(int argc, char** argv) {
    const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
    const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
    const std::string source = EXEMPLAR_SOURCE_DIR;
    const std::string file =
        argc > 3 ? argv[3] : source + "/tests/data/strokes/tu-berlin/airplane/2.svg";
    auto drawing = sketch::load_svg(file);
    auto palette = paint::load_style_palette(source + "/examples/feature/scream_style.json");
    if (!drawing.ok() || !palette.ok()) {
        std::fprintf(stderr, "%s\n",
                     (drawing.ok() ? palette.status() : drawing.status()).message().c_str());
        return 1;
    }
    const auto [width, height] = paint::drawing_canvas_size(*drawing);

    double best_ms = 1e30, cpu_s = 0.0;
    for (int r = 0; r < repeats; ++r) {
        const std::clock_t c0 = std::clock();
        const auto t0 = std::chrono::steady_clock::now();
        auto out =
            paint::vectorize_style(*drawing, *palette, width, height, {}, RunContext(threads));
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count();
        cpu_s += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC / repeats;
        if (!out.ok()) {
            std::fprintf(stderr, "%s\n", out.status().message().c_str());
            return 1;
        }
        best_ms = std::min(best_ms, ms);
        if (r == 0 && argc > 4) (void)save_image(*out, argv[4]);
    }
    std::printf(
        "vectorize-style of %s (%zu paths, %dx%d), %d threads: best %.0f ms wall, %.1f CPU-s "
        "per run (mean of %d)\n",
        file.substr(file.rfind("/tu-berlin/") == std::string::npos ? 0
                                                                   : file.rfind("/tu-berlin/") + 11)
            .c_str(),
        drawing->paths.size(), width, height, threads, best_ms, cpu_s, repeats);
    return 0;
}
