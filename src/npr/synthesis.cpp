// Per-frame coordinate synthesis of "Image Space Texture Synthesis for 3D NPR Animation" §5
// (after Lefebvre and Hoppe 2005/2006, Ashikhmin 2001) and the halftone post-process of §6.
// Deviations from the paper:
// - The per-level buffers (orientation, flow, disocclusion) are sampled from the full-resolution
//   buffers (block centre; disocclusion = any pixel of the block) instead of re-rendered.
// - Initialization tries `init_candidates` random pattern positions on the 2^L grid instead of
//   all of them, plus the previous frame's coordinates at the patch centre's advected position
//   (which the paper's exhaustive grid holds up to the grid spacing).
// - The correction offers the previous frame's coordinates around each pixel's advected
//   position (§5.2.4) only at the `motion_levels` coarsest levels (default none): at every
//   level they carry the motion's scaling and a zoom grows the pattern (docs/npr.md, "Zoom").
// - The bidirectional loop (§5.2.1) is the caller's order of frames; here only its backward
//   pass's held pixels (FrameInput::hold).
// - Neighbourhoods are 3x3 in the appearance space (the paper does not give a size).
#include "exemplar/npr/synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"
#include "exemplar/filters/resample.hpp"

namespace exemplar::npr {
namespace {

int wrap(int v, int n) {
    const int r = v % n;
    return r < 0 ? r + n : r;
}

float wrapf(float v, float n) {
    // Within one period of [0, n) without fmod: fmod(v, n) is v there, and v − n is exact
    if (v >= 0.0f && v < n) return v;
    if (v < 0.0f && v >= -n) return v + n;
    if (v >= n && v < 2.0f * n) return v - n;
    const float r = std::fmod(v, n);
    return r < 0.0f ? r + n : r;
}

// Coordinates of one level: x, y per pixel.
struct Field {
    int width = 0, height = 0;
    std::vector<int> xy;
    int* at(int x, int y) { return xy.data() + 2 * (static_cast<std::size_t>(y) * width + x); }
    const int* at(int x, int y) const {
        return xy.data() + 2 * (static_cast<std::size_t>(y) * width + x);
    }
};

// The full-resolution buffers sampled at one level.
struct LevelBuffers {
    int width = 0, height = 0, spacing = 1;
    std::vector<float> cos_angle, sin_angle;
    std::vector<float> flow;           // 2 per pixel, in level pixels; empty = none
    std::vector<unsigned char> valid;  // 1 where the backward flow may be used
    std::vector<unsigned char> held;   // 1 where the coordinates are held; empty = none
    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
};

LevelBuffers sample_level(const FrameInput& input, int level, int threads) {
    LevelBuffers b;
    b.spacing = 1 << level;
    b.width = (input.width + b.spacing - 1) / b.spacing;
    b.height = (input.height + b.spacing - 1) / b.spacing;
    const std::size_t n = static_cast<std::size_t>(b.width) * b.height;
    b.cos_angle.assign(n, 1.0f);
    b.sin_angle.assign(n, 0.0f);
    const bool has_flow = !input.backward_flow.empty();
    if (has_flow) {
        b.flow.assign(2 * n, 0.0f);
        b.valid.assign(n, 1);
    }
    if (!input.hold.empty()) b.held.assign(n, 0);
    parallel_for(0, b.height, threads, [&](int y) {
        for (int x = 0; x < b.width; ++x) {
            const int cx = std::min(x * b.spacing + b.spacing / 2, input.width - 1);
            const int cy = std::min(y * b.spacing + b.spacing / 2, input.height - 1);
            const std::size_t i = b.index(x, y);
            if (!input.orientation.empty()) {
                const float angle = input.orientation.at(cx, cy, 0);
                b.cos_angle[i] = std::cos(angle);
                b.sin_angle[i] = std::sin(angle);
            }
            if (!input.hold.empty()) {
                bool all = true;
                for (int yy = y * b.spacing; yy < std::min((y + 1) * b.spacing, input.height); ++yy)
                    for (int xx = x * b.spacing; xx < std::min((x + 1) * b.spacing, input.width);
                         ++xx)
                        all = all && input.hold.at(xx, yy, 0) > 0.5f;
                b.held[i] = all ? 1 : 0;
            }
            if (!has_flow) continue;
            b.flow[2 * i] = input.backward_flow.at(cx, cy, 0) / static_cast<float>(b.spacing);
            b.flow[2 * i + 1] = input.backward_flow.at(cx, cy, 1) / static_cast<float>(b.spacing);
            if (input.disocclusion.empty()) continue;
            for (int yy = y * b.spacing; yy < std::min((y + 1) * b.spacing, input.height); ++yy)
                for (int xx = x * b.spacing; xx < std::min((x + 1) * b.spacing, input.width); ++xx)
                    if (input.disocclusion.at(xx, yy, 0) > 0.5f) b.valid[i] = 0;
        }
    });
    return b;
}

// Pattern offset of the screen offset (dx, dy) scaled by h under the rotation (c, s) = θ:
// Rot(-θ) in screen coordinates (y down), rounded to whole pattern pixels.
void pattern_offset(float c, float s, float dx, float dy, float h, int& ox, int& oy) {
    ox = static_cast<int>(std::lround((c * dx - s * dy) * h));
    oy = static_cast<int>(std::lround((s * dx + c * dy) * h));
}

// std::lround for floats without the library call: v - trunc(v) is exact, so this rounds half
// away from zero exactly as lround does (|v| < 2^31).
int round_half_away(float v) {
    int r = static_cast<int>(v);
    const float fraction = v - static_cast<float>(r);
    if (fraction >= 0.5f) ++r;
    if (fraction <= -0.5f) --r;
    return r;
}

// pattern_offset with round_half_away (same results).
void pattern_offset_fast(float c, float s, float dx, float dy, float h, int& ox, int& oy) {
    ox = round_half_away((c * dx - s * dy) * h);
    oy = round_half_away((s * dx + c * dy) * h);
}

// wrap() for values that are usually within one period of [0, n): no division then.
int wrap_near(int v, int n) {
    if (v < 0) v += n;
    if (v >= n) v -= n;
    return v >= 0 && v < n ? v : wrap(v, n);
}

// Appearance of pattern pixel (x, y) (wrapped) at one stack level.
const float* appearance_at(const Image& stack, int x, int y) {
    return stack.pixel(wrap_near(x, stack.width()), wrap_near(y, stack.height()));
}

// Bilinear sample of an image with clamped borders (n channels into out).
void bilinear(const Image& image, float x, float y, float* out) {
    x = std::clamp(x, 0.0f, static_cast<float>(image.width() - 1));
    y = std::clamp(y, 0.0f, static_cast<float>(image.height() - 1));
    const int x0 = std::min(static_cast<int>(x), image.width() - 1);
    const int y0 = std::min(static_cast<int>(y), image.height() - 1);
    const int x1 = std::min(x0 + 1, image.width() - 1), y1 = std::min(y0 + 1, image.height() - 1);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    for (int c = 0; c < image.channels(); ++c)
        out[c] = (1 - fy) * ((1 - fx) * image.at(x0, y0, c) + fx * image.at(x1, y0, c)) +
                 fy * ((1 - fx) * image.at(x0, y1, c) + fx * image.at(x1, y1, c));
}

// Bilinear sample of the screen with wrapped coordinates.
float screen_at(const Image& screen, float x, float y) {
    const float w = static_cast<float>(screen.width()), h = static_cast<float>(screen.height());
    x = wrapf(x, w);
    y = wrapf(y, h);
    const int x0 = std::min(static_cast<int>(x), screen.width() - 1);
    const int y0 = std::min(static_cast<int>(y), screen.height() - 1);
    const int x1 = wrap(x0 + 1, screen.width()), y1 = wrap(y0 + 1, screen.height());
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    return (1 - fy) * ((1 - fx) * screen.at(x0, y0, 0) + fx * screen.at(x1, y0, 0)) +
           fy * ((1 - fx) * screen.at(x0, y1, 0) + fx * screen.at(x1, y1, 0));
}

// The previous frame's appearance advected to this frame (valid[i] = 0 where unusable).
struct Advected {
    std::vector<float> appearance;
    std::vector<unsigned char> valid;
};

Advected advect(const Image& previous, const LevelBuffers& b, int dims, int threads) {
    Advected a;
    const std::size_t n = static_cast<std::size_t>(b.width) * b.height;
    a.appearance.assign(n * static_cast<std::size_t>(dims), 0.0f);
    a.valid.assign(n, 0);
    if (b.flow.empty() || previous.empty()) return a;
    parallel_for(0, b.height, threads, [&](int y) {
        for (int x = 0; x < b.width; ++x) {
            const std::size_t i = b.index(x, y);
            const float px = static_cast<float>(x) + b.flow[2 * i];
            const float py = static_cast<float>(y) + b.flow[2 * i + 1];
            if (!b.valid[i] || px < -0.5f || py < -0.5f ||
                px > static_cast<float>(b.width) - 0.5f || py > static_cast<float>(b.height) - 0.5f)
                continue;
            bilinear(previous, px, py, a.appearance.data() + i * static_cast<std::size_t>(dims));
            a.valid[i] = 1;
        }
    });
    return a;
}

// The previous frame's coordinates around the advected position of pixel (x, y) (rotation (c, s)),
// with the sub-pixel remainder of the motion, where the backward flow is valid: emit(u, v) for
// each of the 3x3 inside the level; `offset` is pattern_offset or pattern_offset_fast.
template <class Offset, class Emit>
void advected_candidates(const LevelBuffers& b, const Field& previous, int x, int y, float c,
                         float s, Offset offset, Emit emit) {
    const std::size_t i = b.index(x, y);
    if (b.valid.empty() || !b.valid[i]) return;
    const float h = static_cast<float>(b.spacing);
    const float px = static_cast<float>(x) + b.flow[2 * i];
    const float py = static_cast<float>(y) + b.flow[2 * i + 1];
    const int qx = static_cast<int>(std::lround(px));
    const int qy = static_cast<int>(std::lround(py));
    for (int k = 0; k < 9; ++k) {
        const int sx = qx + k % 3 - 1, sy = qy + k / 3 - 1;
        if (sx < 0 || sy < 0 || sx >= b.width || sy >= b.height) continue;
        const int* sp = previous.at(sx, sy);
        int ox, oy;
        offset(c, s, static_cast<float>(sx) - px, static_cast<float>(sy) - py, h, ox, oy);
        emit(sp[0] - ox, sp[1] - oy);
    }
}

// One initialization patch: centre (cx, cy), clipped to [x0, x1) x [y0, y1), in a partly filled
// field; candidates are the previous frame's coordinates around the centre's advected position
// (`anchored`), then keyed random positions on the grid of spacing `grid` (grid_w x grid_h).
struct PatchSearch {
    const Image& stack;
    const LevelBuffers& b;
    const Field& field;
    const std::vector<unsigned char>& filled;
    const Advected& advected;  // the previous frame's appearance here; valid empty = none
    const SynthesisOptions& options;
    const std::vector<std::pair<int, int>>& anchored;
    int cx, cy, x0, x1, y0, y1;
    int grid, grid_w, grid_h;
};

// The previous frame's appearance advected to pixel i, or null where there is none.
const float* prior_at(const Advected& advected, std::size_t i, int dims) {
    if (advected.valid.empty() || !advected.valid[i]) return nullptr;
    return advected.appearance.data() + i * static_cast<std::size_t>(dims);
}

// The first of the patch's candidates (the anchored ones, then keyed random grid positions)
// with the least error_of(ux, uy, best) (which may stop summing once it reaches `best`).
template <class Error>
std::pair<int, int> first_best_candidate(const PatchSearch& p, KeyedRng& rng, Error error_of) {
    int best_x = 0, best_y = 0;
    float best = std::numeric_limits<float>::infinity();
    const auto consider = [&](int ux, int uy) {
        const float error = error_of(ux, uy, best);
        if (error < best) {
            best = error;
            best_x = ux;
            best_y = uy;
        }
    };
    for (const auto& [ux, uy] : p.anchored)
        consider(wrap(ux, p.stack.width()), wrap(uy, p.stack.height()));
    for (int k = 0; k < p.options.init_candidates; ++k) {
        const int ux = static_cast<int>(rng.below(static_cast<std::uint32_t>(p.grid_w))) * p.grid;
        const int uy = static_cast<int>(rng.below(static_cast<std::uint32_t>(p.grid_h))) * p.grid;
        consider(ux, uy);
    }
    return {best_x, best_y};
}

// The candidate with the least texture_weight·E_texture over the filled overlap plus
// coherence_weight·E_coherence over the patch pixels the previous frame covers (the plain
// reference of best_patch_fast).
std::pair<int, int> best_patch_reference(const PatchSearch& p, KeyedRng& rng) {
    const int dims = p.stack.channels();
    const float h = static_cast<float>(p.b.spacing);
    const float alpha = p.options.texture_weight, beta = p.options.coherence_weight;
    return first_best_candidate(p, rng, [&](int ux, int uy, float best) {
        float error = 0.0f;
        for (int y = p.y0; y < p.y1 && error < best; ++y)
            for (int x = p.x0; x < p.x1; ++x) {
                const std::size_t i = p.b.index(x, y);
                const float* was = prior_at(p.advected, i, dims);
                if (!p.filled[i] && was == nullptr) continue;
                int ox, oy;
                pattern_offset(p.b.cos_angle[i], p.b.sin_angle[i], static_cast<float>(x - p.cx),
                               static_cast<float>(y - p.cy), h, ox, oy);
                const float* want = appearance_at(p.stack, ux + ox, uy + oy);
                if (p.filled[i]) {
                    const int* s = p.field.at(x, y);
                    const float* have = appearance_at(p.stack, s[0], s[1]);
                    for (int c = 0; c < dims; ++c) {
                        const float d = have[c] - want[c];
                        error += alpha * (d * d);
                    }
                }
                if (was != nullptr)
                    for (int c = 0; c < dims; ++c) {
                        const float d = was[c] - want[c];
                        error += beta * (d * d);
                    }
            }
        return error;
    });
}

// A patch pixel the error reads: its pattern offset, the filled field's appearance there (or
// null) and the previous frame's (or null).
struct Overlap {
    int ox, oy;
    const float* have;
    const float* was;
};

// best_patch_reference with the same candidates and sums, faster: the patch's offsets and
// appearances are gathered once (into `overlap`) instead of per candidate.
std::pair<int, int> best_patch_fast(const PatchSearch& p, KeyedRng& rng,
                                    std::vector<Overlap>& overlap) {
    const int dims = p.stack.channels();
    const float h = static_cast<float>(p.b.spacing);
    const float alpha = p.options.texture_weight, beta = p.options.coherence_weight;
    overlap.clear();
    for (int y = p.y0; y < p.y1; ++y)
        for (int x = p.x0; x < p.x1; ++x) {
            const std::size_t i = p.b.index(x, y);
            Overlap o;
            o.was = prior_at(p.advected, i, dims);
            if (!p.filled[i] && o.was == nullptr) continue;
            pattern_offset_fast(p.b.cos_angle[i], p.b.sin_angle[i], static_cast<float>(x - p.cx),
                                static_cast<float>(y - p.cy), h, o.ox, o.oy);
            const int* s = p.field.at(x, y);
            o.have = p.filled[i] ? appearance_at(p.stack, s[0], s[1]) : nullptr;
            overlap.push_back(o);
        }
    return first_best_candidate(p, rng, [&](int ux, int uy, float best) {
        // The same sum in the same order; stopping earlier only changes losing errors
        float error = 0.0f;
        for (std::size_t j = 0; j < overlap.size() && error < best; ++j) {
            const Overlap& o = overlap[j];
            const float* want = appearance_at(p.stack, ux + o.ox, uy + o.oy);
            if (o.have != nullptr)
                for (int c = 0; c < dims; ++c) {
                    const float d = o.have[c] - want[c];
                    error += alpha * (d * d);
                }
            if (o.was != nullptr)
                for (int c = 0; c < dims; ++c) {
                    const float d = o.was[c] - want[c];
                    error += beta * (d * d);
                }
        }
        return error;
    });
}

// Coarsest level: overlapping oriented patches in scanline order (Efros and Freeman 2001
// without the boundary cut), each the best for the objective of §5.1 (texture over the
// already-filled overlap, coherence with the advected previous frame) among the previous
// frame's coordinates at the patch centre's advected position and a keyed random set of grid
// positions.
Field initialize(const Image& stack, const LevelBuffers& b, const Field* previous,
                 const Advected& advected, const Field* held, const SynthesisOptions& options,
                 int frame_index, int level) {
    Field field{b.width, b.height,
                std::vector<int>(2 * static_cast<std::size_t>(b.width) * b.height)};
    std::vector<unsigned char> filled(static_cast<std::size_t>(b.width) * b.height, 0);
    // Held pixels are filled already: patches join them and leave them as they are
    if (held != nullptr)
        for (int y = 0; y < b.height; ++y)
            for (int x = 0; x < b.width; ++x)
                if (b.held[b.index(x, y)]) {
                    std::copy_n(held->at(x, y), 2, field.at(x, y));
                    filled[b.index(x, y)] = 1;
                }
    const int n = std::min({options.init_patch_size, b.width, b.height});
    const int half = n / 2;
    const float h = static_cast<float>(b.spacing);
    const int grid = b.spacing;
    const int grid_w = std::max(1, stack.width() / grid),
              grid_h = std::max(1, stack.height() / grid);
    std::vector<Overlap> overlap;
    overlap.reserve(static_cast<std::size_t>(n) * n);
    std::vector<std::pair<int, int>> anchored;
    int patch = 0;
    for (int cy = 0; cy < b.height; ++cy)
        for (int cx = 0; cx < b.width; ++cx) {
            if (filled[b.index(cx, cy)]) continue;
            const int x0 = std::max(0, cx - half), x1 = std::min(b.width, cx - half + n);
            const int y0 = std::max(0, cy - half), y1 = std::min(b.height, cy - half + n);
            KeyedRng rng(options.seed, 0x696e6974ull, static_cast<std::uint64_t>(frame_index),
                         static_cast<std::uint64_t>(level), static_cast<std::uint64_t>(patch++));
            // The previous frame's coordinates at the advected position of the centre, or of
            // the patch pixel nearest to it where the centre was not visible before
            anchored.clear();
            int ax = -1, ay = -1;
            if (previous != nullptr && !b.valid.empty())
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) {
                        const int d = (x - cx) * (x - cx) + (y - cy) * (y - cy);
                        if (b.valid[b.index(x, y)] &&
                            (ax < 0 || d < (ax - cx) * (ax - cx) + (ay - cy) * (ay - cy)))
                            ax = x, ay = y;
                    }
            if (ax >= 0) {
                const std::size_t i = b.index(ax, ay);
                int ox, oy;
                pattern_offset(b.cos_angle[i], b.sin_angle[i], static_cast<float>(ax - cx),
                               static_cast<float>(ay - cy), h, ox, oy);
                advected_candidates(b, *previous, ax, ay, b.cos_angle[i], b.sin_angle[i],
                                    pattern_offset,
                                    [&](int u, int v) { anchored.emplace_back(u - ox, v - oy); });
            }
            const PatchSearch search{stack, b,  field, filled, advected, options, anchored, cx,
                                     cy,    x0, x1,    y0,     y1,       grid,    grid_w,   grid_h};
            const auto [best_x, best_y] = options.reference_kernels
                                              ? best_patch_reference(search, rng)
                                              : best_patch_fast(search, rng, overlap);
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const std::size_t i = b.index(x, y);
                    if (held != nullptr && b.held[i]) continue;
                    int ox, oy;
                    pattern_offset(b.cos_angle[i], b.sin_angle[i], static_cast<float>(x - cx),
                                   static_cast<float>(y - cy), h, ox, oy);
                    int* s = field.at(x, y);
                    s[0] = wrap(best_x + ox, stack.width());
                    s[1] = wrap(best_y + oy, stack.height());
                    filled[i] = 1;
                }
        }
    return field;
}

