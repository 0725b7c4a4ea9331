// Timing of Color Me Noisy (`exemplar noisy`, synthesize_frame) at the chapter's scale:
// one ~1 MPix frame (1152x864) of a flat-coloured cel in the medium's colours (a red ground, a
// teal ball with its shadow and highlight, a dark band) from the bundled StyLit pastel painting
// examples/stylit/source_style.png (600x456, public domain) at f = 4 (issue 17: target 3 s per
// frame with 2 threads; the chapter reports 30 s on one core). Loading is not timed.
//
// Usage: bench_noisy [threads] [repeats] [options...]
//   --noise F          low-pass strength f (default 4)
//   --set NAME=VALUE   a noisy option (see `exemplar noisy --help`), e.g. em-iterations=4
//   --size WxH         reference size (default 1152x864)
//   --medium FILE      the drawing medium (default examples/stylit/source_style.png)
//   --frame I          frame index (default 0); repeats use I, I+1, ...
//   --out FILE         save the last frame
//   --save-cel FILE    save the reference cel
// Prints per run the wall and CPU time of the frame, and per pyramid level (strength, size)
// the wall and CPU time it took (the machine may be shared: compare CPU times); then the frame's
// coarse consistency (RMS of h_f * T - h_f * R relative to the contrast of h_f * R), its detail
// (mean squared pixel difference relative to the medium's) and, over the repeats (frames I,
// I+1, ...), the temporal energy (mean variance across frames; the cel is static).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/noisy/noisy.hpp"
#include "procedural.hpp"

using namespace exemplar;
using namespace exemplar::noisy;

namespace {

struct Settings {
    int threads = 2;
    int repeats = 1;
    int width = 1152;
    int height = 864;
    std::int64_t frame = 0;
    NoisyOptions options;
    std::string medium = std::string(EXEMPLAR_SOURCE_DIR) + "/examples/stylit/source_style.png";
    std::string out;
    std::string save_cel;
};

// A cel in the painting's colours: red ground, a teal ball with a dark cast shadow and a pale
// highlight, and a darker band along the bottom; hard edges like flat colouring.
Image cel(int width, int height) {
    const float red[3] = {0.86f, 0.24f, 0.27f};
    const float band[3] = {0.62f, 0.12f, 0.20f};
    const float teal[3] = {0.20f, 0.52f, 0.56f};
    const float shadow[3] = {0.30f, 0.10f, 0.17f};
    const float highlight[3] = {0.80f, 0.85f, 0.86f};
    const double s = std::min(width, height);
    const double cx = 0.45 * width, cy = 0.45 * height, r = 0.25 * s;
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float* c = red;
            if (y > 0.82 * height) c = band;
            if (std::hypot((x - cx - 0.25 * r) / 1.6, y - cy - 0.95 * r) < 0.55 * r) c = shadow;
            if (std::hypot(x - cx, y - cy) < r) c = teal;
            if (std::hypot(x - cx + 0.35 * r, y - cy + 0.4 * r) < 0.17 * r) c = highlight;
            for (int k = 0; k < 3; ++k) image.at(x, y, k) = c[k];
        }
    }
    return image;
}

// Mean over pixels and channels of the squared horizontal and vertical differences: the detail
// a frame holds (plain nearest neighbours wash out towards 0).
double gradient_energy(const Image& image) {
    double sum = 0.0;
    long count = 0;
    for (int y = 0; y + 1 < image.height(); ++y) {
        for (int x = 0; x + 1 < image.width(); ++x) {
            for (int c = 0; c < image.channels(); ++c) {
                const double dx = image.at(x + 1, y, c) - image.at(x, y, c);
                const double dy = image.at(x, y + 1, c) - image.at(x, y, c);
                sum += dx * dx + dy * dy;
                ++count;
            }
        }
    }
    return sum / static_cast<double>(std::max(1L, count));
}

bool parse_options(int argc, char** argv, int first, Settings& settings) {
    return bench::for_each_flag(
        argc, argv, first, [&](const std::string& arg, const std::string& value) {
            Status status = Status::ok();
            if (arg == "--noise") {
                status =
                    set_option(settings.options, *find_noisy_option("noise"), std::stod(value));
            } else if (arg == "--set") {
                const auto eq = value.find('=');
                const NoisyOptionSpec* spec =
                    eq == std::string::npos ? nullptr : find_noisy_option(value.substr(0, eq));
                if (spec == nullptr) {
                    std::fprintf(stderr, "unknown option in --set %s\n", value.c_str());
                    return false;
                }
                status = set_option(settings.options, *spec, std::stod(value.substr(eq + 1)));
            } else if (arg == "--size") {
                if (std::sscanf(value.c_str(), "%dx%d", &settings.width, &settings.height) != 2) {
                    std::fprintf(stderr, "--size: '%s' is not WxH\n", value.c_str());
                    return false;
                }
            } else if (arg == "--medium") {
                settings.medium = value;
            } else if (arg == "--frame") {
                settings.frame = std::stoll(value);
            } else if (arg == "--out") {
                settings.out = value;
            } else if (arg == "--save-cel") {
                settings.save_cel = value;
            } else {
                std::fprintf(stderr, "unknown argument %s\n", arg.c_str());
                return false;
            }
            if (!status.is_ok()) {
                std::fprintf(stderr, "%s\n", status.message().c_str());
                return false;
            }
            return true;
        });
}

}  // namespace

