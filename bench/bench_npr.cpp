// Timing of image-space NPR (`exemplar npr`, npr::stylize_frame) at the scale (issue 20:
// at most 2 s per 960x540 frame with 2 threads): frames 0 and 1 of
// examples/render/spot-turntable.json rendered in-process by the project's renderer
// (render::render_frame, not timed), a generated pattern (tests/npr/npr_patterns.hpp), then
// the first frame (no previous state) and the continuing frame (backward flow, disocclusion and
// the first frame's state). Pattern preparation is timed once.
//
// Usage: bench_npr [threads] [repeats] [options...]
//   --style S          stipple (default), hatch (hatching pattern, orientation buffer),
//                      halftone, pattern
//   --size WxH         frame size (default 960x540)
//   --spp N            render samples per pixel (default 4; the tone's noise only)
//   --pattern-size N   generated pattern side in px (default 128)
//   --out PREFIX       save the two frames as PREFIX0.png, PREFIX1.png
//   --save-pattern F   save the generated pattern (for timing `exemplar npr --pattern F`)
//   --paper 1          with the paper layer (tests/data/paper/struc.pgm; level lines then
//                      include the paper's levels)
// Prints per stage the wall and CPU time (the machine may be shared: compare CPU times): the
// pattern preparation; per frame each synthesis level (initialization or upsampling plus
// correction, from the library's progress events) and the tail (screen, thresholding with tone
// correction, lines), and the frame's total.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/npr/npr.hpp"
#include "exemplar/render/animation.hpp"
#include "npr_patterns.hpp"

using namespace exemplar;

namespace {

struct Settings {
    int threads = 2;
    int repeats = 1;
    int width = 960;
    int height = 540;
    int spp = 4;
    int pattern_size = 128;
    npr::Style style = npr::Style::Stipple;
    std::string out;
    std::string save_pattern;
    bool paper = false;
};

// Wall and CPU time since the last mark.
struct Clock {
    std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
    double cpu = bench::cpu_seconds();
    void print(const char* label) {
        const auto now = std::chrono::steady_clock::now();
        const double cpu_now = bench::cpu_seconds();
        std::printf("  %-28s wall %7.3f s  cpu %7.3f s\n", label,
                    std::chrono::duration<double>(now - wall).count(), cpu_now - cpu);
        wall = now;
        cpu = cpu_now;
    }
};

npr::NprFrame frame_buffers(const render::RenderBuffers& b) {
    npr::NprFrame frame;
    frame.tone = b.direct_diffuse;
    frame.tone_linear = true;
    frame.orientation = b.orientation;
    frame.backward_flow = b.backward_flow;
    frame.disocclusion = b.disocclusion;
    frame.lines = b.lines;
    frame.mask = b.alpha;
    return frame;
}

bool parse(int argc, char** argv, Settings& settings) {
    std::vector<char*> args{argv[0], argv[0]};
    args.insert(args.end(), argv + 1, argv + argc);
    const int first = bench::parse_counts(static_cast<int>(args.size()), args.data(),
                                          settings.threads, settings.repeats);
    return bench::for_each_flag(
        static_cast<int>(args.size()), args.data(), first,
        [&](const std::string& arg, const std::string& value) {
            if (arg == "--style") {
                auto style = npr::parse_style(value);
                if (!style.ok()) {
                    std::fprintf(stderr, "%s\n", style.status().message().c_str());
                    return false;
                }
                settings.style = *style;
            } else if (arg == "--size") {
                if (std::sscanf(value.c_str(), "%dx%d", &settings.width, &settings.height) != 2) {
                    std::fprintf(stderr, "--size: '%s' is not WxH\n", value.c_str());
                    return false;
                }
            } else if (arg == "--spp") {
                settings.spp = std::stoi(value);
            } else if (arg == "--pattern-size") {
                settings.pattern_size = std::stoi(value);
            } else if (arg == "--paper") {
                settings.paper = value != "0";
            } else if (arg == "--save-pattern") {
                settings.save_pattern = value;
            } else if (arg == "--out") {
                settings.out = value;
            } else {
                std::fprintf(stderr, "unknown argument %s\n", arg.c_str());
                return false;
            }
            return true;
        });
}

}  // namespace