// S_l[2i + Δ] = S_{l+1}[i] + Rot(-θ) Δ h_l (eq. 4).
Field upsample(const Field& parent, const LevelBuffers& b, const Image& stack, const Field* held,
               int threads) {
    Field field{b.width, b.height,
                std::vector<int>(2 * static_cast<std::size_t>(b.width) * b.height)};
    const float h = static_cast<float>(b.spacing);
    parallel_for(0, b.height, threads, [&](int y) {
        for (int x = 0; x < b.width; ++x) {
            const std::size_t i = b.index(x, y);
            const int* p =
                parent.at(std::min(x / 2, parent.width - 1), std::min(y / 2, parent.height - 1));
            int ox, oy;
            pattern_offset(b.cos_angle[i], b.sin_angle[i], static_cast<float>(x % 2),
                           static_cast<float>(y % 2), h, ox, oy);
            int* s = field.at(x, y);
            s[0] = wrap(p[0] + ox, stack.width());
            s[1] = wrap(p[1] + oy, stack.height());
            if (held != nullptr && b.held[i]) std::copy_n(held->at(x, y), 2, s);
        }
    });
    return field;
}

// Correction (§5.2.4): per pixel, the best of the coherence candidates and the advected
// previous coordinates for texture_weight·E_texture + coherence_weight·E_coherence.
// Cancelled if the context's token is set before a sub-pass. The plain scalar reference of
// correct_fast (SynthesisOptions::reference_kernels).
Status correct_reference(Field& field, const Image& stack, const LevelBuffers& b,
                         const Field* previous, const Advected& advected,
                         const SynthesisOptions& options, const RunContext& context) {
    const int dims = stack.channels();
    const float h = static_cast<float>(b.spacing);
    for (int pass = 0; pass < options.correction_passes; ++pass)
        for (int sub = 0; sub < 4; ++sub) {
            if (context.cancelled()) return cancelled();
            // Pixels of one parity read only pixels of other parities (3x3), so updating them
            // in place is independent of the order and of the thread count.
            parallel_for(0, b.height, context.threads, [&](int y) {
                if (y % 2 != sub / 2) return;
                std::vector<float> current(9 * static_cast<std::size_t>(dims));
                std::vector<float> prior(9 * static_cast<std::size_t>(dims));
                bool prior_valid[9];
                int offsets[9][2];
                std::vector<int> candidates;
                candidates.reserve(40);
                for (int x = sub % 2; x < b.width; x += 2) {
                    const std::size_t i = b.index(x, y);
                    if (!b.held.empty() && b.held[i]) continue;
                    const float c = b.cos_angle[i], s = b.sin_angle[i];
                    bool any_prior = false;
                    for (int k = 0; k < 9; ++k) {
                        const int dx = k % 3 - 1, dy = k / 3 - 1;
                        pattern_offset(c, s, static_cast<float>(dx), static_cast<float>(dy), h,
                                       offsets[k][0], offsets[k][1]);
                        const int nx = std::clamp(x + dx, 0, b.width - 1);
                        const int ny = std::clamp(y + dy, 0, b.height - 1);
                        const int* sn = field.at(nx, ny);
                        std::copy_n(appearance_at(stack, sn[0], sn[1]), dims,
                                    current.data() + k * dims);
                        const std::size_t j = b.index(nx, ny);
                        prior_valid[k] = !advected.valid.empty() && advected.valid[j];
                        if (prior_valid[k]) {
                            std::copy_n(
                                advected.appearance.data() + j * static_cast<std::size_t>(dims),
                                dims, prior.data() + k * dims);
                            any_prior = true;
                        }
                    }
                    // Candidates: this pixel's coordinate, the coherence candidates of its 3x3
                    // neighbours, and the previous frame's coordinates around the advected
                    // position (with the sub-pixel remainder of the motion)
                    candidates.clear();
                    for (int k = 0; k < 9; ++k) {
                        const int dx = k % 3 - 1, dy = k / 3 - 1;
                        const int* sn = field.at(std::clamp(x + dx, 0, b.width - 1),
                                                 std::clamp(y + dy, 0, b.height - 1));
                        candidates.push_back(sn[0] - offsets[k][0]);
                        candidates.push_back(sn[1] - offsets[k][1]);
                    }
                    if (previous != nullptr)
                        advected_candidates(b, *previous, x, y, c, s, pattern_offset,
                                            [&](int u, int v) {
                                                candidates.push_back(u);
                                                candidates.push_back(v);
                                            });
                    float best = std::numeric_limits<float>::infinity();
                    int best_x = field.at(x, y)[0], best_y = field.at(x, y)[1];
                    for (std::size_t k = 0; k < candidates.size(); k += 2) {
                        const int ux = wrap(candidates[k], stack.width());
                        const int uy = wrap(candidates[k + 1], stack.height());
                        candidates[k] = ux;
                        candidates[k + 1] = uy;
                        // Coherent neighbours propose the same coordinate: evaluate it once
                        bool seen = false;
                        for (std::size_t j = 0; j < k && !seen; j += 2)
                            seen = candidates[j] == ux && candidates[j + 1] == uy;
                        if (seen) continue;
                        float error = 0.0f;
                        for (int m = 0; m < 9 && error < best; ++m) {
                            const float* want =
                                appearance_at(stack, ux + offsets[m][0], uy + offsets[m][1]);
                            const float* have = current.data() + m * dims;
                            float texture = 0.0f, coherence = 0.0f;
                            for (int d = 0; d < dims; ++d) {
                                const float e = have[d] - want[d];
                                texture += e * e;
                            }
                            if (any_prior && prior_valid[m]) {
                                const float* was = prior.data() + m * dims;
                                for (int d = 0; d < dims; ++d) {
                                    const float e = was[d] - want[d];
                                    coherence += e * e;
                                }
                            }
                            error += options.texture_weight * texture +
                                     options.coherence_weight * coherence;
                        }
                        if (error < best) {
                            best = error;
                            best_x = ux;
                            best_y = uy;
                        }
                    }
                    int* out = field.at(x, y);
                    out[0] = wrap(best_x, stack.width());
                    out[1] = wrap(best_y, stack.height());
                }
            });
        }
    return Status::ok();
}