int main(int argc, char** argv) {
    Settings settings;
    // parse_counts reads argv[2] onward; shift so that the counts are the first arguments.
    std::vector<char*> args{argv[0], argv[0]};
    args.insert(args.end(), argv + 1, argv + argc);
    const int first = bench::parse_counts(static_cast<int>(args.size()), args.data(),
                                          settings.threads, settings.repeats);
    if (!parse_options(static_cast<int>(args.size()), args.data(), first, settings)) return 2;

    auto medium = load_image(settings.medium);
    if (!medium.ok()) {
        std::fprintf(stderr, "%s\n", medium.status().message().c_str());
        return 1;
    }
    const Image reference = cel(settings.width, settings.height);
    if (!settings.save_cel.empty()) {
        const Status saved = save_image(reference, settings.save_cel);
        if (!saved.is_ok()) std::fprintf(stderr, "%s\n", saved.message().c_str());
    }
    const std::vector<double> strengths =
        level_strengths(settings.options.noise, settings.options.level_ratio);
    const double mpix = static_cast<double>(settings.width) * settings.height / 1e6;

    const Image reference_low = low_pass(reference, settings.options.noise, LowPassFilter::Box);
    const double contrast =
        testing::rms_difference(reference_low, testing::uniform_like(reference_low));
    const double medium_detail = gradient_energy(*medium);
    std::vector<Image> frames;
    for (int r = 0; r < settings.repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        auto seconds = [&] {
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        };
        const double c0 = bench::cpu_seconds();
        std::vector<double> level_wall, level_cpu;
        RunContext context(settings.threads);
        context.progress = [&](const ProgressEvent& e) {
            if (e.stage != "level") return;
            level_wall.push_back(seconds());
            level_cpu.push_back(bench::cpu_seconds() - c0);
        };
        auto frame = synthesize_frame(*medium, NoisyFrame{reference, {}, {}, {}}, settings.options,
                                      settings.frame + r, context);
        const double wall = seconds(), cpu = bench::cpu_seconds() - c0;
        if (!frame.ok()) {
            std::fprintf(stderr, "%s\n", frame.status().message().c_str());
            return 1;
        }
        std::printf(
            "noisy %dx%d (%.2f MPix) from %dx%d, f = %g, %zu levels, threads=%d, frame %lld: "
            "%.2f s wall, %.2f s cpu (%.2f cpu-s per MPix)\n",
            settings.width, settings.height, mpix, medium->width(), medium->height(),
            settings.options.noise, strengths.size(), settings.threads,
            static_cast<long long>(settings.frame + r), wall, cpu, cpu / mpix);
        double prev_wall = 0.0, prev_cpu = 0.0;
        for (std::size_t k = 0; k < level_wall.size() && k < strengths.size(); ++k) {
            const double f = strengths[k];
            std::printf("  level %2zu  f %5.2f  %4dx%-4d  %6.2f s wall  %6.2f s cpu\n", k, f,
                        std::max(1, static_cast<int>(std::lround(settings.width / f))),
                        std::max(1, static_cast<int>(std::lround(settings.height / f))),
                        level_wall[k] - prev_wall, level_cpu[k] - prev_cpu);
            prev_wall = level_wall[k];
            prev_cpu = level_cpu[k];
        }
        const double coarse =
            testing::rms_difference(low_pass(*frame, settings.options.noise, LowPassFilter::Box),
                                    reference_low) /
            contrast;
        std::printf("  low-pass distance %.3f of the contrast, detail %.3f of the medium's\n",
                    coarse, gradient_energy(*frame) / medium_detail);
        std::fflush(stdout);
        frames.push_back(std::move(frame).value());
    }
    if (frames.size() > 1) {
        std::printf("temporal energy over %zu frames: %.3e\n", frames.size(),
                    testing::temporal_energy(frames));
    }
    if (!settings.out.empty()) {
        const Status saved = save_image(frames.back(), settings.out);
        if (!saved.is_ok()) std::fprintf(stderr, "%s\n", saved.message().c_str());
    }
    return 0;
}
