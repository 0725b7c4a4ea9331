#pragma once
// A synthetic animation with exactly known motion for the TCIA tests: a bright square
// translating by an integer number of pixels per frame over a static gradient background, a
// style pair whose input has the same grey levels and whose output is a noisy texture (blue over
// the background's greys, red over the square's), and the metrics of the tests (warp error on
// visible pixels, gradient energy).

#include <cmath>
#include <cstdint>
#include <vector>

#include "exemplar/animate/animate.hpp"
#include "exemplar/core/image.hpp"
#include "exemplar/core/rng.hpp"
#include "exemplar/video/occlusion.hpp"
#include "exemplar/video/warp.hpp"

namespace exemplar::animate::testing {

struct Scene {
    int width = 64, height = 48, frames = 8;
    int square = 16;      // side
    int x0 = 8, y0 = 16;  // top-left at frame 0
    int speed = 2;        // px per frame, to the right

    int square_x(int t) const { return x0 + speed * t; }
    bool in_square(int x, int y, int t) const {
        return x >= square_x(t) && x < square_x(t) + square && y >= y0 && y < y0 + square;
    }
    // Grey input I_t: background 0.2..0.4 left to right, the square 0.8 with a faint pattern
    // that moves with it.
    Image frame(int t) const {
        Image im(width, height, 1);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                float v = 0.2f + 0.2f * static_cast<float>(x) / static_cast<float>(width - 1);
                if (in_square(x, y, t)) {
                    const int u = x - square_x(t);
                    v = 0.8f + 0.05f * static_cast<float>(((u / 4) + ((y - y0) / 4)) % 2);
                }
                im.at(x, y, 0) = v;
            }
        }
        return im;
    }
    // Exact motion of frame pair (t, t+1).
    video::FlowPair motion(int t) const {
        video::FlowPair p{Image(width, height, 2), Image(width, height, 2)};
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                if (in_square(x, y, t)) p.forward.at(x, y, 0) = static_cast<float>(speed);
                if (in_square(x, y, t + 1)) p.backward.at(x, y, 0) = -static_cast<float>(speed);
            }
        }
        return p;
    }
};

// A textured disc rotating in place over the same background: sub-pixel motion everywhere in
// the disc, no occlusion but at its rim.
struct RotatingDisc {
    int width = 64, height = 48, frames = 8;
    float cx = 32.0f, cy = 24.0f, radius = 17.0f;
    float omega = 0.08f;  // rad per frame, counter-clockwise on screen

    bool in_disc(float x, float y) const {
        return (x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius;
    }
    Image frame(int t) const {
        Image im(width, height, 1);
        const float a = -omega * static_cast<float>(t);  // back to the disc's own coordinates
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const float fx = static_cast<float>(x), fy = static_cast<float>(y);
                float v = 0.2f + 0.2f * fx / static_cast<float>(width - 1);
                if (in_disc(fx, fy)) {
                    const float dx = fx - cx, dy = fy - cy;
                    const float u = std::cos(a) * dx + std::sin(a) * dy;
                    const float w = -std::sin(a) * dx + std::cos(a) * dy;
                    v = 0.8f + 0.025f * (std::sin(u / 2.0f) + std::sin(w / 3.0f));
                }
                im.at(x, y, 0) = v;
            }
        }
        return im;
    }
    // Rotation by ±omega about the centre inside the disc, zero outside.
    Image rotation_flow(float angle) const {
        Image f(width, height, 2);
        const float c = std::cos(angle), s = std::sin(angle);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const float fx = static_cast<float>(x), fy = static_cast<float>(y);
                if (!in_disc(fx, fy)) continue;
                const float dx = fx - cx, dy = fy - cy;
                f.at(x, y, 0) = c * dx + s * dy - dx;  // screen: y down, ccw on screen
                f.at(x, y, 1) = -s * dx + c * dy - dy;
            }
        }
        return f;
    }
    video::FlowPair motion(int) const { return {rotation_flow(omega), rotation_flow(-omega)}; }
};

