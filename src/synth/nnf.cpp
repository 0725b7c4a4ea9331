#include "exemplar/synth/nnf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "exemplar/core/parallel.hpp"
#include "vote.hpp"

namespace exemplar {

namespace {

// std::lround for |v| < 2^63 without the libm call: the cast truncates, the remainder v - t is
// exact, and halves round away from zero.
std::int64_t round_half_away(double v) {
    const auto t = static_cast<std::int64_t>(v);
    const double rest = v - static_cast<double>(t);
    return rest >= 0.5 ? t + 1 : rest <= -0.5 ? t - 1 : t;
}

}  // namespace

// The same relative database position, the offset within the patch kept (rotated with the
// match). Serves the forward NNF (query = target, database = source) and the engine's reversed
// field (query = source, database = target). Runs between every two levels, over rows; the
// coarse pixel and offset of each column and row are computed once, and unrotated matches
// skip the rotation (cos 0 = 1 and sin 0 = 0 exactly: the same sums).
Nnf upsample_nnf(const Nnf& coarse, int coarse_db_w, int coarse_db_h, int fine_w, int fine_h,
                 int fine_db_w, int fine_db_h, int threads) {
    Nnf out(fine_w, fine_h);
    const double dx_scale = static_cast<double>(fine_db_w) / coarse_db_w;
    const double dy_scale = static_cast<double>(fine_db_h) / coarse_db_h;
    // The nearest coarse index of fine index i, and the offset of i's centre from it.
    const auto nearest = [](int coarse_n, int fine_n, std::vector<int>& index,
                            std::vector<double>& offset) {
        const double scale = static_cast<double>(coarse_n) / fine_n;
        index.resize(static_cast<std::size_t>(fine_n));
        offset.resize(static_cast<std::size_t>(fine_n));
        for (int i = 0; i < fine_n; ++i) {
            const double u = (i + 0.5) * scale - 0.5;
            const int c = std::clamp(static_cast<int>(std::lround(u)), 0, coarse_n - 1);
            index[static_cast<std::size_t>(i)] = c;
            offset[static_cast<std::size_t>(i)] = u - c;
        }
    };
    std::vector<int> cx, cy;
    std::vector<double> du, dv;
    nearest(coarse.width(), fine_w, cx, du);
    nearest(coarse.height(), fine_h, cy, dv);
    parallel_for(0, fine_h, threads, [&](int y) {
        const double v = dv[static_cast<std::size_t>(y)];
        for (int x = 0; x < fine_w; ++x) {
            const Match& m =
                coarse.at(cx[static_cast<std::size_t>(x)], cy[static_cast<std::size_t>(y)]);
            Match& o = out.at(x, y);
            if (m.x < 0) {
                o = Match{-1, -1, 0.0f, 0.0f};
                continue;
            }
            const double u = du[static_cast<std::size_t>(x)];
            double su = m.x + u, sv = m.y + v;
            if (m.angle_rad != 0.0f) {
                const double c = std::cos(m.angle_rad), s = std::sin(m.angle_rad);
                su = m.x + c * u - s * v;
                sv = m.y + s * u + c * v;
            }
            o.x = static_cast<int>(round_half_away((su + 0.5) * dx_scale - 0.5));
            o.y = static_cast<int>(round_half_away((sv + 0.5) * dy_scale - 0.5));
            o.angle_rad = m.angle_rad;
        }
    });
    return out;
}

Image nnf_to_image(const Nnf& nnf) {
    Image out(nnf.width(), nnf.height(), 4);
    for (std::size_t i = 0; i < nnf.pixel_count(); ++i) {
        const Match& m = nnf[i];
        float* p = out.data().data() + i * 4;
        p[0] = static_cast<float>(m.x);
        p[1] = static_cast<float>(m.y);
        p[2] = m.angle_rad;
        p[3] = m.error;
    }
    out.set_channel_names({"x", "y", "angle", "error"});
    return out;
}

Result<Nnf> nnf_from_image(const Image& image) {
    if (image.channels() != 3 && image.channels() != 4) {
        return invalid_argument("nnf: has " + std::to_string(image.channels()) +
                                " channels (must be 3 or 4: x, y, angle[, error])");
    }
    Nnf nnf(image.width(), image.height());
    for (std::size_t i = 0; i < nnf.pixel_count(); ++i) {
        const float* p = image.data().data() + i * static_cast<std::size_t>(image.channels());
        const bool none = p[0] == -1.0f && p[1] == -1.0f;
        if (!none && (!(p[0] >= 0.0f) || !(p[1] >= 0.0f))) {
            return invalid_argument("nnf: pixel " + std::to_string(i % nnf.width()) + "," +
                                    std::to_string(i / nnf.width()) +
                                    " holds a negative source position");
        }
        if (p[0] != std::floor(p[0]) || p[1] != std::floor(p[1]) || !std::isfinite(p[2]) ||
            p[0] > 1e8f || p[1] > 1e8f) {
            return invalid_argument("nnf: pixel " + std::to_string(i % nnf.width()) + "," +
                                    std::to_string(i / nnf.width()) +
                                    " holds an invalid source position (must be integers)");
        }
        nnf[i] = Match{static_cast<std::int32_t>(p[0]), static_cast<std::int32_t>(p[1]), p[2],
                       image.channels() == 4 ? p[3] : 0.0f};
    }
    return nnf;
}

Result<Image> apply_nnf(const Nnf& nnf, const Image& source, int patch_size, VoteMode mode,
                        int threads, int vote_size, float vote_coherence, bool vote_seams) {
    if (patch_size < 1 || patch_size % 2 == 0) {
        return invalid_argument("patch-size: " + std::to_string(patch_size) +
                                " is invalid (must be odd and positive)");
    }
    if (vote_size < 0 || (vote_size > 0 && vote_size % 2 == 0)) {
        return invalid_argument("vote-size: " + std::to_string(vote_size) +
                                " is invalid (must be 0 or odd)");
    }
    if (!(vote_coherence >= 0.0f) || !std::isfinite(vote_coherence)) {
        return invalid_argument("vote-coherence: " + std::to_string(vote_coherence) +
                                " is invalid (must be >= 0)");
    }
    if (nnf.empty() || source.empty()) return invalid_argument("apply_nnf: empty input");
    for (const Match& m : nnf.matches()) {
        if (m.x >= source.width() || m.y >= source.height()) {
            return invalid_argument("nnf refers to source position " + std::to_string(m.x) + "," +
                                    std::to_string(m.y) + " outside the " +
                                    std::to_string(source.width()) + "x" +
                                    std::to_string(source.height()) + " source");
        }
    }
    Image out(nnf.width(), nnf.height(), source.channels());
    out.set_channel_names(source.channel_names());
    synth::VoteParams params;
    params.patch_size = patch_size;
    params.footprint = vote_size;
    params.blend_seams = vote_seams;
    params.clamp_source = true;
    std::vector<float> weights;
    if (mode == VoteMode::Weighted) {
        weights = synth::vote_weights(nnf, nullptr, patch_size, vote_coherence, threads);
        params.patch_weights = weights;
    }
    synth::vote(nnf, source, params, out, threads);
    return out;
}

}  // namespace exemplar