int main(int argc, char** argv) {
    Settings settings;
    if (!parse(argc, argv, settings)) return 2;

    // Render frames 0 and 1 (not timed)
    auto animation = render::load_animation(std::string(EXEMPLAR_SOURCE_DIR) +
                                            "/examples/render/spot-turntable.json");
    if (!animation.ok()) {
        std::fprintf(stderr, "%s\n", animation.status().message().c_str());
        return 1;
    }
    render::RenderOptions render_options;
    render_options.width = settings.width;
    render_options.height = settings.height;
    render_options.samples_per_pixel = settings.spp;
    RunContext render_context;
    render_context.threads = settings.threads;
    std::vector<render::RenderBuffers> rendered;
    for (int f = 0; f < 2; ++f) {
        auto buffers = render::render_frame(*animation, f, render_options, render_context);
        if (!buffers.ok()) {
            std::fprintf(stderr, "%s\n", buffers.status().message().c_str());
            return 1;
        }
        rendered.push_back(std::move(buffers).value());
    }
    const int n = settings.pattern_size;
    const Image pattern_image =
        settings.style == npr::Style::Hatch      ? npr::testing::hatching_pattern(n, 8, 2.5f)
        : settings.style == npr::Style::Halftone ? npr::testing::halftone_pattern(n, 8)
                                                 : npr::testing::stipple_pattern(n, 6.0f);
    if (!settings.save_pattern.empty()) {
        const Status saved = save_image(pattern_image, settings.save_pattern);
        if (!saved.is_ok()) std::fprintf(stderr, "%s\n", saved.message().c_str());
    }

    npr::NprOptions options;
    options.style = settings.style;
    std::printf("npr %dx%d, style %s, pattern %dx%d, %d threads\n", settings.width, settings.height,
                std::string(npr::to_string(settings.style)).c_str(), n, n, settings.threads);
    RunContext context;
    context.threads = settings.threads;
    Clock clock;
    auto pattern = npr::prepare_pattern(pattern_image, options, context);
    if (!pattern.ok()) {
        std::fprintf(stderr, "%s\n", pattern.status().message().c_str());
        return 1;
    }
    clock.print("pattern preparation");
    std::optional<npr::Pattern> paper;
    if (settings.paper) {
        options.paper = true;
        auto paper_image =
            load_image(std::string(EXEMPLAR_SOURCE_DIR) + "/tests/data/paper/struc.pgm");
        auto prepared = paper_image.ok() ? npr::prepare_pattern(*paper_image, options, context)
                                         : Result<npr::Pattern>(paper_image.status());
        if (!prepared.ok()) {
            std::fprintf(stderr, "%s\n", prepared.status().message().c_str());
            return 1;
        }
        paper = std::move(prepared).value();
        clock.print("paper preparation");
    }

    for (int repeat = 0; repeat < settings.repeats; ++repeat) {
        std::optional<npr::FrameState> previous, previous_paper;
        for (int f = 0; f < 2; ++f) {
            std::printf("frame %d (%s)\n", f, f == 0 ? "first" : "continuing");
            Clock stage, total;
            context.progress = [&](const ProgressEvent& event) {
                const std::string label =
                    "level " + std::to_string(options.levels - 1 - event.level);
                stage.print(label.c_str());
            };
            npr::NprPaper paper_layer;
            if (paper) {
                paper_layer.pattern = &*paper;
                paper_layer.previous = previous_paper ? &*previous_paper : nullptr;
            }
            auto result = npr::stylize_frame(*pattern, frame_buffers(rendered[f]),
                                             previous ? &*previous : nullptr, f, options, context,
                                             paper_layer);
            if (!result.ok()) {
                std::fprintf(stderr, "%s\n", result.status().message().c_str());
                return 1;
            }
            stage.print("screen, threshold, lines");
            total.print("frame total");
            if (!settings.out.empty() && repeat == 0) {
                const Status saved =
                    save_image(result->image, settings.out + std::to_string(f) + ".png");
                if (!saved.is_ok()) std::fprintf(stderr, "%s\n", saved.message().c_str());
            }
            previous = std::move(result->state);
            if (paper) previous_paper = std::move(result->paper_state);
        }
    }
    return 0;
}
