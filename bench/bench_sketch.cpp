// Interactive latency of sketch beautification: suggestions for one new stroke against a
// resolved drawing of 100 paths (ShipShape is run on every pen-up; the budget is 30 ms).
// The drawing is the TU-Berlin sketches' strokes (tests/data/strokes/tu-berlin, all in one
// 800x800 canvas, so denser than any single sketch), replayed and accepted in order until it
// holds 100 paths; each following stroke is then timed against it (setup is not timed).
// Usage: bench_sketch [new strokes] [repeats]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "exemplar/sketch/beautify.hpp"
#include "exemplar/sketch/svg.hpp"

using namespace exemplar::sketch;

int main(int argc, char** argv) {
    const int new_strokes = argc > 1 ? std::atoi(argv[1]) : 40;
    const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(
             std::string(EXEMPLAR_TEST_DATA_DIR) + "/strokes/tu-berlin")) {
        if (e.path().extension() == ".svg") files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    std::vector<Path> strokes;
    for (const std::string& f : files) {
        auto d = load_svg(f);
        if (!d.ok()) {
            std::fprintf(stderr, "%s\n", d.status().message().c_str());
            return 1;
        }
        strokes.insert(strokes.end(), d->paths.begin(), d->paths.end());
    }

    const BeautifyOptions options;
    ResolvedDrawing drawing;
    std::size_t next = 0;
    while (drawing.paths.size() < 100 && next < strokes.size()) {
        auto s = suggest(drawing, strokes[next++], options);
        if (!s.ok()) return 1;
        accept(drawing, s->front(), options);
    }
    std::printf("drawing: %zu resolved paths from %zu strokes\n", drawing.paths.size(), next);

    std::vector<double> ms;
    std::size_t most_suggestions = 0;
    for (int k = 0; k < new_strokes && next + static_cast<std::size_t>(k) < strokes.size(); ++k) {
        const Path& stroke = strokes[next + static_cast<std::size_t>(k)];
        double best = 1e9;
        for (int r = 0; r < repeats; ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            auto s = suggest(drawing, stroke, options);
            const double t =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count();
            if (!s.ok()) return 1;
            most_suggestions = std::max(most_suggestions, s->size());
            best = std::min(best, t);
        }
        ms.push_back(best);
    }
    std::sort(ms.begin(), ms.end());
    auto at = [&](double q) { return ms[static_cast<std::size_t>(q * (ms.size() - 1) + 0.5)]; };
    std::printf(
        "suggest() for %zu new strokes (best of %d runs each): median %.2f ms, "
        "p90 %.2f ms, max %.2f ms; up to %zu suggestions\n",
        ms.size(), repeats, at(0.5), at(0.9), ms.back(), most_suggestions);
    return 0;
}
