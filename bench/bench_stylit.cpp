// End-to-end timing of `exemplar stylit` (stylize_render) on the StyLit data in ../shared/data
// at 1200x912: full quality and preview (half resolution, PCA buffers). Loading is not timed.
//
// Usage: bench_stylit [full|preview|all] [threads] [repeats] [options...]
//        bench_stylit compare A.png B.png [blur]   (compare_preview of A against B)
//   --set NAME=VALUE   an engine option (see `exemplar stylize --help`) on top of the mode's
//                      defaults (the preview's are preview_synthesis_options of the full ones)
//   --usage NAME       patch-usage strategy of both modes
//   --out PREFIX       save PREFIX-full.png / PREFIX-preview.png
//   --components N     principal components the preview keeps (default 5)
//   --compare FILE     full-quality result to compare the preview with (default: this run's)
// Prints per run the wall time and the time at the end of every level; for the preview also
// compare_preview against the full result (colour difference at 1/4 of the preview's size and
// texture ratio).
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/stylit/preview.hpp"
#include "exemplar/stylit/stylit.hpp"
#include "shared_data.hpp"

using namespace exemplar;

namespace {

struct Settings {
    int threads = 2;
    int repeats = 1;
    std::vector<std::pair<const OptionSpec*, double>> overrides;
    std::optional<UsageStrategy> usage;
    std::string out;
    std::string compare;
    int components = StylitOptions{}.preview_components;
};

struct Data {
    Image exemplar;
    std::vector<LpeBuffer> source, target;
};

Status apply(const Settings& settings, SynthesisOptions& options) {
    if (settings.usage) options.usage = *settings.usage;
    for (const auto& [spec, value] : settings.overrides)
        EXEMPLAR_RETURN_IF_ERROR(set_option(options, *spec, value));
    return Status::ok();
}

// Runs one mode `repeats` times; returns the last result's image (empty on failure).
Image run(bool preview, const Data& data, const Settings& settings, const Image& full) {
    StylitOptions options;
    options.preview = preview;
    options.preview_components = settings.components;
    SynthesisOptions& engine =
        preview ? options.preview_synthesis.emplace(preview_synthesis_options(options.synthesis))
                : options.synthesis;
    const Status applied = apply(settings, engine);
    if (!applied.is_ok()) {
        std::fprintf(stderr, "%s\n", applied.message().c_str());
        return {};
    }
    Image last;
    for (int r = 0; r < settings.repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = bench::cpu_seconds();
        auto seconds = [&] {
            return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        };
        RunContext context(settings.threads);
        std::vector<double> level_end;
        context.progress = [&](const ProgressEvent& e) {
            if (e.iteration + 1 == e.iterations) level_end.push_back(seconds());
        };
        auto result = stylize_render(data.exemplar, data.source, data.target, options, context);
        const double secs = seconds();
        const double cpu = bench::cpu_seconds() - c0;
        if (!result.ok()) {
            std::fprintf(stderr, "%s\n", result.status().message().c_str());
            return {};
        }
        std::printf("%-15s %dx%d -> %dx%d threads=%d guide channels=%d  %.2f s (cpu %.2f s)\n",
                    preview ? "stylit-preview" : "stylit", data.exemplar.width(),
                    data.exemplar.height(), result->synthesis.image.width(),
                    result->synthesis.image.height(), settings.threads, result->guide_channels,
                    secs, cpu);
        std::printf("  time at the end of each level (and of the final 3x3 pass, if on):");
        for (double t : level_end) std::printf(" %.2f", t);
        std::printf("\n");
        last = std::move(result->synthesis.image);
    }
    if (preview && !full.empty()) {
        auto similarity = compare_preview(last, full, 4, settings.threads);
        if (similarity.ok()) {
            std::printf("  vs full: colour difference %.4f, texture ratio %.3f\n",
                        similarity->colour_difference, similarity->texture_ratio);
        }
    }
    std::fflush(stdout);
    if (!settings.out.empty()) {
        const Status saved =
            save_image(last, settings.out + (preview ? "-preview.png" : "-full.png"));
        if (!saved.is_ok()) std::fprintf(stderr, "%s\n", saved.message().c_str());
    }
    return last;
}

bool parse_options(int argc, char** argv, int first, Settings& settings) {
    return bench::for_each_flag(argc, argv, first,
                                [&](const std::string& arg, const std::string& value) {
                                    if (arg == "--out") {
                                        settings.out = value;
                                    } else if (arg == "--components") {
                                        settings.components = std::stoi(value);
                                    } else if (arg == "--compare") {
                                        settings.compare = value;
                                    } else if (arg == "--usage") {
                                        UsageStrategy usage{};
                                        if (!bench::parse_usage(value, usage)) return false;
                                        settings.usage = usage;
                                    } else if (arg == "--set") {
                                        const auto set = bench::parse_set(value);
                                        if (set.first == nullptr) return false;
                                        settings.overrides.push_back(set);
                                    } else {
                                        std::fprintf(stderr, "unknown argument %s\n", arg.c_str());
                                        return false;
                                    }
                                    return true;
                                });
}

}  // namespace

