// Signed direction fields: Brushables (Lukáč et al. 2015) §3.1 on top of the edge tangent flow of
// Kang et al. 2007 ("Coherent line drawing", eq. 1-4 with η = 1).
//
// Deviations: (1) where the centre tangent is zero (flat regions, stripe centres of a sinusoid)
// the direction weight w_d is 1 and the sign φ is +1, so flat pixels take the harmonized average
// of their surroundings instead of staying zero; (2) the sign propagation visits pixels
// best-first by local agreement instead of breadth-first and decides each sign by the already
// harmonized 8-neighbours (see harmonize_signs); it runs on one thread in a fixed order.

#include "exemplar/paint/directions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <string>
#include <vector>

#include "exemplar/core/parallel.hpp"
#include "exemplar/filters/resample.hpp"

namespace exemplar::paint {

namespace {

Image grey(const Image& image) {
    Image out(image.width(), image.height(), 1);
    const int channels = image.channels();
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            const float* p = image.pixel(x, y);
            out.at(x, y, 0) =
                channels >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
        }
    }
    return out;
}

// Initial tangents: Sobel gradients rotated by 90° counter-clockwise on screen, normalized, and
// the gradient magnitude normalized to [0, 1] (channel 2).
Image initial_tangents(const Image& g, int threads) {
    const int w = g.width(), h = g.height();
    Image t(w, h, 3);
    parallel_for(0, h, threads, [&](int y) {
        const int ym = std::max(y - 1, 0), yp = std::min(y + 1, h - 1);
        for (int x = 0; x < w; ++x) {
            const int xm = std::max(x - 1, 0), xp = std::min(x + 1, w - 1);
            const float gx = (g.at(xp, ym, 0) + 2.0f * g.at(xp, y, 0) + g.at(xp, yp, 0)) -
                             (g.at(xm, ym, 0) + 2.0f * g.at(xm, y, 0) + g.at(xm, yp, 0));
            const float gy = (g.at(xm, yp, 0) + 2.0f * g.at(x, yp, 0) + g.at(xp, yp, 0)) -
                             (g.at(xm, ym, 0) + 2.0f * g.at(x, ym, 0) + g.at(xp, ym, 0));
            const float m = std::sqrt(gx * gx + gy * gy);
            float* o = t.pixel(x, y);
            if (m > 1e-6f) {
                o[0] = gy / m;
                o[1] = -gx / m;
            }
            o[2] = m;
        }
    });
    float max_m = 0.0f;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) max_m = std::max(max_m, t.at(x, y, 2));
    }
    if (max_m > 0.0f) {
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) t.at(x, y, 2) /= max_m;
        }
    }
    return t;
}

// How much a pixel's tangent agrees with its 3x3 neighbourhood, sign aside: the length of the
// mean doubled-angle vector (1 = all parallel, 0 = isotropic or zero tangents).
std::vector<float> tangent_agreement(const Image& t) {
    const int w = t.width(), h = t.height();
    std::vector<float> out(static_cast<std::size_t>(w) * h, 0.0f);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            float cx = 0.0f, cy = 0.0f;
            int n = 0;
            for (int v = std::max(y - 1, 0); v <= std::min(y + 1, h - 1); ++v) {
                for (int u = std::max(x - 1, 0); u <= std::min(x + 1, w - 1); ++u) {
                    const float* d = t.pixel(u, v);
                    cx += d[0] * d[0] - d[1] * d[1];
                    cy += 2.0f * d[0] * d[1];
                    ++n;
                }
            }
            out[static_cast<std::size_t>(y) * w + x] = std::hypot(cx, cy) / static_cast<float>(n);
        }
    }
    return out;
}

