// End-to-end timing of `synthesize` on the ebsynth examples in ../shared/data (the issue's
// reference workloads). Usage: bench_examples [stylit|facestyle|all] [threads] [repeats]
// Prints one line per run: example, size, threads, seconds, strategy.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/synthesize.hpp"

using namespace exemplar;

namespace {

struct GuideFiles {
    const char* source;
    const char* target;
    float weight;
};

int run(const std::string& name, const char* style, const std::vector<GuideFiles>& guides,
        int threads, int repeats) {
    const std::string dir = std::string(EXEMPLAR_SHARED_DATA_DIR) + "/guided/ebsynth/" + name + "/";
    SynthesisInput in;
    auto s = load_image(dir + style);
    if (!s.ok()) {
        std::fprintf(stderr, "%s\n", s.status().message().c_str());
        return 1;
    }
    in.style = std::move(s).value();
    for (const GuideFiles& g : guides) {
        auto a = load_image(dir + g.source);
        auto b = load_image(dir + g.target);
        if (!a.ok() || !b.ok()) {
            std::fprintf(stderr, "cannot load %s\n", g.source);
            return 1;
        }
        in.guides.push_back(
            GuidePair{g.source, std::move(a).value(), std::move(b).value(), g.weight, {}});
    }
    SynthesisOptions opt;
    for (int r = 0; r < repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        RunContext context(threads);
        // Per-level wall time, printed after the run: where the time goes.
        std::vector<double> level_end;
        context.progress = [&](const ProgressEvent& e) {
            if (e.iteration + 1 != e.iterations) return;
            level_end.push_back(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        };
        auto result = synthesize(in, opt, context);
        const double secs =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (!result.ok()) {
            std::fprintf(stderr, "%s\n", result.status().message().c_str());
            return 1;
        }
        std::printf("%-10s %dx%d threads=%d usage=%s  %.2f s\n", name.c_str(),
                    result->image.width(), result->image.height(), threads,
                    std::string(to_string(opt.usage)).c_str(), secs);
        std::printf("  time at the end of each level (last: final 3x3 pass):");
        for (double t : level_end) std::printf(" %.2f", t);
        std::printf("\n");
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string which = argc > 1 ? argv[1] : "all";
    const int threads = argc > 2 ? std::stoi(argv[2]) : 2;
    const int repeats = argc > 3 ? std::stoi(argv[3]) : 1;
    int rc = 0;
    if (which == "all" || which == "stylit") {
        rc |= run("stylit", "source_style.png",
                  {{"source_fullgi.png", "target_fullgi.png", 0.5f},
                   {"source_dirdif.png", "target_dirdif.png", 0.5f},
                   {"source_dirspc.png", "target_dirspc.png", 0.5f},
                   {"source_indirb.png", "target_indirb.png", 0.5f}},
                  threads, repeats);
    }
    if (which == "all" || which == "facestyle") {
        rc |= run("facestyle", "source_painting.png",
                  {{"source_Gapp.png", "target_Gapp.png", 0.5f},
                   {"source_Gseg.png", "target_Gseg.png", 1.5f},
                   {"source_Gpos.png", "target_Gpos.png", 10.0f}},
                  threads, repeats);
    }
    return rc;
}
