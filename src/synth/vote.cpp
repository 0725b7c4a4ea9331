#include "vote.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"
#include "patch_distance.hpp"

namespace exemplar::synth {

// Relative error at which a patch's weight has halved from its maximum: small values let good
// matches dominate the average (ebsynth's 1/(1+E) on 0..255 SSD behaves like ~0.001); 0.01 keeps
// the stroke texture of the stylit and texbynum examples (docs/algorithms.md).
constexpr double kWeightedVoteEpsilon = 0.01;

std::vector<float> vote_weights(const Nnf& nnf, const std::uint8_t* active, int patch_size,
                                float coherence, int threads) {
    auto votes = [&](std::size_t i) { return (active == nullptr || active[i]) && nnf[i].x >= 0; };
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < nnf.pixel_count(); ++i) {
        if (!votes(i)) continue;
        sum += nnf[i].error;
        ++n;
    }
    const double mean = n > 0 ? sum / static_cast<double>(n) : 0.0;
    std::vector<float> weights(nnf.pixel_count(), 1.0f);
    const int w = nnf.width(), h = nnf.height(), r = patch_size / 2;
    parallel_for(0, h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            float& weight = weights[i];
            if (mean > 0.0) {
                weight = static_cast<float>(1.0 / (kWeightedVoteEpsilon + nnf[i].error / mean));
            }
            if (!(coherence > 0.0f) || !votes(i)) continue;
            // Coherence: where this match puts each neighbour q, against q's own match.
            const Match& p = nnf[i];
            const double c = std::cos(p.angle_rad), s = std::sin(p.angle_rad);
            double agree = 0.0;
            for (int dy = -r; dy <= r; ++dy) {
                const int qy = y + dy;
                if (qy < 0 || qy >= h) continue;
                for (int dx = -r; dx <= r; ++dx) {
                    const int qx = x + dx;
                    if (qx < 0 || qx >= w) continue;
                    const std::size_t qi = static_cast<std::size_t>(qy) * w + qx;
                    if (!votes(qi)) continue;
                    const Match& q = nnf[qi];
                    const double ex = p.x + c * dx - s * dy - q.x;
                    const double ey = p.y + s * dx + c * dy - q.y;
                    agree += std::exp(-(ex * ex + ey * ey) / (2.0 * coherence));
                }
            }
            weight = static_cast<float>(weight * agree);
        }
    });
    return weights;
}

SourceHistogram::SourceHistogram(const Image& source) : source_(&source) {
    const int C = source.channels();
    const std::size_t n = source.pixel_count();
    lo_.resize(static_cast<std::size_t>(C));
    scale_.resize(static_cast<std::size_t>(C));
    for (int c = 0; c < C; ++c) {
        float mn = std::numeric_limits<float>::max(), mx = std::numeric_limits<float>::lowest();
        for (std::size_t i = 0; i < n; ++i) {
            mn = std::min(mn, source.data()[i * C + c]);
            mx = std::max(mx, source.data()[i * C + c]);
        }
        lo_[c] = mn;
        scale_[c] = mx > mn ? kHistogramBins / (mx - mn) : 0.0f;
    }
    // Counts are integers, so the density does not depend on the order of summation.
    bins_.resize(n * static_cast<std::size_t>(C));
    std::vector<std::int64_t> count(static_cast<std::size_t>(C) * kHistogramBins, 0);
    for (std::size_t i = 0; i < n; ++i) {
        for (int c = 0; c < C; ++c) {
            const int b = bin(source.data()[i * C + c], c);
            bins_[i * C + c] = static_cast<std::uint8_t>(b);
            ++count[c * kHistogramBins + b];
        }
    }
    density_.resize(count.size());
    for (std::size_t b = 0; b < count.size(); ++b) {
        density_[b] = n == 0 ? 0.0 : static_cast<double>(count[b]) / static_cast<double>(n);
    }
}

int SourceHistogram::bin(float value, int channel) const {
    return std::clamp(static_cast<int>((value - lo_[channel]) * scale_[channel]), 0,
                      kHistogramBins - 1);
}

