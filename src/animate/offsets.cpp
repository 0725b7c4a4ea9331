// Offset-field operations of the TCIA solver (Bénard et al. 2013 §3.3, "Advecting and
// interpolating offsets"): nearest-sample lookup plus extrapolation by the match's rotation,
// never interpolation between offsets.

#include "exemplar/animate/offsets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "exemplar/core/check.hpp"
#include "exemplar/core/rng.hpp"
#include "exemplar/video/warp.hpp"

namespace exemplar::animate {

namespace {

constexpr Match kNoMatch{-1, -1, 0.0f, 0.0f};

// m shifted by the target-space offset (du, dv), rotated into the style, on a style grid scaled
// by (sx, sy); kNoMatch if it leaves the style.
Match extrapolate(const Match& m, double du, double dv, double sx, double sy, int sw, int sh) {
    const double c = std::cos(m.angle_rad), s = std::sin(m.angle_rad);
    const double u = m.x + c * du - s * dv;
    const double v = m.y + s * du + c * dv;
    const long x = std::lround((u + 0.5) * sx - 0.5);
    const long y = std::lround((v + 0.5) * sy - 0.5);
    if (x < 0 || y < 0 || x >= sw || y >= sh) return kNoMatch;
    return Match{static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), m.angle_rad, 0.0f};
}

}  // namespace

Nnf advect_nnf(const Nnf& from, const Image& flow, const Image& visible, int style_width,
               int style_height) {
    EXEMPLAR_CHECK_EQ(flow.channels(), 2);
    EXEMPLAR_CHECK(visible.empty() || (visible.same_size(flow) && visible.channels() == 1));
    const int w = flow.width(), h = flow.height();
    Nnf out(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            Match& o = out.at(x, y);
            o = kNoMatch;
            if (!visible.empty() && !(visible.at(x, y, 0) > 0.5f)) continue;
            const double qx = x + static_cast<double>(flow.at(x, y, 0));
            const double qy = y + static_cast<double>(flow.at(x, y, 1));
            if (!std::isfinite(qx) || !std::isfinite(qy)) continue;
            const long px = std::lround(qx), py = std::lround(qy);
            if (px < 0 || py < 0 || px >= from.width() || py >= from.height()) continue;
            const Match& m = from.at(static_cast<int>(px), static_cast<int>(py));
            if (m.x < 0) continue;
            o = extrapolate(m, qx - px, qy - py, 1.0, 1.0, style_width, style_height);
        }
    }
    return out;
}

Nnf upsample_nnf(const Nnf& coarse, const std::vector<AtlasSlot>& coarse_slots, int width,
                 int height, const std::vector<AtlasSlot>& fine_slots) {
    EXEMPLAR_CHECK_EQ(coarse_slots.size(), fine_slots.size());
    Nnf out(width, height);
    const double qx = static_cast<double>(coarse.width()) / width;
    const double qy = static_cast<double>(coarse.height()) / height;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double u = (x + 0.5) * qx - 0.5, v = (y + 0.5) * qy - 0.5;
            const long cx = std::clamp(std::lround(u), 0L, static_cast<long>(coarse.width()) - 1);
            const long cy = std::clamp(std::lround(v), 0L, static_cast<long>(coarse.height()) - 1);
            Match m = coarse.at(static_cast<int>(cx), static_cast<int>(cy));
            Match& o = out.at(x, y);
            o = kNoMatch;
            if (m.x < 0) continue;
            for (std::size_t s = 0; s < coarse_slots.size(); ++s) {
                const AtlasSlot& c = coarse_slots[s];
                if (m.x < c.x0 || m.x >= c.x0 + c.width || m.y >= c.height) continue;
                const AtlasSlot& f = fine_slots[s];
                m.x -= c.x0;
                o = extrapolate(m, u - static_cast<double>(cx), v - static_cast<double>(cy),
                                static_cast<double>(f.width) / c.width,
                                static_cast<double>(f.height) / c.height, f.width, f.height);
                if (o.x >= 0) o.x += f.x0;
                break;
            }
        }
    }
    return out;
}

namespace {

// Pixel i of the merge takes a[i] if both are matches and take_a(i), else whichever is one.
template <class TakeA>
Nnf merge_where(const Nnf& a, const Nnf& b, TakeA take_a) {
    EXEMPLAR_CHECK(a.width() == b.width() && a.height() == b.height());
    Nnf out(a.width(), a.height());
    for (std::size_t i = 0; i < out.pixel_count(); ++i) {
        const bool a_ok = a[i].x >= 0, b_ok = b[i].x >= 0;
        out[i] = (a_ok && (!b_ok || take_a(i))) ? a[i] : b[i];
    }
    return out;
}

}  // namespace

Nnf random_merge(const Nnf& a, const Nnf& b, float probability_a, std::uint64_t key) {
    return merge_where(a, b, [&](std::size_t i) {
        KeyedRng rng(key, i);
        return rng.uniform() < probability_a;
    });
}

Nnf threshold_merge(const Nnf& a, const Nnf& b, float probability_a, const Image& draw) {
    EXEMPLAR_CHECK(draw.width() == a.width() && draw.height() == a.height() &&
                   draw.channels() == 1);
    return merge_where(a, b, [&](std::size_t i) { return draw.data()[i] < probability_a; });
}

