// End-to-end timing and quality of `synthesize` on the ebsynth examples in ../shared/data (the
// issue's reference workloads).
//
// Usage: bench_examples [stylit|facestyle|texbynum|guided2|inpaint3|all] [threads] [repeats]
//                       [options...]
//   --scale S          resize inputs by S first (0.5 = the bundled half-resolution job)
//   --quality NAME     start from SynthesisOptions::preset (fast, default, best); --usage and
//                      --set apply over it, whatever the order
//   --usage NAME       patch-usage strategy (none, uniform, error-budget, occurrence)
//   --set NAME=VALUE   any numeric synthesis option (see `exemplar stylize --help`)
//   --out FILE         save the result (to look at it)
//   --fidelity         also print the output's patch fidelity (see patch_fidelity; a few seconds)
//   --measure FILE     print texture kept and patch fidelity of FILE (e.g. another tool's output
//                      for the same example) instead of synthesizing
//   --fidelity-map F   with --fidelity or --measure: save the per-pixel fidelity map to F (red:
//                      the distance, ×4; green: seams of the final NNF; blue: a 2 px band around
//                      the first guide's region edges) and print where the distance sits
//   --write-guides DIR inpaint3: write the guides of ebsynth's formulation (bench/vs_ebsynth.sh)
//                      instead of synthesizing: DIR/inpaint3_filled.png (3.jpg with the hole at
//                      the known pixels' mean colour, the start of inpainting_input),
//                      DIR/inpaint3_hole.png (1 in the hole) and DIR/inpaint3_none.png (all 0)
// Prints per run: wall and CPU seconds, the time at the end of every level, the texture kept
// (output / exemplar luminance gradient energy; plain averaging washes out to ~0.6) and the mean
// final patch error (the synthesis energy per pixel of the final NNF, whose patch size depends
// on the options; lower = closer to the exemplar).
//
// inpaint3 (EmbarkStudios/texture-synthesis imgs/3.jpg, birch bark with a red "Z" painted over
// it, and imgs/masks/3_inpaint.jpg, black over the Z) fills the Z's hole from the rest of the
// image (inpainting_input). Its exemplar is the known region only: texture kept is the hole's
// gradient energy over the known region's, fidelity the mean over the hole of the distance to
// the nearest patch entirely inside the known region (the Z is no exemplar), and "outside" the
// largest difference (of 255) from 3.jpg outside the hole (0: kept byte for byte).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "exemplar/filters/measures.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/inpaint.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "shared_data.hpp"

using namespace exemplar;

namespace {

struct GuideFiles {
    const char* source;
    const char* target;
    float weight;
};

struct Settings {
    int threads = 2;
    int repeats = 1;
    double scale = 1.0;
    SynthesisOptions options;
    std::string out;
    bool fidelity = false;     // also measure the output's patch fidelity (slower)
    std::string measure;       // measure this image instead of synthesizing
    std::string guides;        // inpaint3: write ebsynth's guides into this folder instead
    std::string fidelity_map;  // save the per-pixel fidelity map here
    float smooth_sigma = 8.0f;
};

// Patch fidelity: the mean distance of the output's 5x5 patches (style channels only) to their
// nearest exemplar patches, found by a plain nearest-neighbour synthesis with the output as the
// only guide. Wash-out (blurred patches) and seams (patches found nowhere in the exemplar) both
// raise it; a copy of exemplar regions scores 0. With `known` (inpainting; 1 channel, 1 = known):
// only patches entirely inside it are the exemplar's, and the mean is taken over the hole
// (known = 0) alone. `map` (if given) receives the per-pixel distances.
double patch_fidelity(const Image& exemplar, const Image& output, int threads,
                      const Image& known = {}, Image* map = nullptr) {
    SynthesisInput in;
    in.style = exemplar;
    in.source_mask = known;
    in.guides.push_back(GuidePair{"exemplar", exemplar, output, 1.0f, {}});
    SynthesisOptions o;
    o.usage = UsageStrategy::None;
    o.style_weight = 0.0f;
    o.em_iterations = 1;
    o.finest_em_iterations = 1;
    o.final_pass_iterations = 0;
    o.search_iterations = 6;
    o.warm_search_iterations = 6;
    RunContext context(threads);
    auto r = synthesize(in, o, context);
    if (!r.ok()) return -1.0;
    if (map != nullptr) *map = r->error;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < r->error.pixel_count(); ++i) {
        if (!known.empty() && known.data()[i] > 0.5f) continue;
        sum += r->error.data()[i];
        ++count;
    }
    return sum / static_cast<double>(std::max<std::size_t>(1, count));
}