std::vector<float> SourceHistogram::weights(const Image& target, const std::uint8_t* target_pixels,
                                            float strength, int threads) const {
    EXEMPLAR_CHECK_EQ(source_->channels(), target.channels());
    const int C = target.channels();
    const std::size_t sn = source_->pixel_count(), tn = target.pixel_count();
    std::vector<std::int64_t> target_count(density_.size(), 0);
    std::int64_t target_total = 0;
    for (std::size_t i = 0; i < tn; ++i) {
        if (target_pixels != nullptr && !target_pixels[i]) continue;
        ++target_total;
        for (int c = 0; c < C; ++c)
            ++target_count[c * kHistogramBins + bin(target.data()[i * C + c], c)];
    }
    std::vector<float> weights(sn, 1.0f);
    if (target_total == 0 || sn == 0) return weights;
    std::vector<double> excess(density_.size());
    for (std::size_t b = 0; b < excess.size(); ++b) {
        const double ht = static_cast<double>(target_count[b]) / static_cast<double>(target_total);
        excess[b] = std::max(0.0, (ht - density_[b]) * kHistogramBins);
    }
    const int sw = source_->width();
    parallel_for(0, source_->height(), threads, [&](int y) {
        for (int x = 0; x < sw; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * sw + x;
            double sum = 0.0;
            for (int c = 0; c < C; ++c) sum += excess[c * kHistogramBins + bins_[i * C + c]];
            weights[i] = static_cast<float>(1.0 / (1.0 + strength * sum));
        }
    });
    return weights;
}

std::vector<float> histogram_weights(const Image& source, const Image& target,
                                     const std::uint8_t* target_pixels, float strength,
                                     int threads) {
    return SourceHistogram(source).weights(target, target_pixels, strength, threads);
}