// Style: S has the background's grey ramp on the left and the square's grey on the right; Ŝ is
// blue noise texture on the left, red on the right (texture: values vary pixel to pixel).
struct Style {
    Image input, output;
};

inline Style make_style(int size = 64, std::uint64_t seed = 7) {
    Style s{Image(size, size, 1), Image(size, size, 3)};
    KeyedRng rng(seed);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const bool right = x >= size / 2;
            s.input.at(x, y, 0) =
                right ? 0.8f + 0.05f * static_cast<float>(((x / 4) + (y / 4)) % 2)
                      : 0.2f + 0.2f * static_cast<float>(x) / static_cast<float>(size / 2 - 1);
            const float n = 0.25f * rng.uniform();
            if (right) {
                s.output.at(x, y, 0) = 0.65f + n;
                s.output.at(x, y, 1) = 0.15f + n;
                s.output.at(x, y, 2) = 0.1f + 0.5f * n;
            } else {
                s.output.at(x, y, 0) = 0.1f + 0.5f * n;
                s.output.at(x, y, 1) = 0.2f + n;
                s.output.at(x, y, 2) = 0.55f + n;
            }
        }
    }
    return s;
}

/// Any scene with `frames`, `frame(t)` and `motion(t)` (Scene, or a test's own).
template <class AnyScene>
AnimationInput make_input(const AnyScene& scene, const Style& style) {
    AnimationInput in;
    in.style_input = style.input;
    in.style_output = style.output;
    in.frame_count = scene.frames;
    in.frame = [scene](int t) -> Result<Image> { return scene.frame(t); };
    in.motion = [scene](int t) -> Result<video::FlowPair> { return scene.motion(t); };
    return in;
}

// Mean squared difference between frame t and frame t−1 pulled along the backward flow of t,
// over pixels not marked in `occluded` (1 channel, 1 = not visible in frame t−1; e.g. a
// renderer's disocclusion buffer) and whose sample is inside frame t−1.
inline double warp_error_visible(const Image& previous, const Image& current, const Image& backward,
                                 const Image& occluded) {
    const video::WarpResult w = video::backward_warp(previous, backward, 1).value();
    double sum = 0.0;
    std::size_t n = 0;
    const int C = current.channels();
    for (std::size_t p = 0; p < current.pixel_count(); ++p) {
        if (occluded.data()[p] > 0.5f || w.valid.data()[p] < 0.5f) continue;
        for (int c = 0; c < C; ++c) {
            const std::size_t j = p * static_cast<std::size_t>(C) + static_cast<std::size_t>(c);
            const double d = current.data()[j] - w.image.data()[j];
            sum += d * d;
        }
        ++n;
    }
    return n == 0 ? 0.0 : sum / static_cast<double>(n * static_cast<std::size_t>(C));
}

// The same over pixels that pass the occlusion test χ⁻ of the flows.
inline double warp_error(const Image& previous, const Image& current, const Image& backward,
                         const Image& forward_of_previous, float tolerance = 2.0f) {
    return warp_error_visible(
        previous, current, backward,
        video::occlusion_mask(backward, forward_of_previous, {tolerance}, 1).value());
}

// Mean squared luminance gradient (forward differences) of an RGB or grey image.
inline double gradient_energy(const Image& im) {
    auto luma = [&](int x, int y) {
        if (im.channels() < 3) return static_cast<double>(im.at(x, y, 0));
        return 0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
    };
    double sum = 0.0;
    std::size_t n = 0;
    for (int y = 0; y + 1 < im.height(); ++y) {
        for (int x = 0; x + 1 < im.width(); ++x) {
            const double dx = luma(x + 1, y) - luma(x, y), dy = luma(x, y + 1) - luma(x, y);
            sum += dx * dx + dy * dy;
            ++n;
        }
    }
    return sum / static_cast<double>(n);
}

}  // namespace exemplar::animate::testing
