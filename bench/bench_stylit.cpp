// End-to-end timing of `exemplar stylit` (stylize_render) on the StyLit data in ../shared/data
// at 1200x912: full quality and preview (half resolution, PCA buffers). Loading is not timed.
// Usage: bench_stylit [full|preview|all] [threads] [repeats]
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "exemplar/io/image_io.hpp"
#include "exemplar/stylit/stylit.hpp"

using namespace exemplar;

namespace {

int run(bool preview, const Image& exemplar, const std::vector<LpeBuffer>& source,
        const std::vector<LpeBuffer>& target, int threads, int repeats) {
    StylitOptions options;
    options.preview = preview;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        auto result = stylize_render(exemplar, source, target, options, RunContext(threads));
        const double secs =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (!result.ok()) {
            std::fprintf(stderr, "%s\n", result.status().message().c_str());
            return 1;
        }
        std::printf("%-15s %dx%d -> %dx%d threads=%d guide channels=%d  %.2f s\n",
                    preview ? "stylit-preview" : "stylit", exemplar.width(), exemplar.height(),
                    result->synthesis.image.width(), result->synthesis.image.height(), threads,
                    result->guide_channels, secs);
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string which = argc > 1 ? argv[1] : "all";
    const int threads = argc > 2 ? std::stoi(argv[2]) : 2;
    const int repeats = argc > 3 ? std::stoi(argv[3]) : 1;
    const std::string dir = std::string(EXEMPLAR_SHARED_DATA_DIR) + "/guided/ebsynth/stylit/";
    auto exemplar = load_image(dir + "source_style.png");
    if (!exemplar.ok()) {
        std::fprintf(stderr, "%s\n", exemplar.status().message().c_str());
        return 1;
    }
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
    int rc = 0;
    if (which == "all" || which == "full")
        rc |= run(false, *exemplar, *source, *target, threads, repeats);
    if (which == "all" || which == "preview")
        rc |= run(true, *exemplar, *source, *target, threads, repeats);
    return rc;
}