// texture_weight·Σ‖have − want‖² + coherence_weight·Σ‖was − want‖² over the 3x3 neighbours of
// pattern position (ux, uy), stopping once it reaches `best`; the same sums in the same order as
// correct_reference, so the same floats. Dims is the appearance dimension (0 = `dims`).
template <int Dims>
float candidate_error(const Image& stack, int ux, int uy, const int (*offsets)[2],
                      const float* const* have, const float* const* was, bool any_prior,
                      float texture_weight, float coherence_weight, float best, int dims) {
    const int n = Dims > 0 ? Dims : dims;
    float error = 0.0f;
    for (int m = 0; m < 9 && error < best; ++m) {
        const float* want = appearance_at(stack, ux + offsets[m][0], uy + offsets[m][1]);
        float texture = 0.0f, coherence = 0.0f;
        for (int d = 0; d < n; ++d) {
            const float e = have[m][d] - want[d];
            texture += e * e;
        }
        if (any_prior && was[m] != nullptr) {
            for (int d = 0; d < n; ++d) {
                const float e = was[m][d] - want[d];
                coherence += e * e;
            }
        }
        error += texture_weight * texture + coherence_weight * coherence;
    }
    return error;
}

// The correction of correct_reference, with the same candidates, order and sums, faster: the
// field's appearance is kept in one contiguous buffer (updated in place as pixels change; a
// pixel's 3x3 holds no other pixel of its parity), the neighbours are read through pointers
// instead of copies, the 3x3 offsets are computed without lround (and once per level when the
// orientation is constant 0), candidates live on the stack, and the error kernel is unrolled
// for the default 6 dimensions.
Status correct_fast(Field& field, const Image& stack, const LevelBuffers& b, const Field* previous,
                    const Advected& advected, const SynthesisOptions& options,
                    const RunContext& context) {
    const int dims = stack.channels();
    const float h = static_cast<float>(b.spacing);
    const int pw = stack.width(), ph = stack.height();
    std::vector<float> current(static_cast<std::size_t>(b.width) * b.height * dims);
    parallel_for(0, b.height, context.threads, [&](int y) {
        for (int x = 0; x < b.width; ++x) {
            const int* s = field.at(x, y);
            std::copy_n(appearance_at(stack, s[0], s[1]), dims,
                        current.data() + b.index(x, y) * dims);
        }
    });
    // The offsets of an unrotated pixel (orientation 0: cos 1, sin 0)
    int upright[9][2];
    for (int k = 0; k < 9; ++k)
        pattern_offset_fast(1.0f, 0.0f, static_cast<float>(k % 3 - 1),
                            static_cast<float>(k / 3 - 1), h, upright[k][0], upright[k][1]);
    const bool has_prior = !advected.valid.empty();
    const auto error_of = dims == 6 ? &candidate_error<6> : &candidate_error<0>;
    for (int pass = 0; pass < options.correction_passes; ++pass)
        for (int sub = 0; sub < 4; ++sub) {
            if (context.cancelled()) return cancelled();
            // As in correct_reference: one parity at a time, in place
            const int row0 = sub / 2;
            const int rows = (b.height - row0 + 1) / 2;
            parallel_for(0, rows, context.threads, [&](int r) {
                const int y = row0 + 2 * r;
                const float* have[9];
                const float* was[9];
                int rotated[9][2];
                int candidates[18][2];
                for (int x = sub % 2; x < b.width; x += 2) {
                    const std::size_t i = b.index(x, y);
                    if (!b.held.empty() && b.held[i]) continue;
                    const float c = b.cos_angle[i], s = b.sin_angle[i];
                    const int(*offsets)[2] = upright;
                    if (c != 1.0f || s != 0.0f) {
                        for (int k = 0; k < 9; ++k)
                            pattern_offset_fast(c, s, static_cast<float>(k % 3 - 1),
                                                static_cast<float>(k / 3 - 1), h, rotated[k][0],
                                                rotated[k][1]);
                        offsets = rotated;
                    }
                    bool any_prior = false;
                    int count = 0;
                    for (int k = 0; k < 9; ++k) {
                        const int nx = std::clamp(x + k % 3 - 1, 0, b.width - 1);
                        const int ny = std::clamp(y + k / 3 - 1, 0, b.height - 1);
                        const std::size_t j = b.index(nx, ny);
                        have[k] = current.data() + j * dims;
                        was[k] = has_prior && advected.valid[j]
                                     ? advected.appearance.data() + j * dims
                                     : nullptr;
                        any_prior = any_prior || was[k] != nullptr;
                        // Ashikhmin candidate of this neighbour
                        const int* sn = field.at(nx, ny);
                        candidates[count][0] = sn[0] - offsets[k][0];
                        candidates[count][1] = sn[1] - offsets[k][1];
                        ++count;
                    }
                    // The previous frame's coordinates around the advected position
                    if (previous != nullptr)
                        advected_candidates(b, *previous, x, y, c, s, pattern_offset_fast,
                                            [&](int u, int v) {
                                                candidates[count][0] = u;
                                                candidates[count][1] = v;
                                                ++count;
                                            });
                    float best = std::numeric_limits<float>::infinity();
                    int best_x = field.at(x, y)[0], best_y = field.at(x, y)[1];
                    // Coherent neighbours propose the same coordinate: evaluate it once (a
                    // candidate is compared with the distinct ones before it only)
                    std::uint64_t distinct[18];
                    int distinct_count = 0;
                    for (int k = 0; k < count; ++k) {
                        const int ux = wrap_near(candidates[k][0], pw);
                        const int uy = wrap_near(candidates[k][1], ph);
                        const std::uint64_t key =
                            static_cast<std::uint64_t>(ux) << 32 | static_cast<std::uint32_t>(uy);
                        bool seen = false;
                        for (int j = 0; j < distinct_count; ++j) seen |= distinct[j] == key;
                        if (seen) continue;
                        distinct[distinct_count++] = key;
                        const float error =
                            error_of(stack, ux, uy, offsets, have, was, any_prior,
                                     options.texture_weight, options.coherence_weight, best, dims);
                        if (error < best) {
                            best = error;
                            best_x = ux;
                            best_y = uy;
                        }
                    }
                    int* out = field.at(x, y);
                    out[0] = wrap_near(best_x, pw);
                    out[1] = wrap_near(best_y, ph);
                    std::copy_n(appearance_at(stack, out[0], out[1]), dims,
                                current.data() + i * dims);
                }
            });
        }
    return Status::ok();
}