// Brushables' initialization: the strongest gradient keeps its sign and the others are flipped
// to agree with their already harmonized neighbours, visited outwards from it. The visiting order
// is best-first by `tangent_agreement` rather than breadth-first: a breadth-first front that
// crosses a singularity (the centre of radial stripes) comes back around it with the opposite
// sign and leaves a flipped wedge (5% of the annulus in the radial-stripes test); visiting
// coherent pixels first goes around singularities and reaches them last.
void harmonize_signs(Image& t) {
    const int w = t.width(), h = t.height();
    const std::size_t count = static_cast<std::size_t>(w) * h;
    int seed = 0;
    float best = -1.0f;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (t.at(x, y, 2) > best) {
                best = t.at(x, y, 2);
                seed = y * w + x;
            }
        }
    }
    const std::vector<float> agreement = tangent_agreement(t);
    // Reference direction per harmonized pixel: its tangent, or for a zero tangent the mean of
    // the references it was harmonized against (a zero tangent carries no sign of its own).
    std::vector<float> ref(count * 2, 0.0f);
    std::vector<char> queued(count, 0), assigned(count, 0);
    std::priority_queue<std::pair<float, int>> frontier;  // (agreement, -index): deterministic
    frontier.push({agreement[static_cast<std::size_t>(seed)], -seed});
    queued[static_cast<std::size_t>(seed)] = 1;
    constexpr int dx[4] = {1, -1, 0, 0};
    constexpr int dy[4] = {0, 0, 1, -1};
    while (!frontier.empty()) {
        const int i = -frontier.top().second;
        frontier.pop();
        const int x = i % w, y = i / w;
        float rx = 0.0f, ry = 0.0f;
        for (int v = std::max(y - 1, 0); v <= std::min(y + 1, h - 1); ++v) {
            for (int u = std::max(x - 1, 0); u <= std::min(x + 1, w - 1); ++u) {
                const auto m = static_cast<std::size_t>(v) * w + u;
                if (!assigned[m]) continue;
                rx += ref[2 * m];
                ry += ref[2 * m + 1];
            }
        }
        float* ti = t.pixel(x, y);
        if (ti[0] * rx + ti[1] * ry < 0.0f) {
            ti[0] = -ti[0];
            ti[1] = -ti[1];
        }
        const auto ii = static_cast<std::size_t>(i);
        const float rl = std::hypot(rx, ry);
        const bool zero = ti[0] == 0.0f && ti[1] == 0.0f;
        ref[2 * ii] = zero ? (rl > 0.0f ? rx / rl : 0.0f) : ti[0];
        ref[2 * ii + 1] = zero ? (rl > 0.0f ? ry / rl : 0.0f) : ti[1];
        assigned[ii] = 1;
        for (int k = 0; k < 4; ++k) {
            const int nx = x + dx[k], ny = y + dy[k];
            if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            const int n = ny * w + nx;
            if (queued[static_cast<std::size_t>(n)]) continue;
            queued[static_cast<std::size_t>(n)] = 1;
            frontier.push({agreement[static_cast<std::size_t>(n)], -n});
        }
    }
}

// One edge tangent flow iteration (Kang et al. 2007 eq. 1): t_new(x) = Σ φ w_s w_m w_d t(y) over
// the disc of radius r, normalized.
Image etf_iteration(const Image& t, float radius, int threads) {
    const int w = t.width(), h = t.height();
    const int r = static_cast<int>(std::floor(radius));
    const float r2 = radius * radius;
    Image out(w, h, 3);
    parallel_for(0, h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const float* c = t.pixel(x, y);
            const bool centre_zero = c[0] == 0.0f && c[1] == 0.0f;
            double sx = 0.0, sy = 0.0;
            for (int v = std::max(y - r, 0); v <= std::min(y + r, h - 1); ++v) {
                for (int u = std::max(x - r, 0); u <= std::min(x + r, w - 1); ++u) {
                    const float d2 = static_cast<float>((u - x) * (u - x) + (v - y) * (v - y));
                    if (d2 > r2) continue;
                    const float* n = t.pixel(u, v);
                    if (n[0] == 0.0f && n[1] == 0.0f) continue;
                    const float dot = c[0] * n[0] + c[1] * n[1];
                    const float wm = 0.5f * (1.0f + std::tanh(n[2] - c[2]));
                    const float wd = centre_zero ? 1.0f : std::abs(dot);
                    const float phi = dot < 0.0f ? -1.0f : 1.0f;
                    sx += static_cast<double>(phi * wm * wd * n[0]);
                    sy += static_cast<double>(phi * wm * wd * n[1]);
                }
            }
            const double len = std::sqrt(sx * sx + sy * sy);
            float* o = out.pixel(x, y);
            if (len > 1e-12) {
                o[0] = static_cast<float>(sx / len);
                o[1] = static_cast<float>(sy / len);
            }
            o[2] = c[2];
        }
    });
    return out;
}

}  // namespace

