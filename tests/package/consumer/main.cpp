// Stylizes a small procedural image through the installed library and checks the result:
// usage `consumer OUT.png`. Exit status 0 on success.
#include <cmath>
#include <cstdio>
#include <string>

#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "exemplar/version.hpp"

int main(int argc, char** argv) {
    if (argc != 2) return 2;
    using namespace exemplar;
    // Style: stripes; guide: a horizontal ramp on both sides, the target's mirrored.
    const int w = 48, h = 40;
    SynthesisInput in;
    in.style = Image(w, h, 3);
    Image source_guide(w, h, 1), target_guide(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c)
                in.style.at(x, y, c) = 0.5f + 0.4f * std::sin(0.7f * static_cast<float>(x + c));
            source_guide.at(x, y, 0) = static_cast<float>(x) / w;
            target_guide.at(x, y, 0) = static_cast<float>(w - 1 - x) / w;
        }
    }
    in.guides.push_back({"ramp", source_guide, target_guide, 2.0f, {}});
    auto result = synthesize(std::move(in), SynthesisOptions{}, RunContext(1));
    if (!result.ok()) {
        std::fprintf(stderr, "%s\n", result.status().message().c_str());
        return 1;
    }
    const Status saved = save_image(result->image, argv[1]);
    auto loaded = load_image(argv[1]);
    if (!saved.is_ok() || !loaded.ok() || loaded->width() != w || loaded->height() != h) {
        std::fprintf(stderr, "cannot write and read back %s\n", argv[1]);
        return 1;
    }
    // The target's guide is mirrored, so its right edge must take the style's left edge.
    const Match& m = result->nnf.at(w - 3, h / 2);
    if (m.x > w / 3) {
        std::fprintf(stderr, "the guide was not followed: match x %d\n", m.x);
        return 1;
    }
    std::printf("exemplar %s: %dx%d written to %s\n", std::string(version()).c_str(),
                loaded->width(), loaded->height(), argv[1]);
    return 0;
}
