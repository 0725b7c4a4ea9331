// Animation benchmark: the full TCIA forward-backward solve (exemplar::animate) on a procedural
// 960x540 sequence (a textured disc moving over a textured background) stylized after Starry
// Night (shared data; S = its blurred luminance, Ŝ = the painting), default settings.
//
//   bench_animate [frames=6] [threads=2] [--given-flow] [--keys] [--scale s]
//                 [--no-derivative] [--no-ribbons] [--set name=value ...]
//
// --keys adds full keyframes at the first and last frame (the painting resized to the frame:
// only their cost matters here, the source atlas grows by two frames). With keys,
// --no-derivative uses g_tc instead of g_din (input_derivative_weight = 0) and --no-ribbons
// turns the ribbon candidates off: both together are the solver before those terms.
//
// --set changes an engine option of every call (names of `exemplar stylize --help`).
//
// Prints the wall time per stage (motion, occlusion, forward, backward, merge) in total and
// per frame.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "animate_scene.hpp"
#include "exemplar/animate/animate.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/io/image_io.hpp"
#include "shared_data.hpp"

using namespace exemplar;

int main(int argc, char** argv) {
    int frames = 6, threads = 2;
    bool given = false, keys = false;
    float scale = 1.0f;
    int positional = 0;
    animate::AnimateOptions options;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--given-flow") {
            given = true;
        } else if (a == "--keys") {
            keys = true;
        } else if (a == "--no-derivative") {
            options.input_derivative_weight = 0.0f;
        } else if (a == "--no-ribbons") {
            options.ribbons = false;
        } else if (a == "--set" && i + 1 < argc) {
            const std::string kv = argv[++i];
            const auto eq = kv.find('=');
            const OptionSpec* spec = find_option(kv.substr(0, eq));
            if (eq == std::string::npos || spec == nullptr) {
                std::fprintf(stderr, "--set %s: unknown option\n", kv.c_str());
                return 2;
            }
            const Status st =
                set_option(options.synthesis, *spec, std::strtod(kv.c_str() + eq + 1, nullptr));
            if (!st.is_ok()) {
                std::fprintf(stderr, "%s\n", st.message().c_str());
                return 2;
            }
        } else if (a == "--scale" && i + 1 < argc) {
            scale = std::strtof(argv[++i], nullptr);
        } else if (positional++ == 0) {
            frames = std::atoi(argv[i]);
        } else {
            threads = std::atoi(argv[i]);
        }
    }
    bench::DiscScene scene;
    scene.width = static_cast<int>(960 * scale);
    scene.height = static_cast<int>(540 * scale);
    const std::string painting_file = bench::shared_data("style/neural-style/starry_night.jpg");
    if (!bench::shared_data_present(painting_file)) return 1;
    auto painting = load_image(painting_file);
    if (!painting.ok()) {
        std::fprintf(stderr, "%s\n", painting.status().message().c_str());
        return 1;
    }
    // Style at the frames' scale (the painting is 1024x640).
    const Image out = resize(*painting, static_cast<int>(1024 * scale),
                             static_cast<int>(640 * scale), ResampleFilter::Gaussian);
    Image luma(out.width(), out.height(), 1);
    for (std::size_t i = 0; i < luma.pixel_count(); ++i) {
        luma.data()[i] = 0.2126f * out.data()[3 * i] + 0.7152f * out.data()[3 * i + 1] +
                         0.0722f * out.data()[3 * i + 2];
    }
    luma = gaussian_blur(luma, 2.0f * scale);

    animate::AnimationInput in;
    in.style_input = luma;
    in.style_output = out;
    in.frame_count = frames;
    in.frame = [&](int t) -> Result<Image> { return scene.frame(t); };
    if (given) in.motion = [&](int t) -> Result<video::FlowPair> { return scene.motion(t); };
    if (keys) {
        const Image key = resize(out, scene.width, scene.height, ResampleFilter::Gaussian);
        in.keyframes = {{0, key, {}}, {frames - 1, key, {}}};
    }
    RunContext context(threads);
    const auto start = std::chrono::steady_clock::now();
    auto r = animate::animate(in, options, context);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!r.ok()) {
        std::fprintf(stderr, "%s\n", r.status().message().c_str());
        return 1;
    }
    const animate::StageTimes& s = r->times;
    std::printf("%dx%d, %d frames, %d threads, motion %s%s\n", scene.width, scene.height, frames,
                threads, given ? "given" : "estimated (DIS medium)",
                keys ? ", keys at the first and last frame" : "");
    std::printf("%-10s %9s %9s\n", "stage", "total s", "per frame");
    const std::pair<const char*, double> rows[] = {
        {"motion", s.flow},       {"occlusion", s.occlusion}, {"forward", s.forward},
        {"backward", s.backward}, {"merge", s.merge},         {"wall", wall}};
    for (const auto& [name, v] : rows) std::printf("%-10s %9.2f %9.2f\n", name, v, v / frames);
    if (argc > 0 && std::getenv("BENCH_ANIMATE_SAVE")) {
        for (int t = 0; t < frames; ++t) {
            (void)save_image(
                r->frames[static_cast<std::size_t>(t)],
                std::string(std::getenv("BENCH_ANIMATE_SAVE")) + "/" + std::to_string(t) + ".png");
        }
    }
    return 0;
}
