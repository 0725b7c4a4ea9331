// Renders sphere-on-table (or a scene file) and prints, per light buffer, the error against the
// StyLit authors' buffers of the same set-up (examples/stylit/). The numbers of docs/render.md.
//
//   render_calibrate [--scene FILE] [--width 600] [--height 456] [--spp 256] [--threads 0]
//                    [--max-bounces 6] [--save FOLDER] [--regions 1]
//
// --regions 1 also prints, per buffer, the mean sRGB value of ours and theirs over regions of
// the image (by our object ids; "lit"/"shadow" of the table by their dirdif), which tells a
// wrong light intensity (all regions off by one factor) from a wrong sky or albedo.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "calibration.hpp"
#include "exemplar/render/scene.hpp"

namespace {

using namespace exemplar;

// Mean sRGB value (over RGB) of ours and theirs per region; see the header comment.
void print_regions(const render::RenderBuffers& b, const std::string& reference_dir) {
    const int w = b.fullgi.width(), h = b.fullgi.height();
    auto dirdif = load_image(reference_dir + "/source_dirdif.png");
    if (!dirdif.ok()) return;
    const Image ref_dirdif = resize(extract_channels(*dirdif, 0, 3), w, h, ResampleFilter::Box, 1);
    // Sphere: object 1; its top and bottom halves by its bounding rows.
    int top = h, bottom = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (b.object_id.at(x, y, 0) == 1.0f) {
                top = std::min(top, y);
                bottom = std::max(bottom, y);
            }
        }
    }
    const auto region_of = [&](int x, int y) -> int {
        const float id = b.object_id.at(x, y, 0);
        if (id == 1.0f) return y < (top + bottom) / 2 ? 0 : 1;
        if (id == 2.0f) return ref_dirdif.at(x, y, 0) < 0.05f ? 3 : 2;
        if (id == 3.0f) return 4;
        return -1;
    };
    const char* names[5] = {"sphere top", "sphere bottom", "table lit", "table shadow", "wall"};
    const std::vector<std::pair<const Image*, std::string>> pairs = {
        {&b.fullgi, "fullgi"},
        {&b.direct_diffuse, "dirdif"},
        {&b.direct_specular, "dirspc"},
        {&b.indirect_diffuse, "indirb"}};
    // How the StyLit files encode light: with the right decoding, fullgi = dirdif + dirspc +
    // indirb (+ glossy reflections, small off the sphere) wherever nothing is clipped.
    {
        std::vector<Image> refs;
        for (const char* name : {"fullgi", "dirdif", "dirspc", "indirb"}) {
            auto reference = load_image(reference_dir + "/source_" + name + ".png");
            if (!reference.ok()) return;
            refs.push_back(extract_channels(*reference, 0, 3));
        }
        const auto srgb = [](double v) {
            return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
        };
        const auto gamma22 = [](double v) { return std::pow(v, 2.2); };
        const auto identity = [](double v) { return v; };
        const std::vector<std::pair<const char*, std::function<double(double)>>> decodings = {
            {"sRGB", srgb}, {"gamma 2.2", gamma22}, {"none (linear file)", identity}};
        std::printf(
            "\nStyLit files, unclipped pixels off the sphere: mean |fullgi - (dirdif + "
            "dirspc + indirb)| / mean fullgi, decoded as\n");
        for (const auto& [label, decode] : decodings) {
            double diff = 0.0, total = 0.0;
            for (int y = 0; y < refs[0].height(); ++y) {
                for (int x = 0; x < refs[0].width(); ++x) {
                    const int sx = std::min(w - 1, x * w / refs[0].width());
                    const int sy = std::min(h - 1, y * h / refs[0].height());
                    if (b.object_id.at(sx, sy, 0) == 1.0f) continue;
                    for (int c = 0; c < 3; ++c) {
                        if (refs[0].at(x, y, c) >= 0.99f || refs[1].at(x, y, c) >= 0.99f) continue;
                        const double sum = decode(refs[1].at(x, y, c)) +
                                           decode(refs[2].at(x, y, c)) +
                                           decode(refs[3].at(x, y, c));
                        diff += std::abs(decode(refs[0].at(x, y, c)) - sum);
                        total += decode(refs[0].at(x, y, c));
                    }
                }
            }
            std::printf("  %-20s %.4f\n", label, diff / std::max(total, 1e-12));
        }
    }
    std::printf("\nregion means (sRGB, mean of R, G, B), ours / theirs\n%-8s", "buffer");
    for (const char* n : names) std::printf(" %15s", n);
    std::printf("\n");
    for (const auto& [image, name] : pairs) {
        auto reference = load_image(reference_dir + "/source_" + name + ".png");
        if (!reference.ok()) return;
        const Image ref = resize(extract_channels(*reference, 0, 3), w, h, ResampleFilter::Box, 1);
        const Image ours = render::encode_srgb(*image);
        double sum_ours[5] = {}, sum_ref[5] = {};
        int count[5] = {};
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const int r = region_of(x, y);
                if (r < 0) continue;
                for (int c = 0; c < 3; ++c) {
                    sum_ours[r] += ours.at(x, y, c) / 3.0;
                    sum_ref[r] += ref.at(x, y, c) / 3.0;
                }
                ++count[r];
            }
        }
        std::printf("%-8s", name.c_str());
        for (int r = 0; r < 5; ++r) {
            const double n = std::max(count[r], 1);
            std::printf("     %.3f/%.3f", sum_ours[r] / n, sum_ref[r] / n);
        }
        std::printf("\n");
    }
}

}  // namespace

