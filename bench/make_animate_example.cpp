// Writes the inputs of examples/animate/: the frames of the procedural disc scene
// (bench/animate_scene.hpp) as grey PNGs, and the style pair made from Starry Night (shared
// data, public domain): Ŝ = the painting reduced, S = its blurred luminance.
//
//   make_animate_example OUT_FOLDER [width=192] [height=108] [frames=24]

#include <cstdio>
#include <cstdlib>
#include <string>

#include "animate_scene.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/io/image_io.hpp"
#include "shared_data.hpp"

using namespace exemplar;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: make_animate_example OUT_FOLDER [width height frames]\n");
        return 2;
    }
    const std::string out = argv[1];
    bench::DiscScene scene;
    scene.width = argc > 2 ? std::atoi(argv[2]) : 192;
    scene.height = argc > 3 ? std::atoi(argv[3]) : 108;
    const int frames = argc > 4 ? std::atoi(argv[4]) : 24;
    scene.speed = 2.0f;
    for (int t = 0; t < frames; ++t) {
        char name[64];
        std::snprintf(name, sizeof name, "/frames/%04d.png", t);
        const Status st = save_image(scene.frame(t), out + name);
        if (!st.is_ok()) {
            std::fprintf(stderr, "%s\n", st.message().c_str());
            return 1;
        }
    }
    const std::string painting_file = bench::shared_data("style/neural-style/starry_night.jpg");
    if (!bench::shared_data_present(painting_file)) return 1;
    auto painting = load_image(painting_file);
    if (!painting.ok()) {
        std::fprintf(stderr, "%s\n", painting.status().message().c_str());
        return 1;
    }
    const int sw = scene.width * 4 / 3, sh = sw * 640 / 1024;
    const Image style = resize(*painting, sw, sh, ResampleFilter::Gaussian);
    Image luma(sw, sh, 1);
    for (std::size_t i = 0; i < luma.pixel_count(); ++i) {
        luma.data()[i] = 0.2126f * style.data()[3 * i] + 0.7152f * style.data()[3 * i + 1] +
                         0.0722f * style.data()[3 * i + 2];
    }
    const float blur = static_cast<float>(scene.height) / 270.0f;
    if (!save_image(style, out + "/style_output.png").is_ok() ||
        !save_image(gaussian_blur(luma, blur), out + "/style_input.png").is_ok()) {
        std::fprintf(stderr, "cannot write the style pair to %s\n", out.c_str());
        return 1;
    }
    return 0;
}
