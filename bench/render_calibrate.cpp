// Renders sphere-on-table (or a scene file) and prints, per light buffer, the error against the
// StyLit authors' buffers of the same set-up (examples/stylit/). The numbers of docs/render.md.
//
//   render_calibrate [--scene FILE] [--width 600] [--height 456] [--spp 256] [--threads 0]
//                    [--save FOLDER]

#include <cstdio>
#include <cstdlib>
#include <string>

#include "calibration.hpp"
#include "exemplar/render/scene.hpp"

int main(int argc, char** argv) {
    using namespace exemplar;
    render::RenderOptions options;
    options.samples_per_pixel = 256;
    std::string scene_file, save;
    int threads = 0;
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
        else if (flag == "--threads")
            threads = std::atoi(value.c_str());
        else if (flag == "--save")
            save = value;
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
    return 0;
}