int main(int argc, char** argv) {
    render::RenderOptions options;
    options.samples_per_pixel = 256;
    std::string scene_file, save;
    int threads = 0;
    bool regions = false;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string flag = argv[i], value = argv[i + 1];
        if (flag == "--scene")
            scene_file = value;
        else if (flag == "--width")
            options.width = std::atoi(value.c_str());
        else if (flag == "--height")
            options.height = std::atoi(value.c_str());
        else if (flag == "--spp")
            options.samples_per_pixel = std::atoi(value.c_str());
        else if (flag == "--max-bounces")
            options.max_bounces = std::atoi(value.c_str());
        else if (flag == "--threads")
            threads = std::atoi(value.c_str());
        else if (flag == "--save")
            save = value;
        else if (flag == "--regions")
            regions = value != "0";
        else {
            std::fprintf(stderr, "render_calibrate: unknown flag %s\n", flag.c_str());
            return 2;
        }
    }
    auto scene = scene_file.empty() ? render::builtin_scene("sphere-on-table")
                                    : render::load_scene(scene_file);
    if (!scene.ok()) {
        std::fprintf(stderr, "render_calibrate: %s\n", scene.status().message().c_str());
        return 1;
    }
    auto buffers = render::render(*scene, options, RunContext(threads));
    if (!buffers.ok()) {
        std::fprintf(stderr, "render_calibrate: %s\n", buffers.status().message().c_str());
        return 1;
    }
    if (!save.empty()) {
        const Status saved =
            render::save_buffers_to_folder(*buffers, save, render::BufferFileFormat::Png);
        if (!saved.is_ok()) std::fprintf(stderr, "render_calibrate: %s\n", saved.message().c_str());
    }
    auto errors =
        render::testing::calibration_errors(*buffers, EXEMPLAR_SOURCE_DIR "/examples/stylit");
    if (!errors.ok()) {
        std::fprintf(stderr, "render_calibrate: %s\n", errors.status().message().c_str());
        return 1;
    }
    std::printf("%dx%d, %d spp\n%-18s %-8s %8s %9s %9s %9s\n", options.width, options.height,
                options.samples_per_pixel, "buffer", "StyLit", "MAE", "PSNR dB", "our mean",
                "ref mean");
    for (const auto& e : *errors) {
        std::printf("%-18s %-8s %8.4f %9.2f %9.4f %9.4f\n", e.ours.c_str(), e.reference.c_str(),
                    e.mean_abs, e.psnr_db, e.our_mean, e.reference_mean);
    }
    if (regions) print_regions(*buffers, EXEMPLAR_SOURCE_DIR "/examples/stylit");
    return 0;
}