// The known pixels' colours spread smoothly over the whole image: a normalized convolution,
// blur(image x known) / blur(known), Gaussian of `sigma` pixels.
Image smooth_fill(const Image& image, const Image& known, float sigma) {
    Image weighted = image;
    const auto channels = static_cast<std::size_t>(image.channels());
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        for (std::size_t c = 0; c < channels; ++c)
            weighted.data()[i * channels + c] *= known.data()[i];
    }
    weighted = gaussian_blur(weighted, sigma);
    const Image weight = gaussian_blur(known, sigma);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const float w = std::max(weight.data()[i], 1e-6f);
        for (std::size_t c = 0; c < channels; ++c) weighted.data()[i * channels + c] /= w;
    }
    return weighted;
}

// An example's input and how to judge its outputs.
struct Example {
    SynthesisInput input;
    Image known;  // inpainting: 1 = known (kept, the exemplar), 0 = the hole; else empty
    Image hole;   // inpainting: 1 - known
};

// Texture kept and patch fidelity; inpainting: of the output pasted into the hole of the
// original (what a user of a tool that redraws everything would keep; the same image when the
// outside is kept), and the largest and mean change outside the hole (in 255ths) before that.
std::string quality(const Example& e, const Image& output, int threads, Image* map = nullptr) {
    const Image& style = e.input.style;
    Image pasted = output;
    double outside = 0.0, outside_sum = 0.0;
    if (!e.known.empty()) {
        const auto channels = static_cast<std::size_t>(style.channels());
        for (std::size_t i = 0; i < style.pixel_count(); ++i) {
            if (e.known.data()[i] <= 0.5f) continue;
            for (std::size_t c = 0; c < channels; ++c) {
                const std::size_t k = i * channels + c;
                const double d = 255.0 * std::abs(static_cast<double>(output.data()[k]) -
                                                  static_cast<double>(style.data()[k]));
                outside = std::max(outside, d);
                outside_sum += d / static_cast<double>(channels);
                pasted.data()[k] = style.data()[k];
            }
        }
    }
    char text[160];
    std::snprintf(text, sizeof text, "texture %.3f  fidelity %.4f",
                  gradient_energy(pasted, e.hole) / gradient_energy(style, e.known),
                  patch_fidelity(style, pasted, threads, e.known, map));
    std::string out = text;
    if (!e.known.empty()) {
        double known_pixels = 0.0;
        for (float k : e.known.data()) known_pixels += k;
        std::snprintf(text, sizeof text, "  outside %.0f max %.2f mean", outside,
                      outside_sum / known_pixels);
        out += text;
    }
    return out;
}