Image appearance_image(const Field& field, const Image& stack, int threads) {
    Image out(field.width, field.height, stack.channels());
    parallel_for(0, field.height, threads, [&](int y) {
        for (int x = 0; x < field.width; ++x) {
            const int* s = field.at(x, y);
            std::copy_n(appearance_at(stack, s[0], s[1]), stack.channels(), out.pixel(x, y));
        }
    });
    return out;
}

Image coords_image(const Field& field) {
    Image out(field.width, field.height, 2);
    for (std::size_t i = 0; i < field.xy.size(); ++i)
        out.data()[i] = static_cast<float>(field.xy[i]);
    out.set_channel_names({"x", "y"});
    return out;
}

Field field_from_image(const Image& coords) {
    Field field{coords.width(), coords.height(), std::vector<int>(coords.size())};
    for (std::size_t i = 0; i < field.xy.size(); ++i)
        field.xy[i] = static_cast<int>(std::lround(coords.data()[i]));
    return field;
}

// I[i] = 1/N Σ_Δ P[S[i + Δ] − Rot(−θ)Δ] over 3x3 (eq. 5), or P[S[i]].
Image render_screen(const Field& field, const LevelBuffers& b, const Image& screen, bool blend,
                    int threads) {
    Image out(field.width, field.height, 1);
    parallel_for(0, field.height, threads, [&](int y) {
        for (int x = 0; x < field.width; ++x) {
            if (!blend) {
                const int* s = field.at(x, y);
                out.at(x, y, 0) = screen.at(s[0], s[1], 0);
                continue;
            }
            const std::size_t i = b.index(x, y);
            const float c = b.cos_angle[i], s = b.sin_angle[i];
            float sum = 0.0f;
            int count = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= field.width || ny >= field.height) continue;
                    const int* sn = field.at(nx, ny);
                    const float fx = static_cast<float>(sn[0]) -
                                     (c * static_cast<float>(dx) - s * static_cast<float>(dy));
                    const float fy = static_cast<float>(sn[1]) -
                                     (s * static_cast<float>(dx) + c * static_cast<float>(dy));
                    sum += screen_at(screen, fx, fy);
                    ++count;
                }
            out.at(x, y, 0) = sum / static_cast<float>(count);
        }
    });
    return out;
}

