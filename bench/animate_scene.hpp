#pragma once
// A procedural animation with exactly known motion, for the animation benchmark and the
// example's input frames: a textured disc translating over a static textured background
// (grey, values in [0, 1]), with its exact forward/backward flow per frame pair.

#include <cmath>

#include "exemplar/core/image.hpp"
#include "exemplar/video/optical_flow.hpp"

namespace exemplar::bench {

struct DiscScene {
    int width = 960, height = 540;
    float speed = 4.0f;  // px per frame, to the right (an integer keeps the flow exact)

    float radius() const { return 0.22f * static_cast<float>(height); }
    float cx(int t) const {
        return 0.3f * static_cast<float>(width) + speed * static_cast<float>(t);
    }
    float cy() const { return 0.5f * static_cast<float>(height); }
    bool in_disc(int x, int y, int t) const {
        const float dx = static_cast<float>(x) - cx(t), dy = static_cast<float>(y) - cy();
        return dx * dx + dy * dy <= radius() * radius();
    }
    Image frame(int t) const {
        Image im(width, height, 1);
        const float s = static_cast<float>(height) / 540.0f;  // texture scale follows the size
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const float fx = static_cast<float>(x) / s, fy = static_cast<float>(y) / s;
                float v = 0.3f + 0.12f * std::sin(fx / 31.0f) * std::cos(fy / 19.0f) +
                          0.05f * std::sin((fx + 2.0f * fy) / 7.0f);
                if (in_disc(x, y, t)) {
                    const float u = (static_cast<float>(x) - cx(t)) / s;
                    const float w = (static_cast<float>(y) - cy()) / s;
                    v = 0.75f + 0.1f * std::sin(u / 5.0f) * std::sin(w / 5.0f);
                }
                im.at(x, y, 0) = v;
            }
        }
        return im;
    }
    video::FlowPair motion(int t) const {
        video::FlowPair p{Image(width, height, 2), Image(width, height, 2)};
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                if (in_disc(x, y, t)) p.forward.at(x, y, 0) = speed;
                if (in_disc(x, y, t + 1)) p.backward.at(x, y, 0) = -speed;
            }
        }
        return p;
    }
};

}  // namespace exemplar::bench
