// Pen-up latency of `exemplar studio` (issue 22's budget: a paint stroke within 100 ms of pen-up
// for a 0.25 MPix region, a sketch suggestion within 50 ms), measured through the HTTP API of an
// in-process server as the browser calls it (request, library call, answer bytes; not the
// browser's drawing, which the browser test logs).
// Paint: a 512x512 canvas (0.26 MPix) painted with tests/data/flow/synthetic-img0.png; each
// stroke's changed rectangle is printed with its wall and CPU time from pen-up to the preview
// pixels (POST /api/paint/preview) and to the final pixels (then POST /api/paint/stroke, as the
// SPA does), and of the final alone (the stroke posted without a preview). Strokes: a thin
// diagonal (the rectangle is the whole canvas, a sixth of it painted) and a wide stroke painting
// most of the canvas, then a comb across both.
// Sketch: a stroke against a drawing of 12 accepted strokes (a grid of lines), suggestions
// as the client receives them; median and maximum over the repeats.
// Usage: bench_studio [threads] [repeats]
#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "studio.hpp"

using namespace exemplar;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
    const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
    const fs::path workspace = fs::temp_directory_path() / "exemplar_bench_studio";
    fs::remove_all(workspace);
    fs::create_directories(workspace);
    fs::copy_file(fs::path(EXEMPLAR_TEST_DATA_DIR) / "flow" / "synthetic-img0.png",
                  workspace / "exemplar.png");
    studio::StudioOptions options;
    options.port = 0;
    options.workspace = workspace.string();
    options.threads = threads;
    auto server = studio::StudioServer::create(options);
    if (!server.ok()) {
        std::fprintf(stderr, "bench_studio: %s\n", server.status().message().c_str());
        return 1;
    }
    std::thread serving([&] { (*server)->run(); });
    httplib::Client client("127.0.0.1", (*server)->port());
    client.set_read_timeout(300, 0);
    const auto post = [&](const char* path, const json& body) {
        return client.Post(path, body.dump(), "application/json");
    };
    std::printf("threads %d, repeats %d\n", threads, repeats);

    const json strokes[] = {
        {{"points", {{64, 64}, {448, 448}}}, {"width", 64}},
        {{"points", {{60, 150}, {450, 160}, {450, 360}, {60, 370}}}, {"width", 200}},
        {{"points", {{40, 256}, {470, 256}}}, {"width", 120}, {"comb", true}},
    };
    for (std::size_t s = 0; s < std::size(strokes); ++s) {
        // Wall and CPU (the process's: the server is in it) times from pen-up to the preview,
        // to the final after the preview, and to the final posted alone.
        std::vector<double> wall[3], cpu[3];
        std::string rect;
        for (int r = 0; r < repeats; ++r) {
            for (int previewed = 0; previewed < 2; ++previewed) {
                post("/api/paint/start",
                     {{"exemplar", "exemplar.png"}, {"width", 512}, {"height", 512}});
                for (std::size_t before = 0; before < s; ++before)
                    post("/api/paint/stroke", strokes[before]);
                const auto t0 = std::chrono::steady_clock::now();
                const std::clock_t c0 = std::clock();
                const auto lap = [&](int k) {
                    wall[k].push_back(ms_since(t0));
                    cpu[k].push_back(1000.0 * static_cast<double>(std::clock() - c0) /
                                     CLOCKS_PER_SEC);
                };
                if (previewed) {
                    auto pre = post("/api/paint/preview", strokes[s]);
                    if (!pre || pre->status != 200) {
                        std::fprintf(stderr, "bench_studio: preview failed\n");
                        return 1;
                    }
                    lap(0);
                }
                auto res = post("/api/paint/stroke", strokes[s]);
                if (!res || res->status != 200) {
                    std::fprintf(stderr, "bench_studio: stroke failed\n");
                    return 1;
                }
                lap(previewed ? 1 : 2);
                rect = res->get_header_value("X-Rect");
            }
        }
        int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
        std::sscanf(rect.c_str(), "%d,%d,%d,%d", &x0, &y0, &x1, &y1);
        std::printf(
            "paint stroke %zu (%s, width %g px): rectangle %dx%d = %.3f MPix: wall median (min) / "
            "CPU median: preview %.0f (%.0f) / %.0f ms, final after it %.0f (%.0f) / %.0f ms, "
            "final alone %.0f (%.0f) / %.0f ms\n",
            s + 1, strokes[s].value("comb", false) ? "comb" : "paint",
            strokes[s]["width"].get<double>(), x1 - x0, y1 - y0, (x1 - x0) * (y1 - y0) / 1e6,
            median(wall[0]), *std::min_element(wall[0].begin(), wall[0].end()), median(cpu[0]),
            median(wall[1]), *std::min_element(wall[1].begin(), wall[1].end()), median(cpu[1]),
            median(wall[2]), *std::min_element(wall[2].begin(), wall[2].end()), median(cpu[2]));
    }

    // Sketch: 12 accepted lines (a grid), then the timed stroke.
    std::vector<double> sketch_times;
    int suggestions = 0;
    for (int r = 0; r < repeats; ++r) {
        post("/api/sketch/reset", json::object());
        for (int i = 0; i < 12; ++i) {
            const double c = 60.0 + 40.0 * (i % 6);
            const json line = i < 6 ? json{{c, 40.0}, {c + 1.5, 140.0}, {c - 1.0, 260.0}}
                                    : json{{40.0, c}, {140.0, c + 1.5}, {260.0, c - 1.0}};
            post("/api/sketch/stroke", {{"points", line}});
            post("/api/sketch/accept", {{"index", 0}});
        }
        json wobbly = json::array();
        for (int k = 0; k <= 40; ++k)
            wobbly.push_back({30.0 + 6.0 * k, 300.0 + ((k % 3) - 1) * 1.5});
        const auto t0 = std::chrono::steady_clock::now();
        auto res = post("/api/sketch/stroke", {{"points", wobbly}});
        sketch_times.push_back(ms_since(t0));
        if (!res || res->status != 200) {
            std::fprintf(stderr, "bench_studio: sketch stroke failed\n");
            return 1;
        }
        suggestions = static_cast<int>(json::parse(res->body)["suggestions"].size());
    }
    std::printf(
        "sketch suggestion (41-point stroke, 12 accepted strokes, %d suggestions): median "
        "%.1f ms, max %.1f ms\n",
        suggestions, median(sketch_times),
        *std::max_element(sketch_times.begin(), sketch_times.end()));
    (*server)->shutdown();
    serving.join();
    fs::remove_all(workspace);
    return 0;
}