Status check_buffer(const Image& image, const FrameInput& input, int channels, const char* name) {
    if (image.empty()) return Status::ok();
    if (image.width() != input.width || image.height() != input.height ||
        image.channels() < channels)
        return invalid_argument(std::string(name) + ": " + std::to_string(image.width()) + "x" +
                                std::to_string(image.height()) + "x" +
                                std::to_string(image.channels()) + " does not match the frame " +
                                std::to_string(input.width) + "x" + std::to_string(input.height) +
                                " (needs " + std::to_string(channels) + " channels)");
    return Status::ok();
}

}  // namespace

Status validate(const SynthesisOptions& options) {
    if (options.init_patch_size < 3 || options.init_patch_size > 32)
        return invalid_argument("init_patch_size: " + std::to_string(options.init_patch_size) +
                                " is invalid (must be 3..32)");
    if (options.init_candidates < 1 || options.init_candidates > 100000)
        return invalid_argument("init_candidates: " + std::to_string(options.init_candidates) +
                                " is invalid (must be 1..100000)");
    if (options.correction_passes < 0 || options.correction_passes > 8)
        return invalid_argument("correction_passes: " + std::to_string(options.correction_passes) +
                                " is invalid (must be 0..8)");
    if (options.motion_levels < 0 || options.motion_levels > 6)
        return invalid_argument("motion_levels: " + std::to_string(options.motion_levels) +
                                " is invalid (must be 0..6)");
    if (!(options.texture_weight >= 0.0f && options.texture_weight <= 100.0f))
        return invalid_argument("texture_weight: " + std::to_string(options.texture_weight) +
                                " is invalid (must be in [0, 100])");
    if (!(options.coherence_weight >= 0.0f && options.coherence_weight <= 100.0f))
        return invalid_argument("coherence_weight: " + std::to_string(options.coherence_weight) +
                                " is invalid (must be in [0, 100])");
    return Status::ok();
}