// Prints compare_preview(a, b, blur): how two results differ (b may be larger).
int compare_files(const std::string& a, const std::string& b, int blur) {
    auto first = load_image(a);
    auto second = load_image(b);
    if (!first.ok() || !second.ok()) {
        std::fprintf(stderr, "%s\n",
                     (first.ok() ? second.status() : first.status()).message().c_str());
        return 1;
    }
    auto similarity = compare_preview(*first, *second, blur);
    if (!similarity.ok()) {
        std::fprintf(stderr, "%s\n", similarity.status().message().c_str());
        return 1;
    }
    std::printf("%s vs %s: colour difference %.4f, texture ratio %.3f\n", a.c_str(), b.c_str(),
                similarity->colour_difference, similarity->texture_ratio);
    return 0;
}

int main(int argc, char** argv) {
    const std::string which = argc > 1 ? argv[1] : "all";
    if (which == "compare" && argc >= 4)
        return compare_files(argv[2], argv[3], argc > 4 ? std::stoi(argv[4]) : 4);
    Settings settings;
    const int first_option = bench::parse_counts(argc, argv, settings.threads, settings.repeats);
    if (!parse_options(argc, argv, first_option, settings)) return 2;

    const std::string dir = bench::shared_data("guided/ebsynth/stylit/");
    if (!bench::shared_data_present(dir)) return 1;
    Data data;
    auto exemplar = load_image(dir + "source_style.png");
    if (!exemplar.ok()) {
        std::fprintf(stderr, "%s\n", exemplar.status().message().c_str());
        return 1;
    }
    data.exemplar = std::move(exemplar).value();
    const auto preset = find_layer_preset("exemplar");
    std::vector<std::string> source_files, target_files;
    for (const char* name : {"fullgi", "dirdif", "dirspc", "indirb"}) {
        source_files.push_back(dir + "source_" + name + ".png");
        target_files.push_back(dir + "target_" + name + ".png");
    }
    auto source = load_lpe_buffers(source_files, *preset);
    auto target = load_lpe_buffers(target_files, *preset);
    if (!source.ok() || !target.ok()) {
        std::fprintf(stderr, "%s\n",
                     (source.ok() ? target.status() : source.status()).message().c_str());
        return 1;
    }
    data.source = std::move(source).value();
    data.target = std::move(target).value();

    Image full;
    if (!settings.compare.empty()) {
        auto loaded = load_image(settings.compare);
        if (!loaded.ok()) {
            std::fprintf(stderr, "%s\n", loaded.status().message().c_str());
            return 1;
        }
        full = std::move(loaded).value();
    }
    if (which == "all" || which == "full") {
        Image result = run(false, data, settings, {});
        if (result.empty()) return 1;
        if (full.empty()) full = std::move(result);
    }
    if ((which == "all" || which == "preview") && run(true, data, settings, full).empty()) return 1;
    return 0;
}