Status validate(const DirectionAnalysisOptions& o) {
    if (!(o.radius_px >= 1.0f && o.radius_px <= 100.0f)) {
        return invalid_argument("radius: " + std::to_string(o.radius_px) +
                                " is invalid (must be 1..100 px)");
    }
    if (o.iterations < 0 || o.iterations > 10) {
        return invalid_argument("iterations: " + std::to_string(o.iterations) +
                                " is invalid (must be 0..10)");
    }
    if (!(o.gradient_sigma_px >= 0.0f && o.gradient_sigma_px <= 10.0f)) {
        return invalid_argument("gradient-sigma: " + std::to_string(o.gradient_sigma_px) +
                                " is invalid (must be 0..10 px)");
    }
    return Status::ok();
}

Result<Image> analyze_directions(const Image& image, const DirectionAnalysisOptions& options,
                                 int threads) {
    if (Status s = validate(options); !s.is_ok()) return s;
    if (image.empty()) return Image{};

    // Tangents perpendicular to the gradients of the smoothed grey image.
    Image t =
        initial_tangents(gaussian_blur(grey(image), options.gradient_sigma_px, threads), threads);
    if (options.harmonize_signs) harmonize_signs(t);

    // Smooth them with the sign-preserving edge tangent flow filter.
    for (int i = 0; i < options.iterations; ++i) t = etf_iteration(t, options.radius_px, threads);

    Image field = extract_channels(t, 0, 2);
    field.set_channel_names({"x", "y"});
    return field;
}

Image direction_angles(const Image& directions) {
    Image out(directions.width(), directions.height(), 1);
    for (int y = 0; y < directions.height(); ++y) {
        for (int x = 0; x < directions.width(); ++x) {
            const float* d = directions.pixel(x, y);
            out.at(x, y, 0) = (d[0] == 0.0f && d[1] == 0.0f) ? 0.0f : std::atan2(-d[1], d[0]);
        }
    }
    out.set_channel_names({"angle"});
    return out;
}

Image directions_from_angles(const Image& angles) {
    Image out(angles.width(), angles.height(), 2);
    for (int y = 0; y < angles.height(); ++y) {
        for (int x = 0; x < angles.width(); ++x) {
            const float a = angles.at(x, y, 0);
            out.at(x, y, 0) = std::cos(a);
            out.at(x, y, 1) = -std::sin(a);
        }
    }
    out.set_channel_names({"x", "y"});
    return out;
}

Image direction_wheel(const Image& directions) {
    Image out(directions.width(), directions.height(), 3);
    for (int y = 0; y < directions.height(); ++y) {
        for (int x = 0; x < directions.width(); ++x) {
            const float* d = directions.pixel(x, y);
            const float value = std::min(1.0f, std::sqrt(d[0] * d[0] + d[1] * d[1]));
            if (value == 0.0f) continue;
            float hue = std::atan2(-d[1], d[0]) / (2.0f * std::numbers::pi_v<float>);
            if (hue < 0.0f) hue += 1.0f;
            // HSV to RGB with full saturation.
            const float h6 = hue * 6.0f;
            const int sector = std::min(static_cast<int>(h6), 5);
            const float f = h6 - static_cast<float>(sector);
            const float rgb[6][3] = {{1, f, 0},     {1 - f, 1, 0}, {0, 1, f},
                                     {0, 1 - f, 1}, {f, 0, 1},     {1, 0, 1 - f}};
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = value * rgb[sector][c];
        }
    }
    return out;
}

}  // namespace exemplar::paint