Result<FrameState> synthesize_frame(const Pattern& pattern, const FrameInput& input,
                                    const FrameState* previous, int frame_index,
                                    const SynthesisOptions& options, const RunContext& context) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (context.threads < 0)
        return invalid_argument("threads: " + std::to_string(context.threads) +
                                " is invalid (must be >= 0)");
    if (pattern.stack.empty()) return invalid_argument("pattern: not prepared");
    const int levels = static_cast<int>(pattern.stack.size());
    const int min_size = 1 << (levels - 1);
    if (input.width < min_size || input.height < min_size)
        return invalid_argument("frame: " + std::to_string(input.width) + "x" +
                                std::to_string(input.height) + " is too small for " +
                                std::to_string(levels) + " levels");
    EXEMPLAR_RETURN_IF_ERROR(check_buffer(input.orientation, input, 1, "orientation"));
    EXEMPLAR_RETURN_IF_ERROR(check_buffer(input.backward_flow, input, 2, "backward_flow"));
    EXEMPLAR_RETURN_IF_ERROR(check_buffer(input.disocclusion, input, 1, "disocclusion"));
    const bool use_previous = previous != nullptr && !input.backward_flow.empty();
    if (use_previous && (static_cast<int>(previous->coords.size()) != levels ||
                         previous->coords[0].width() != input.width ||
                         previous->coords[0].height() != input.height))
        return invalid_argument("previous frame: its size or level count differs from this frame");
    EXEMPLAR_RETURN_IF_ERROR(check_buffer(input.hold, input, 1, "hold"));
    if (!input.hold.empty() &&
        (input.held == nullptr || static_cast<int>(input.held->coords.size()) != levels ||
         input.held->coords[0].width() != input.width ||
         input.held->coords[0].height() != input.height))
        return invalid_argument(
            "held: the hold mask needs held coordinates of this frame's size "
            "and level count");

    FrameState state;
    state.coords.resize(static_cast<std::size_t>(levels));
    state.appearance.resize(static_cast<std::size_t>(levels));
    Field field;
    LevelBuffers buffers;
    // Progress: the share of the pixels of all levels done (level l has 4^-l of the finest's)
    double work_total = 0.0, work_done = 0.0;
    for (int level = 0; level < levels; ++level) work_total += std::ldexp(1.0, -2 * level);
    for (int level = levels - 1; level >= 0; --level) {
        const Image& stack = pattern.stack[static_cast<std::size_t>(level)];
        buffers = sample_level(input, level, context.threads);
        // The previous frame's coordinates and appearance, advected
        Field previous_field;
        Advected advected;
        if (use_previous) {
            previous_field = field_from_image(previous->coords[static_cast<std::size_t>(level)]);
            advected = advect(previous->appearance[static_cast<std::size_t>(level)], buffers,
                              stack.channels(), context.threads);
        }
        Field held_field;
        if (!input.hold.empty())
            held_field = field_from_image(input.held->coords[static_cast<std::size_t>(level)]);
        const Field* held = input.hold.empty() ? nullptr : &held_field;
        // Initialize the coarsest level with patches, upsample the finer ones
        field = level == levels - 1
                    ? initialize(stack, buffers, use_previous ? &previous_field : nullptr, advected,
                                 held, options, frame_index, level)
                    : upsample(field, buffers, stack, held, context.threads);
        // Correct with coherence candidates and the advected previous frame
        const auto correct = options.reference_kernels ? &correct_reference : &correct_fast;
        // The previous frame's coordinates as candidates at each pixel: only at the coarsest
        // motion_levels levels (elsewhere they would carry the exact motion and grow the pattern
        // with a zoom)
        const bool motion_candidates = use_previous && level >= levels - options.motion_levels;
        EXEMPLAR_RETURN_IF_ERROR(correct(field, stack, buffers,
                                         motion_candidates ? &previous_field : nullptr, advected,
                                         options, context));
        state.coords[static_cast<std::size_t>(level)] = coords_image(field);
        state.appearance[static_cast<std::size_t>(level)] =
            appearance_image(field, stack, context.threads);
        work_done += std::ldexp(1.0, -2 * level);
        context.report({"synthesis", levels - 1 - level, levels, 0, 0, work_done / work_total});
    }
    state.screen =
        render_screen(field, buffers, pattern.screen, options.blend_coordinates, context.threads);
    return state;
}