namespace {

// The vote with kChannels channels known at compile time (0 = any count, from the source), so
// that the per-pixel sums of the common 1-4 channel cases stay in registers.
template <int kChannels>
void vote_channels(const Nnf& nnf, const Image& source, const VoteParams& params, Image& out,
                   int threads) {
    const int w = nnf.width();
    const int h = nnf.height();
    const int C = kChannels > 0 ? kChannels : source.channels();
    const int patch_r = params.patch_size / 2;
    const int vote_r = params.footprint > 0 ? std::min(patch_r, params.footprint / 2) : patch_r;
    const bool blend_seams = params.blend_seams && vote_r < patch_r;
    // Each rotated match's cosine and sine, once: every pixel reads its patch_size² neighbours'.
    std::vector<std::array<float, 2>> rotation;
    bool rotated = false;
    for (std::size_t i = 0; i < nnf.pixel_count() && !rotated; ++i) {
        rotated = nnf[i].angle_rad != 0.0f;
    }
    if (rotated) {
        rotation.resize(nnf.pixel_count());
        parallel_for(0, h, threads, [&](int y) {
            for (std::size_t i = static_cast<std::size_t>(y) * w, end = i + w; i < end; ++i) {
                const float angle = nnf[i].angle_rad;
                if (angle != 0.0f) rotation[i] = {std::cos(angle), std::sin(angle)};
            }
        });
    }
    parallel_for(0, h, threads, [&](int y) {
        using Sums = std::conditional_t<(kChannels > 0), std::array<double, std::max(kChannels, 1)>,
                                        std::vector<double>>;
        Sums acc{};
        if constexpr (kChannels == 0) acc.resize(static_cast<std::size_t>(C));
        // The source pixel that the patch centred at (x - dx, y - dy) maps (x, y) to, or false
        // if that pixel is no voting patch centre.
        auto source_of = [&](int x, int dx, int dy, int& sx, int& sy) {
            const int cx = x - dx, cy = y - dy;
            if (cx < 0 || cx >= w || cy < 0 || cy >= h) return false;
            const std::size_t ci = static_cast<std::size_t>(cy) * w + cx;
            if (params.active != nullptr && !params.active[ci]) return false;
            const Match& m = nnf[ci];
            if (m.x < 0) return false;  // not a patch centre
            const RotatedOffset o = m.angle_rad == 0.0f
                                        ? RotatedOffset{dx, dy}
                                        : rotate_offset(dx, dy, rotation[ci][0], rotation[ci][1]);
            sx = m.x + o.dx;
            sy = m.y + o.dy;
            return true;
        };
        // Sum of the votes of the patches centred within r of (x, y), each weighing its patch
        // weight unless `plain`; returns their total weight.
        auto gather = [&](int x, int r, bool plain) {
            std::fill(acc.begin(), acc.end(), 0.0);
            double total = 0.0;
            // The patch centred at (x - dx, y - dy) covers this pixel at its offset (dx, dy).
            for (int dy = -r; dy <= r; ++dy) {
                for (int dx = -r; dx <= r; ++dx) {
                    int sx = 0, sy = 0;
                    if (!source_of(x, dx, dy, sx, sy)) continue;
                    const std::size_t ci = static_cast<std::size_t>(y - dy) * w + (x - dx);
                    const float weight =
                        params.patch_weights.empty() || plain ? 1.0f : params.patch_weights[ci];
                    if (!(weight > 0.0f)) continue;
                    if (params.clamp_source) {
                        sx = std::clamp(sx, 0, source.width() - 1);
                        sy = std::clamp(sy, 0, source.height() - 1);
                    }
                    EXEMPLAR_DCHECK(sx >= 0 && sy >= 0 && sx < source.width() &&
                                    sy < source.height());
                    const float* s = source.pixel(sx, sy);
                    const float vote_weight =
                        params.source_weights.empty()
                            ? weight
                            : weight * params.source_weights[static_cast<std::size_t>(sy) *
                                                                 source.width() +
                                                             sx];
                    for (int c = 0; c < C; ++c) {
                        acc[static_cast<std::size_t>(c)] += vote_weight * s[c];
                    }
                    total += vote_weight;
                }
            }
            return total;
        };
        // Whether the patches centred within vote_r of (x, y) map it to different source pixels.
        auto seam_at = [&](int x) {
            int fx = 0, fy = 0;
            bool first = true;
            for (int dy = -vote_r; dy <= vote_r; ++dy) {
                for (int dx = -vote_r; dx <= vote_r; ++dx) {
                    int sx = 0, sy = 0;
                    if (!source_of(x, dx, dy, sx, sy)) continue;
                    if (first) {
                        fx = sx;
                        fy = sy;
                        first = false;
                    } else if (sx != fx || sy != fy) {
                        return true;
                    }
                }
            }
            return false;
        };
        for (int x = 0; x < w; ++x) {
            const std::size_t qi = static_cast<std::size_t>(y) * w + x;
            if (params.fixed != nullptr && params.fixed[qi]) continue;
            double total = blend_seams && seam_at(x) ? gather(x, patch_r, /*plain=*/true)
                                                     : gather(x, vote_r, /*plain=*/false);
            if (total <= 0.0 && vote_r < patch_r) total = gather(x, patch_r, /*plain=*/false);
            if (total <= 0.0) continue;
            float* o = out.pixel(x, y);
            for (int c = 0; c < C; ++c) {
                o[c] = static_cast<float>(acc[static_cast<std::size_t>(c)] / total);
            }
        }
    });
}

}  // namespace

void vote(const Nnf& nnf, const Image& source, const VoteParams& params, Image& out, int threads) {
    EXEMPLAR_CHECK_EQ(out.width(), nnf.width());
    EXEMPLAR_CHECK_EQ(out.height(), nnf.height());
    EXEMPLAR_CHECK_EQ(out.channels(), source.channels());
    switch (source.channels()) {
        case 1: vote_channels<1>(nnf, source, params, out, threads); break;
        case 3: vote_channels<3>(nnf, source, params, out, threads); break;
        case 4: vote_channels<4>(nnf, source, params, out, threads); break;
        default: vote_channels<0>(nnf, source, params, out, threads); break;
    }
}

}  // namespace exemplar::synth