// Where the fidelity distance sits: each pixel's category (seam of `nnf` or within 2 px of one,
// if given; within 2 px of an edge of `regions`), its share of the mean and its own mean. Saves
// the map with the categories to `path`.
void fidelity_map(const Image& map, const Image& regions, const Nnf* nnf, const std::string& path) {
    const int w = map.width(), h = map.height();
    auto near = [&](auto&& is_edge) {
        std::vector<std::uint8_t> edge(map.pixel_count(), 0), band(map.pixel_count(), 0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) edge[static_cast<std::size_t>(y) * w + x] = is_edge(x, y);
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                for (int dy = -2; dy <= 2; ++dy) {
                    for (int dx = -2; dx <= 2; ++dx) {
                        const int qx = x + dx, qy = y + dy;
                        if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                        if (edge[static_cast<std::size_t>(qy) * w + qx])
                            band[static_cast<std::size_t>(y) * w + x] = 1;
                    }
                }
            }
        }
        return std::pair{edge, band};
    };
    const auto [region_edge, region_band] = near([&](int x, int y) {
        const float* p = regions.pixel(x, y);
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const float* q = regions.pixel(qx, qy);
            for (int c = 0; c < regions.channels(); ++c)
                if (std::abs(p[c] - q[c]) > 0.1f) return true;
        }
        return false;
    });
    const auto [seam, seam_band] = near([&](int x, int y) {
        if (nnf == nullptr) return false;
        const Match& m = nnf->at(x, y);
        if (m.x < 0) return false;
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const Match& q = nnf->at(qx, qy);
            if (q.x >= 0 && (q.x != m.x + dx || q.y != m.y + dy)) return true;
        }
        return false;
    });
    // Categories: seam / near a seam / inside a piece, each by region edge band or not.
    const char* names[6] = {"seam, region edge",        "seam, inside a region",
                            "near a seam, region edge", "near a seam, inside a region",
                            "in a piece, region edge",  "in a piece, inside a region"};
    double sum[6] = {}, count[6] = {}, total = 0.0;
    Image out(w, h, 3);
    for (std::size_t i = 0; i < map.pixel_count(); ++i) {
        const int k = (seam[i] ? 0 : seam_band[i] ? 2 : 4) + (region_band[i] ? 0 : 1);
        const double e = map.data()[i];
        sum[k] += e;
        count[k] += 1.0;
        total += e;
        out.data()[i * 3] = std::min(1.0f, map.data()[i] * 4.0f);
        out.data()[i * 3 + 1] = seam[i] ? 0.5f : 0.0f;
        out.data()[i * 3 + 2] = region_edge[i] ? 0.5f : 0.0f;
    }
    const double n = static_cast<double>(map.pixel_count());
    for (int k = 0; k < 6; ++k) {
        if (count[k] == 0.0) continue;
        std::printf("  %-30s %5.1f%% of pixels  %.4f of the mean (%4.1f%%)  own mean %.4f\n",
                    names[k], 100.0 * count[k] / n, sum[k] / n, 100.0 * sum[k] / total,
                    sum[k] / count[k]);
    }
    // Per region, by the first guide's strongest channel (texbynum: sea, rock, sky).
    const int nc = std::min(3, regions.channels());
    std::vector<double> region_sum(nc, 0.0), region_seam(nc, 0.0), region_count(nc, 0.0);
    // Per region and place (seam, near a seam, in a piece): pixels and summed distance.
    std::vector<std::array<double, 3>> place_count(nc), place_sum(nc);
    for (std::size_t i = 0; i < map.pixel_count(); ++i) {
        const float* p = regions.pixel(static_cast<int>(i % w), static_cast<int>(i / w));
        const int r = static_cast<int>(std::max_element(p, p + nc) - p);
        region_sum[r] += map.data()[i];
        region_seam[r] += seam[i] ? 1.0 : 0.0;
        region_count[r] += 1.0;
        const int place = seam[i] ? 0 : seam_band[i] ? 1 : 2;
        place_count[r][place] += 1.0;
        place_sum[r][place] += map.data()[i];
    }
    for (int r = 0; r < nc; ++r) {
        if (region_count[r] == 0.0) continue;
        std::printf(
            "  guide channel %d strongest: %5.1f%% of pixels, %4.1f%% seams, %.4f of the "
            "mean, own mean %.4f\n",
            r, 100.0 * region_count[r] / n, 100.0 * region_seam[r] / region_count[r],
            region_sum[r] / n, region_sum[r] / region_count[r]);
        if (nnf == nullptr) continue;
        std::printf(
            "    seam / near a seam / in a piece: %4.1f / %4.1f / %4.1f%% of its pixels, "
            "own mean %.4f / %.4f / %.4f\n",
            100.0 * place_count[r][0] / region_count[r],
            100.0 * place_count[r][1] / region_count[r],
            100.0 * place_count[r][2] / region_count[r],
            place_sum[r][0] / std::max(1.0, place_count[r][0]),
            place_sum[r][1] / std::max(1.0, place_count[r][1]),
            place_sum[r][2] / std::max(1.0, place_count[r][2]));
    }
    const Status saved = save_image(out, path);
    if (!saved.is_ok()) std::fprintf(stderr, "%s\n", saved.message().c_str());
}

bool load(const std::string& path, double scale, Image& out) {
    auto image = load_image(path);
    if (!image.ok()) {
        std::fprintf(stderr, "%s\n", image.status().message().c_str());
        return false;
    }
    out = std::move(image).value();
    if (scale != 1.0) {
        out = resize(out, static_cast<int>(std::lround(out.width() * scale)),
                     static_cast<int>(std::lround(out.height() * scale)), ResampleFilter::Lanczos3,
                     0);
    }
    return true;
}

// The example's files under ../shared/data/guided/`folder`/ (default ebsynth/<name>/).
bool load_guided(const std::string& name, const char* style, const std::vector<GuideFiles>& guides,
                 const Settings& settings, Example& e, const std::string& folder = "") {
    const std::string dir =
        bench::shared_data("guided/" + (folder.empty() ? "ebsynth/" + name : folder) + "/");
    if (!bench::shared_data_present(dir)) return false;
    SynthesisInput& in = e.input;
    if (!load(dir + style, settings.scale, in.style)) return false;
    for (const GuideFiles& g : guides) {
        GuidePair pair{g.source, {}, {}, g.weight, {}};
        if (!load(dir + g.source, settings.scale, pair.source) ||
            !load(dir + g.target, settings.scale, pair.target)) {
            return false;
        }
        in.guides.push_back(std::move(pair));
    }
    return true;
}