Image pack_state(const FrameState& state) {
    if (state.coords.empty()) return {};
    const int levels = static_cast<int>(state.coords.size());
    Image packed(state.coords[0].width(), state.coords[0].height(), 2 * levels);
    std::vector<std::string> names;
    for (int l = 0; l < levels; ++l) {
        const Image& coords = state.coords[static_cast<std::size_t>(l)];
        for (int y = 0; y < coords.height(); ++y)
            for (int x = 0; x < coords.width(); ++x)
                for (int c = 0; c < 2; ++c) packed.at(x, y, 2 * l + c) = coords.at(x, y, c);
        // insert, not "x" + ...: GCC 12 warns (-Wrestrict) on that concatenation
        names.push_back(std::to_string(l).insert(0, 1, 'x'));
        names.push_back(std::to_string(l).insert(0, 1, 'y'));
    }
    packed.set_channel_names(names);
    return packed;
}

Result<FrameState> unpack_state(const Pattern& pattern, const Image& packed) {
    const int levels = static_cast<int>(pattern.stack.size());
    if (packed.channels() != 2 * levels)
        return invalid_argument("state: " + std::to_string(packed.channels()) +
                                " channels, but the pattern has " + std::to_string(levels) +
                                " levels (needs " + std::to_string(2 * levels) + ")");
    FrameState state;
    for (int l = 0; l < levels; ++l) {
        const int spacing = 1 << l;
        const int width = (packed.width() + spacing - 1) / spacing;
        const int height = (packed.height() + spacing - 1) / spacing;
        Field field{width, height, std::vector<int>(2 * static_cast<std::size_t>(width) * height)};
        // By name: a file format may reorder channels (OpenEXR sorts them)
        const int channel[2] = {find_channel(packed, std::to_string(l).insert(0, 1, 'x')),
                                find_channel(packed, std::to_string(l).insert(0, 1, 'y'))};
        if (channel[0] < 0 || channel[1] < 0)
            return invalid_argument("state: no channels x" + std::to_string(l) + ", y" +
                                    std::to_string(l));
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                for (int c = 0; c < 2; ++c) {
                    const float v = packed.at(x, y, channel[c]);
                    const int limit = c == 0 ? pattern.screen.width() : pattern.screen.height();
                    if (!(v >= 0.0f && v < static_cast<float>(limit)))
                        return invalid_argument("state: coordinate " + std::to_string(v) +
                                                " at level " + std::to_string(l) +
                                                " is outside the pattern");
                    field.at(x, y)[c] = static_cast<int>(v);
                }
        state.coords.push_back(coords_image(field));
        state.appearance.push_back(
            appearance_image(field, pattern.stack[static_cast<std::size_t>(l)], 1));
    }
    return state;
}

