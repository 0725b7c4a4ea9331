// Times one render of a built-in scene (default: sphere-on-table at 1200x912, 2 threads), the
// benchmark of docs/PERFORMANCE.md. Not a test.
//
//   bench_render [--scene NAME] [--width 1200] [--height 912] [--spp 64] [--threads 2]

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "exemplar/render/render.hpp"
#include "exemplar/render/scene.hpp"

int main(int argc, char** argv) {
    using namespace exemplar;
    render::RenderOptions options;
    options.width = 1200;
    options.height = 912;
    int threads = 2;
    std::string name = "sphere-on-table";
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i], value = argv[i + 1];
        if (flag == "--scene")
            name = value;
        else if (flag == "--width")
            options.width = std::atoi(value.c_str());
        else if (flag == "--height")
            options.height = std::atoi(value.c_str());
        else if (flag == "--spp")
            options.samples_per_pixel = std::atoi(value.c_str());
        else if (flag == "--threads")
            threads = std::atoi(value.c_str());
        else {
            std::fprintf(stderr, "bench_render: unknown flag %s\n", flag.c_str());
            return 2;
        }
    }
    auto scene = render::builtin_scene(name);
    if (!scene.ok()) {
        std::fprintf(stderr, "bench_render: %s\n", scene.status().message().c_str());
        return 1;
    }
    const auto start = std::chrono::steady_clock::now();
    auto buffers = render::render(*scene, options, RunContext(threads));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!buffers.ok()) {
        std::fprintf(stderr, "bench_render: %s\n", buffers.status().message().c_str());
        return 1;
    }
    const double paths =
        static_cast<double>(options.width) * options.height * options.samples_per_pixel;
    std::printf("%s %dx%d, %d spp, %d threads: %.2f s (%.2f M paths/s)\n", name.c_str(),
                options.width, options.height, options.samples_per_pixel, threads, seconds,
                paths / seconds / 1e6);
    return 0;
}