// Inpainting: `image` with its hole where `mask` is black, under guided/texture-synthesis/.
bool load_inpainting(const char* image, const char* mask, const Settings& settings, Example& e) {
    const std::string dir = bench::shared_data("guided/texture-synthesis/");
    if (!bench::shared_data_present(dir)) return false;
    Image picture, drawn;
    if (!load(dir + image, settings.scale, picture) || !load(dir + mask, settings.scale, drawn)) {
        return false;
    }
    auto known = inpainting_known(drawn, dir + mask);
    auto input =
        known.ok() ? inpainting_input(picture, *known) : Result<SynthesisInput>(known.status());
    if (!input.ok()) {
        std::fprintf(stderr, "%s\n", input.status().message().c_str());
        return false;
    }
    e.input = std::move(input).value();
    e.known = std::move(known).value();
    e.hole = e.input.target_mask;
    return true;
}

int run(const std::string& name, const Example& example, const Settings& settings) {
    const SynthesisInput& in = example.input;
    if (!settings.guides.empty()) {
        if (example.known.empty()) return 0;  // only the inpainting example has them
        const std::string stem = settings.guides + "/" + name + "_";
        const Image smooth = smooth_fill(in.style, example.known, settings.smooth_sigma);
        for (const auto& [file, image] : {std::pair{"filled.png", &in.initial_target},
                                          {"smooth.png", &smooth},
                                          {"hole.png", &in.target_mask},
                                          {"none.png", nullptr}}) {
            const Status saved = save_image(
                image != nullptr ? *image : Image(in.style.width(), in.style.height(), 1, 0.0f),
                stem + file);
            if (!saved.is_ok()) {
                std::fprintf(stderr, "%s\n", saved.message().c_str());
                return 1;
            }
        }
        return 0;
    }
    if (!settings.measure.empty()) {
        auto image = load_image(settings.measure);
        if (!image.ok()) {
            std::fprintf(stderr, "%s\n", image.status().message().c_str());
            return 1;
        }
        Image map;
        std::printf("%-10s %s  %s\n", name.c_str(), settings.measure.c_str(),
                    quality(example, *image, settings.threads, &map).c_str());
        if (!settings.fidelity_map.empty())
            fidelity_map(map, in.guides.front().target, nullptr, settings.fidelity_map);
        return 0;
    }
    for (int r = 0; r < settings.repeats; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = bench::cpu_seconds();
        RunContext context(settings.threads);
        // Per-level wall time, printed after the run: where the time goes.
        std::vector<double> level_end;
        context.progress = [&](const ProgressEvent& e) {
            if (e.iteration + 1 != e.iterations) return;
            level_end.push_back(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        };
        auto result = synthesize(in, settings.options, context);
        const double secs =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double cpu = bench::cpu_seconds() - c0;
        if (!result.ok()) {
            std::fprintf(stderr, "%s\n", result.status().message().c_str());
            return 1;
        }
        // Distinct source patches used per target patch: repetition (1 = no patch reused).
        std::vector<std::uint8_t> used(static_cast<std::size_t>(in.style.width()) *
                                           static_cast<std::size_t>(in.style.height()),
                                       0);
        std::size_t centres = 0, distinct = 0;
        for (const Match& m : result->nnf.matches()) {
            if (m.x < 0) continue;
            ++centres;
            std::uint8_t& u = used[static_cast<std::size_t>(m.y) * in.style.width() + m.x];
            distinct += u == 0 ? 1 : 0;
            u = 1;
        }
        double error_sum = 0.0;
        for (float e : result->error.data()) error_sum += e;
        std::printf(
            "%-10s %dx%d threads=%d usage=%s  %.2f s (cpu %.2f s)  texture %.3f  "
            "mean error %.4f  distinct %.3f\n",
            name.c_str(), result->image.width(), result->image.height(), settings.threads,
            std::string(to_string(settings.options.usage)).c_str(), secs, cpu,
            gradient_energy(result->image, example.hole) / gradient_energy(in.style, example.known),
            error_sum / static_cast<double>(result->error.pixel_count()),
            static_cast<double>(distinct) / static_cast<double>(std::max<std::size_t>(1, centres)));
        if (settings.fidelity) {
            Image map;
            std::printf("  %s\n", quality(example, result->image, settings.threads, &map).c_str());
            if (!settings.fidelity_map.empty()) {
                fidelity_map(map, in.guides.front().target, &result->nnf, settings.fidelity_map);
            }
        }
        std::printf("  time at the end of each level (and of the final 3x3 pass, if on):");
        for (double t : level_end) std::printf(" %.2f", t);
        std::printf("\n");
        std::fflush(stdout);
        if (!settings.out.empty()) {
            const Status saved = save_image(result->image, settings.out);
            if (!saved.is_ok()) std::fprintf(stderr, "%s\n", saved.message().c_str());
        }
    }
    return 0;
}

bool parse_options(int argc, char** argv, int first, Settings& settings) {
    // The preset first (default when not given), as the CLI does, so that --usage and --set
    // override it in any order.
    settings.options = SynthesisOptions::preset(Quality::Default);
    for (int i = first; i + 1 < argc; ++i) {
        if (std::strcmp(argv[i], "--quality") != 0) continue;
        auto quality = parse_quality(argv[i + 1]);
        if (!quality.ok()) {
            std::fprintf(stderr, "%s\n", quality.status().message().c_str());
            return false;
        }
        settings.options = SynthesisOptions::preset(*quality);
    }
    for (int i = first; i < argc; ++i) {
        const std::string arg = argv[i];
        const bool has_value = i + 1 < argc;
        if (arg == "--quality" && has_value) {
            ++i;  // applied above
        } else if (arg == "--scale" && has_value) {
            settings.scale = std::stod(argv[++i]);
        } else if (arg == "--out" && has_value) {
            settings.out = argv[++i];
        } else if (arg == "--fidelity") {
            settings.fidelity = true;
        } else if (arg == "--fidelity-map" && has_value) {
            settings.fidelity_map = argv[++i];
        } else if (arg == "--measure" && has_value) {
            settings.measure = argv[++i];
        } else if (arg == "--write-guides" && has_value) {
            settings.guides = argv[++i];
        } else if (arg == "--smooth-sigma" && has_value) {
            settings.smooth_sigma = std::stof(argv[++i]);
        } else if (arg == "--usage" && has_value) {
            if (!bench::parse_usage(argv[++i], settings.options.usage)) return false;
        } else if (arg == "--set" && has_value) {
            const auto [spec, value] = bench::parse_set(argv[++i]);
            if (spec == nullptr) return false;
            const Status set = set_option(settings.options, *spec, value);
            if (!set.is_ok()) {
                std::fprintf(stderr, "%s\n", set.message().c_str());
                return false;
            }
        } else {
            std::fprintf(stderr, "unknown argument %s\n", arg.c_str());
            return false;
        }
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string which = argc > 1 ? argv[1] : "all";
    Settings settings;
    const int first_option = bench::parse_counts(argc, argv, settings.threads, settings.repeats);
    if (!parse_options(argc, argv, first_option, settings)) return 2;
    int rc = 0;
    const auto want = [&](const char* name) { return which == "all" || which == name; };
    Example e;
    if (want("stylit")) {
        rc |= !load_guided("stylit", "source_style.png",
                           {{"source_fullgi.png", "target_fullgi.png", 0.5f},
                            {"source_dirdif.png", "target_dirdif.png", 0.5f},
                            {"source_dirspc.png", "target_dirspc.png", 0.5f},
                            {"source_indirb.png", "target_indirb.png", 0.5f}},
                           settings, e = {}) ||
              run("stylit", e, settings);
    }
    if (want("facestyle")) {
        rc |= !load_guided("facestyle", "source_painting.png",
                           {{"source_Gapp.png", "target_Gapp.png", 0.5f},
                            {"source_Gseg.png", "target_Gseg.png", 1.5f},
                            {"source_Gpos.png", "target_Gpos.png", 10.0f}},
                           settings, e = {}) ||
              run("facestyle", e, settings);
    }
    // Guided texture synthesis (EmbarkStudios/texture-synthesis, imgs/2.jpg): the example's
    // mask guides where the target's should go.
    if (want("guided2")) {
        rc |=
            !load_guided("guided2", "2.jpg", {{"masks/2_example.jpg", "masks/2_target.jpg", 1.0f}},
                         settings, e = {}, "texture-synthesis") ||
            run("guided2", e, settings);
    }
    if (want("texbynum")) {
        rc |=
            !load_guided("texbynum", "source_photo.png",
                         {{"source_segment.png", "target_segment.png", 1.0f}}, settings, e = {}) ||
            run("texbynum", e, settings);
    }
    if (want("inpaint3")) {
        rc |= !load_inpainting("3.jpg", "masks/3_inpaint.jpg", settings, e = {}) ||
              run("inpaint3", e, settings);
    }
    return rc;
}