Status validate(const HalftoneOptions& options) {
    if (!(options.blur_sigma_px > 0.0f && options.blur_sigma_px <= 50.0f))
        return invalid_argument("blur_sigma_px: " + std::to_string(options.blur_sigma_px) +
                                " is invalid (must be in (0, 50])");
    return Status::ok();
}

Image halftone(const Image& screen, const Image& tone, const HalftoneOptions& options,
               int threads) {
    const auto threshold = [&](const Image& t) {
        Image out(screen.width(), screen.height(), 1);
        parallel_for(0, screen.height(), threads, [&](int y) {
            for (int x = 0; x < screen.width(); ++x)
                out.at(x, y, 0) = screen.at(x, y, 0) < 1.0f - t.at(x, y, 0) ? 0.0f : 1.0f;
        });
        return out;
    };
    Image first = threshold(tone);
    if (!options.tone_correction) return first;
    // Blur the result (the eye's integration), subtract its error from the tone, re-threshold
    const Image seen = gaussian_blur(first, options.blur_sigma_px, threads);
    Image adjusted(tone.width(), tone.height(), 1);
    parallel_for(0, tone.height(), threads, [&](int y) {
        for (int x = 0; x < tone.width(); ++x)
            adjusted.at(x, y, 0) =
                std::clamp(2.0f * tone.at(x, y, 0) - seen.at(x, y, 0), 0.0f, 1.0f);
    });
    return threshold(adjusted);
}

}  // namespace exemplar::npr
