// LazyFluids benchmark: one ~1 MPix frame (1024x1024) with the temporal term, 2 threads by
// default. The target is the built-in plume simulated at 256x256 (warm-up of 100 frames, so it
// fills a good part of the frame), its alpha and motion upsampled 4x; the exemplar is the
// procedural fire of the tests at `exemplar` px (default 128). Prints the simulation time, the
// time of the first frame (no previous frame) and of the next one (temporal term), the fluid's
// share of the frame and the K of each segment.
//
//   bench_fluid [threads=2] [exemplar=128] [scale=4] [warmup=100]

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "exemplar/filters/resample.hpp"
#include "exemplar/fluid/lazy_fluids.hpp"
#include "exemplar/fluid/simulate.hpp"
#include "fluid_scene.hpp"

using namespace exemplar;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// User + system CPU seconds of this process so far (the machine may be shared: CPU time is the
// steadier figure).
double cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    auto secs = [](const timeval& t) { return static_cast<double>(t.tv_sec) + t.tv_usec * 1e-6; };
    return secs(usage.ru_utime) + secs(usage.ru_stime);
}

}  // namespace

int main(int argc, char** argv) {
    const int threads = argc > 1 ? std::atoi(argv[1]) : 2;
    const int exemplar_size = argc > 2 ? std::atoi(argv[2]) : 128;
    const int scale = argc > 3 ? std::atoi(argv[3]) : 4;

    auto start = std::chrono::steady_clock::now();
    fluid::FluidScene scene = fluid::plume_scene(256, 256);
    scene.warmup_frames = argc > 4 ? std::atoi(argv[4]) : 100;
    std::vector<Image> alphas, motions;
    const Status simulated = fluid::simulate(
        scene, 2,
        [&](int, const Image& alpha, const Image& motion) {
            alphas.push_back(resize(alpha, 256 * scale, 256 * scale, ResampleFilter::Gaussian));
            Image m = resize(motion, 256 * scale, 256 * scale, ResampleFilter::Gaussian);
            for (float& v : m.data()) v *= static_cast<float>(scale);
            motions.push_back(std::move(m));
            return Status::ok();
        },
        RunContext(threads));
    if (!simulated.is_ok()) {
        std::fprintf(stderr, "%s\n", simulated.message().c_str());
        return 1;
    }
    std::printf("simulation 256x256, %d frames: %.2f s\n", scene.warmup_frames + 2,
                seconds_since(start));

    const Image exemplar = fluid::test::fire_exemplar(exemplar_size);
    fluid::FluidOptions options;
    options.blur_radius_px = 3.0f;  // the paper's r at about this resolution
    fluid::FluidFrameInput in;
    in.exemplar = &exemplar;
    in.target_alpha = &alphas[0];
    start = std::chrono::steady_clock::now();
    double cpu = cpu_seconds();
    auto first = fluid::synthesize_fluid_frame(in, options, RunContext(threads));
    if (!first.ok()) {
        std::fprintf(stderr, "%s\n", first.status().message().c_str());
        return 1;
    }
    const double t_first = seconds_since(start);
    const double cpu_first = cpu_seconds() - cpu;
    cpu = cpu_seconds();
    in.target_alpha = &alphas[1];
    in.previous_output = &first->rgba;
    in.previous_motion = &motions[0];
    start = std::chrono::steady_clock::now();
    auto second = fluid::synthesize_fluid_frame(in, options, RunContext(threads));
    if (!second.ok()) {
        std::fprintf(stderr, "%s\n", second.status().message().c_str());
        return 1;
    }
    const double t_second = seconds_since(start);
    const double cpu_second = cpu_seconds() - cpu;

    long counts[3] = {0, 0, 0}, sources[3] = {0, 0, 0};
    for (float v : second->target_segments.data()) ++counts[static_cast<int>(v)];
    for (float v : second->source_segments.data()) ++sources[static_cast<int>(v)];
    const long pixels = static_cast<long>(alphas[1].width()) * alphas[1].height();
    std::printf("frame %dx%d, exemplar %dx%d, %d threads\n", alphas[1].width(), alphas[1].height(),
                exemplar_size, exemplar_size, threads);
    std::printf("fluid %.1f%% of the frame (boundary %ld px, interior %ld px; K ~ %ld and %ld)\n",
                100.0 * static_cast<double>(counts[1] + counts[2]) / static_cast<double>(pixels),
                counts[1], counts[2], sources[1] ? counts[1] / sources[1] : 0,
                sources[2] ? counts[2] / sources[2] : 0);
    std::printf("first frame (no temporal term): %.2f s (CPU %.2f s)\n", t_first, cpu_first);
    std::printf("next frame (temporal term): %.2f s (CPU %.2f s)\n", t_second, cpu_second);
    return 0;
}