Image dot_screen(int width, int height, float cell_px, std::uint64_t seed) {
    EXEMPLAR_CHECK(width > 0 && height > 0 && cell_px > 0.0f);
    // Centres of lattice l (shifted by l / 2 cells) in cells a = -2 .. columns, b likewise; they
    // stay 0.15 of a cell away from their cell's sides, so a point's nearest one is in the 3 x 3
    // cells around it.
    const int columns = static_cast<int>(std::ceil(width / cell_px)) + 1;
    const int rows = static_cast<int>(std::ceil(height / cell_px)) + 1;
    const auto stride = static_cast<std::size_t>(columns + 2);
    std::vector<double> centres(2 * stride * static_cast<std::size_t>(rows + 2) * 2);
    auto centre = [&](int lattice, long a, long b) {
        return centres.data() +
               2 * ((static_cast<std::size_t>(lattice) * static_cast<std::size_t>(rows + 2) +
                     static_cast<std::size_t>(b + 2)) *
                        stride +
                    static_cast<std::size_t>(a + 2));
    };
    for (int lattice = 0; lattice < 2; ++lattice) {
        for (long b = -2; b < rows; ++b) {
            for (long a = -2; a < columns; ++a) {
                // Keyed by a + 1, b + 1 (cell -2 wraps to 2^64 - 1: still its own key).
                KeyedRng rng(seed, static_cast<std::uint64_t>(lattice),
                             static_cast<std::uint64_t>(a + 1), static_cast<std::uint64_t>(b + 1));
                double* c = centre(lattice, a, b);
                c[0] = 0.5 * lattice + a + 0.15 + 0.7 * rng.uniform();
                c[1] = 0.5 * lattice + b + 0.15 + 0.7 * rng.uniform();
            }
        }
    }
    // Distance (in cells) from (u, v) to the nearest centre of a lattice.
    auto nearest = [&](double u, double v, int lattice) {
        const auto i = static_cast<long>(std::floor(u - 0.5 * lattice));
        const auto j = static_cast<long>(std::floor(v - 0.5 * lattice));
        double best = std::numeric_limits<double>::max();
        for (long b = j - 1; b <= j + 1; ++b) {
            for (long a = i - 1; a <= i + 1; ++a) {
                const double* c = centre(lattice, a, b);
                best = std::min(best, (u - c[0]) * (u - c[0]) + (v - c[1]) * (v - c[1]));
            }
        }
        return std::sqrt(best);
    };
    // (value, position), sorted: the rank, ties by position, / n is uniform in [0, 1).
    const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<std::pair<double, std::size_t>> order(n);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double u = (x + 0.5) / cell_px, v = (y + 0.5) / cell_px;
            const double low = nearest(u, v, 0), high = nearest(u, v, 1);
            const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x);
            order[p] = {low / (low + high), p};
        }
    }
    std::sort(order.begin(), order.end());
    Image out(width, height, 1);
    for (std::size_t k = 0; k < n; ++k) {
        out.data()[order[k].second] =
            static_cast<float>(static_cast<double>(k) / static_cast<double>(n));
    }
    return out;
}

Result<DerivativeGuide> input_derivative_guide(const Image& frame, const Image& neighbour_frame,
                                               const Nnf& neighbour_offsets,
                                               const Image& source_input, const Image& flow,
                                               const Image& visible) {
    const int w = frame.width(), h = frame.height(), C = frame.channels();
    EXEMPLAR_CHECK(neighbour_frame.same_size(frame) && neighbour_frame.channels() == C);
    EXEMPLAR_CHECK(neighbour_offsets.width() == w && neighbour_offsets.height() == h);
    EXEMPLAR_CHECK(visible.width() == w && visible.height() == h);
    EXEMPLAR_CHECK(source_input.channels() == C);
    // (S(C_n) − I_n, has a match) on the neighbour's grid.
    Image diff(w, h, C + 1, 0.0f);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const Match& m = neighbour_offsets.at(x, y);
            if (m.x < 0 || m.y < 0 || m.x >= source_input.width() || m.y >= source_input.height()) {
                continue;
            }
            for (int c = 0; c < C; ++c) {
                diff.at(x, y, c) = source_input.at(m.x, m.y, c) - neighbour_frame.at(x, y, c);
            }
            diff.at(x, y, C) = 1.0f;
        }
    }
    auto warped = video::backward_warp(diff, flow, 1);
    if (!warped.ok()) return warped.status();
    DerivativeGuide guide{frame, Image(w, h, 1, 0.0f)};
    bool all_weighted = true;
    for (std::size_t p = 0; p < guide.target.pixel_count(); ++p) {
        const float* d = warped->image.data().data() + p * static_cast<std::size_t>(C + 1);
        // d[C] < 1: the bilinear sample mixed in pixels without a match.
        if (!(visible.data()[p] > 0.5f && warped->valid.data()[p] > 0.5f && d[C] > 0.999f)) {
            all_weighted = false;
            continue;
        }
        guide.weight.data()[p] = 1.0f;
        for (int c = 0; c < C; ++c) {
            guide.target.data()[p * static_cast<std::size_t>(C) + static_cast<std::size_t>(c)] +=
                d[c];
        }
    }
    if (all_weighted) guide.weight = Image();
    return guide;
}

}  // namespace exemplar::animate
