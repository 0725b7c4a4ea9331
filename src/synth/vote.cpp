#include "vote.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "coherence.hpp"
#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"
#include "patch_distance.hpp"

namespace exemplar::synth {

// Relative error at which a patch's weight has halved from its maximum: small values let good
// matches dominate the average (ebsynth's 1/(1+E) on 0..255 SSD behaves like ~0.001); 0.01 keeps
// the stroke texture of the stylit and texbynum examples (docs/algorithms.md).
constexpr double kWeightedVoteEpsilon = 0.01;

namespace {

// Fields with more distinct angles than this take the per-pixel paths of the vote and of the
// coherence weights (Brushables' fields have 32, one per orientation step).
constexpr std::size_t kMaxFieldAngles = 256;

// The distinct angles of a field's matches: 0 (whether or not it occurs), then the others in
// increasing order; empty when there are more than kMaxFieldAngles. The vote and the coherence
// weights tabulate what they need per angle instead of per match.
std::vector<float> field_angles(const Nnf& nnf) {
    std::vector<float> angles{0.0f};
    float last = 0.0f;
    for (const Match& m : nnf.matches()) {
        if (m.angle_rad == 0.0f || m.angle_rad == last) continue;
        last = m.angle_rad;
        const auto at = std::lower_bound(angles.begin() + 1, angles.end(), last);
        if (at != angles.end() && *at == last) continue;
        if (angles.size() > kMaxFieldAngles) return {};
        angles.insert(at, last);
    }
    return angles;
}

// The index of `angle`, one of field_angles' `angles`.
int angle_index(const std::vector<float>& angles, float angle) {
    if (angle == 0.0f) return 0;
    return static_cast<int>(std::lower_bound(angles.begin() + 1, angles.end(), angle) -
                            angles.begin());
}

// One axis of a coherence term: exp(-e² / 2σ²) for e = dd + o, the difference dd of two
// matches' coordinates and the rotated patch offset o along the axis.
double coherence_factor(int dd, double o, double two_sigma2) {
    const double e = static_cast<double>(dd) + o;
    return std::exp(-(e * e) / two_sigma2);
}

// The coherence terms' cut: matches whose coordinates differ by more than this count 0. Their
// factor is below e^-36 (1e-16, under a double's precision next to a match's own term of 1):
// |e| >= reach - r√2 >= √(72σ²).
int coherence_reach(int r, float coherence) {
    return static_cast<int>(
        std::ceil(static_cast<double>(r) * 1.41422 + std::sqrt(72.0 * coherence)));
}

// Tables with more entries than this (a wide coherence range) are not built.
constexpr std::size_t kMaxCoherenceTable = std::size_t{1} << 20;

std::vector<float> weights_of(const Nnf& nnf, const std::uint8_t* active, int patch_size,
                              float coherence, int threads, bool reference) {
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
    const int w = nnf.width(), h = nnf.height(), r = patch_size / 2, P = 2 * r + 1;
    const double two_sigma2 = 2.0 * coherence;
    const int reach = coherence > 0.0f ? coherence_reach(r, coherence) : 0;
    const std::size_t area = static_cast<std::size_t>(P) * P;
    // Per angle and patch offset (dx, dy) (row-major), a row of the factors of dd = -reach..reach
    // for o = c·dx − s·dy between two zeros (the factor of any dd beyond: adding a term of 0
    // leaves a sum of non-negative terms as it is, as the reference's skipping it does). The y
    // factor of (dx, dy), o = s·dx + c·dy, is the x factor of (dy, −dx): the same products and
    // sum, to the bit.
    std::vector<float> angles;
    std::vector<double> table;
    const std::size_t row = 2 * static_cast<std::size_t>(reach) + 3;
    if (!reference && coherence > 0.0f) angles = field_angles(nnf);
    if (angles.size() * area * row > kMaxCoherenceTable) angles.clear();
    if (!angles.empty()) {
        table.resize(angles.size() * area * row, 0.0);
        parallel_for(0, static_cast<int>(angles.size()), threads, [&](int a) {
            const float angle = angles[static_cast<std::size_t>(a)];
            const double c = std::cos(angle), s = std::sin(angle);
            double* out = table.data() + static_cast<std::size_t>(a) * area * row;
            for (int dy = -r; dy <= r; ++dy) {
                for (int dx = -r; dx <= r; ++dx, out += row) {
                    for (int dd = -reach; dd <= reach; ++dd) {
                        out[dd + reach + 1] = coherence_factor(dd, c * dx - s * dy, two_sigma2);
                    }
                }
            }
        });
    }
    parallel_for(0, h, threads, [&](int y) {
        const std::size_t y0 = static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            if (mean > 0.0) {
                weights[y0 + x] =
                    static_cast<float>(1.0 / (kWeightedVoteEpsilon + nnf[y0 + x].error / mean));
            }
        }
        if (!(coherence > 0.0f)) return;
        // Coherence: where each match puts its neighbours q, against q's own matches.
        if (angles.empty()) {
            for (int x = 0; x < w; ++x) {
                const std::size_t i = y0 + x;
                if (!votes(i)) continue;
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
                        const int ddx = p.x - q.x, ddy = p.y - q.y;
                        if (std::abs(ddx) > reach || std::abs(ddy) > reach) continue;
                        agree += coherence_factor(ddx, c * dx - s * dy, two_sigma2) *
                                 coherence_factor(ddy, s * dx + c * dy, two_sigma2);
                    }
                }
                weights[i] = static_cast<float>(weights[i] * agree);
            }
            return;
        }
        // The same sums from the tables, the loops turned inside out: the row's pixels take
        // the terms of one neighbour offset after another (each pixel's in the reference's
        // order), so that a pixel's chain of dependent additions does not stall the loop.
        std::vector<double> agree(static_cast<std::size_t>(w), 0.0);
        if (angles.size() == 1) {
            // Unrotated: the SIMD kernel, several pixels per step (coherence.hpp).
            add_coherence_row(
                CoherenceRow{nnf.matches().data(), active, w, h, r, reach, table.data(), row}, y,
                agree.data());
            for (int x = 0; x < w; ++x) {
                const std::size_t i = y0 + x;
                if (votes(i)) {
                    weights[i] =
                        static_cast<float>(weights[i] * agree[static_cast<std::size_t>(x)]);
                }
            }
            return;
        }
        std::vector<const double*> factors(static_cast<std::size_t>(w), nullptr);
        for (int x = 0; x < w; ++x) {
            const std::size_t i = y0 + x;
            if (!votes(i)) continue;
            factors[static_cast<std::size_t>(x)] =
                table.data() +
                static_cast<std::size_t>(angle_index(angles, nnf[i].angle_rad)) * area * row;
        }
        const int lo = -reach - 1, hi = reach + 1;
        for (int dy = -r; dy <= r; ++dy) {
            const int qy = y + dy;
            if (qy < 0 || qy >= h) continue;
            const std::size_t q0 = static_cast<std::size_t>(qy) * w;
            for (int dx = -r; dx <= r; ++dx) {
                const std::size_t kx = static_cast<std::size_t>((dy + r) * P + dx + r) * row;
                const std::size_t ky = static_cast<std::size_t>((r - dx) * P + dy + r) * row;
                for (int x = std::max(0, -dx), x_end = std::min(w, w - dx); x < x_end; ++x) {
                    const double* f = factors[static_cast<std::size_t>(x)];
                    const std::size_t qi = q0 + static_cast<std::size_t>(x + dx);
                    if (f == nullptr || !votes(qi)) continue;
                    const Match& p = nnf[y0 + x];
                    const Match& q = nnf[qi];
                    const int ddx = std::clamp(p.x - q.x, lo, hi) + reach + 1;
                    const int ddy = std::clamp(p.y - q.y, lo, hi) + reach + 1;
                    agree[static_cast<std::size_t>(x)] += f[kx + static_cast<std::size_t>(ddx)] *
                                                          f[ky + static_cast<std::size_t>(ddy)];
                }
            }
        }
        for (int x = 0; x < w; ++x) {
            if (factors[static_cast<std::size_t>(x)] == nullptr) continue;
            weights[y0 + x] =
                static_cast<float>(weights[y0 + x] * agree[static_cast<std::size_t>(x)]);
        }
    });
    return weights;
}

}  // namespace

std::vector<float> vote_weights(const Nnf& nnf, const std::uint8_t* active, int patch_size,
                                float coherence, int threads) {
    return weights_of(nnf, active, patch_size, coherence, threads, /*reference=*/false);
}

std::vector<float> vote_weights_reference(const Nnf& nnf, const std::uint8_t* active,
                                          int patch_size, float coherence, int threads) {
    return weights_of(nnf, active, patch_size, coherence, threads, /*reference=*/true);
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

// Per-channel sums of one pixel: a fixed array for kChannels > 0 (registers), else a vector.
template <int kChannels>
using Sums = std::conditional_t<(kChannels > 0), std::array<double, std::max(kChannels, 1)>,
                                std::vector<double>>;

// What every vote of one NNF shares: the parameters, the source and, for a rotated field, its
// distinct angles (field_angles: the row vote's offset tables, one per angle) or, on the
// per-pixel path, each match's cosine and sine (once: every pixel reads its patch_size²
// neighbours').
struct VoteSetup {
    VoteSetup(const Nnf& nnf_, const Image& source_, const VoteParams& params_, int threads,
              bool reference)
        : nnf(nnf_), source(source_), params(params_), w(nnf_.width()), h(nnf_.height()) {
        patch_r = params.patch_size / 2;
        vote_r = params.footprint > 0 ? std::min(patch_r, params.footprint / 2) : patch_r;
        blend_seams = params.blend_seams && vote_r < patch_r;
        if (!reference) angles = field_angles(nnf);
        const bool rotated =
            std::ranges::any_of(nnf.matches(), [](const Match& m) { return m.angle_rad != 0.0f; });
        if (rotated && angles.empty()) {
            rotation.resize(nnf.pixel_count());
            parallel_for(0, h, threads, [&](int y) {
                for (std::size_t i = static_cast<std::size_t>(y) * w, end = i + w; i < end; ++i) {
                    const float angle = nnf[i].angle_rad;
                    if (angle != 0.0f) rotation[i] = {std::cos(angle), std::sin(angle)};
                }
            });
        }
    }

    // Patch offset (dx, dy) of the match of pixel i, at `angle`.
    RotatedOffset offset(std::size_t i, float angle, int dx, int dy) const {
        if (angle == 0.0f || rotation.empty()) return turned(angle, dx, dy);
        return rotate_offset(dx, dy, rotation[i][0], rotation[i][1]);
    }
    static RotatedOffset turned(float angle, int dx, int dy) {
        if (angle == 0.0f) return {dx, dy};
        return rotate_offset(dx, dy, std::cos(angle), std::sin(angle));
    }

    const Nnf& nnf;
    const Image& source;
    const VoteParams& params;
    int w, h, patch_r = 0, vote_r = 0;
    bool blend_seams = false;
    std::vector<float> angles;  // field_angles; empty on the per-pixel path
    std::vector<std::array<float, 2>> rotation;
};

// The vote's definition, one target pixel at a time (row y): the reference, and the fast row
// vote's path for seams and for pixels its footprint leaves without votes.
template <int kChannels>
class PixelVote {
public:
    PixelVote(const VoteSetup& setup, int y) : v_(setup), y_(y) {
        if constexpr (kChannels == 0) acc.resize(static_cast<std::size_t>(setup.source.channels()));
    }

    // The source pixel that the patch centred at (x - dx, y - dy) maps (x, y) to, or false if
    // that pixel is no voting patch centre.
    bool source_of(int x, int dx, int dy, int& sx, int& sy) const {
        const int cx = x - dx, cy = y_ - dy;
        if (cx < 0 || cx >= v_.w || cy < 0 || cy >= v_.h) return false;
        const std::size_t ci = static_cast<std::size_t>(cy) * v_.w + cx;
        if (v_.params.active != nullptr && !v_.params.active[ci]) return false;
        const Match& m = v_.nnf[ci];
        if (m.x < 0) return false;  // not a patch centre
        const RotatedOffset o = v_.offset(ci, m.angle_rad, dx, dy);
        sx = m.x + o.dx;
        sy = m.y + o.dy;
        return true;
    }

    // Sum of the votes of the patches centred within r of (x, y) into `acc`, each weighing its
    // patch weight unless `plain`; returns their total weight.
    double gather(int x, int r, bool plain) {
        const VoteParams& params = v_.params;
        const Image& source = v_.source;
        const int C = channels();
        std::fill(acc.begin(), acc.end(), 0.0);
        double total = 0.0;
        // The patch centred at (x - dx, y - dy) covers this pixel at its offset (dx, dy).
        for (int dy = -r; dy <= r; ++dy) {
            for (int dx = -r; dx <= r; ++dx) {
                int sx = 0, sy = 0;
                if (!source_of(x, dx, dy, sx, sy)) continue;
                const std::size_t ci = static_cast<std::size_t>(y_ - dy) * v_.w + (x - dx);
                const float weight =
                    params.patch_weights.empty() || plain ? 1.0f : params.patch_weights[ci];
                if (!(weight > 0.0f)) continue;
                if (params.clamp_source) {
                    sx = std::clamp(sx, 0, source.width() - 1);
                    sy = std::clamp(sy, 0, source.height() - 1);
                }
                EXEMPLAR_DCHECK(sx >= 0 && sy >= 0 && sx < source.width() && sy < source.height());
                const float* s = source.pixel(sx, sy);
                const float vote_weight =
                    params.source_weights.empty()
                        ? weight
                        : weight *
                              params.source_weights[static_cast<std::size_t>(sy) * source.width() +
                                                    sx];
                for (int c = 0; c < C; ++c) acc[static_cast<std::size_t>(c)] += vote_weight * s[c];
                total += vote_weight;
            }
        }
        return total;
    }

    // Whether the patches centred within vote_r of (x, y) map it to different source pixels.
    bool seam_at(int x) const {
        int fx = 0, fy = 0;
        bool first = true;
        for (int dy = -v_.vote_r; dy <= v_.vote_r; ++dy) {
            for (int dx = -v_.vote_r; dx <= v_.vote_r; ++dx) {
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
    }

    // Pixel x's total weight with its sums in `acc`: across a seam the plain average of the
    // whole patches, else the footprint's weighted vote, else (no footprint patch) the whole
    // patches'. `footprint_total` is the footprint's total if already summed (then in `acc`).
    double vote_at(int x, const double* footprint_total = nullptr) {
        if (v_.blend_seams && seam_at(x)) return gather(x, v_.patch_r, /*plain=*/true);
        double total =
            footprint_total != nullptr ? *footprint_total : gather(x, v_.vote_r, /*plain=*/false);
        if (total <= 0.0 && v_.vote_r < v_.patch_r) total = gather(x, v_.patch_r, false);
        return total;
    }

    int channels() const { return kChannels > 0 ? kChannels : v_.source.channels(); }

    Sums<kChannels> acc{};

private:
    const VoteSetup& v_;
    int y_;
};

template <int kChannels>
void write_vote(const Sums<kChannels>& acc, double total, int channels, float* out) {
    for (int c = 0; c < channels; ++c) {
        out[c] = static_cast<float>(acc[static_cast<std::size_t>(c)] / total);
    }
}

// The reference: every pixel gathers its votes on its own.
template <int kChannels>
void vote_pixels(const VoteSetup& v, Image& out, int threads) {
    parallel_for(0, v.h, threads, [&](int y) {
        PixelVote<kChannels> pixel(v, y);
        for (int x = 0; x < v.w; ++x) {
            const std::size_t qi = static_cast<std::size_t>(y) * v.w + x;
            if (v.params.fixed != nullptr && v.params.fixed[qi]) continue;
            const double total = pixel.vote_at(x);
            if (total > 0.0)
                write_vote<kChannels>(pixel.acc, total, pixel.channels(), out.pixel(x, y));
        }
    });
}

// A voting patch centre as the row vote reads it: its weight (0 = it does not vote: inactive,
// no match, or a weight that is not positive), its match's source pixel index when the match's
// rotated footprint lies inside the source, else -1 (clamped reads, from the NNF), and its
// angle's offset table.
struct Centre {
    float weight;
    std::int32_t index;
    std::int32_t table;
};

// Adds the vote of weight w read from source pixel s to a pixel's sums: kChannels channels
// (0 = `channels`) and the total weight after them. The product is rounded to float before it
// is added in double, as in PixelVote::gather.
template <int kChannels>
inline void add_vote(double* sums, const float* s, float w, int channels) {
    const int C = kChannels > 0 ? kChannels : channels;
    for (int k = 0; k < C; ++k) sums[k] += w * s[k];
    sums[C] += w;
}

// The same sums as vote_pixels, with the loops turned inside out: a row's pixels take the votes
// of one patch offset (dy, dx) after another, so every pixel adds the same terms in the same
// order as the reference (exact to the bit), while its chain of dependent double additions no
// longer stalls the loop: neighbouring pixels' additions are independent. A rotated match reads
// its offsets from its angle's table (VoteSetup::angles), each vote times its source pixel's
// weight when there are source weights, as in PixelVote::gather. Seams and pixels without a
// footprint patch take the reference's per-pixel path.
template <int kChannels>
void vote_rows(const VoteSetup& v, Image& out, int threads) {
    const VoteParams& params = v.params;
    const int w = v.w, h = v.h, r = v.vote_r, P = 2 * r + 1;
    const int sw = v.source.width(), sh = v.source.height();
    const float* source = v.source.data().data();
    const float* source_weights =
        params.source_weights.empty() ? nullptr : params.source_weights.data();
    // Per table, the footprint's offsets (row-major) and their index offsets in the source.
    const auto area = static_cast<std::size_t>(P) * P;
    std::vector<RotatedOffset> moves(v.angles.size() * area);
    std::vector<std::int32_t> offsets(moves.size());
    int reach = 0;  // the largest offset coordinate of any table
    for (std::size_t t = 0; t < v.angles.size(); ++t) {
        const float angle = v.angles[t];
        for (int dy = -r, k = 0; dy <= r; ++dy) {
            for (int dx = -r; dx <= r; ++dx, ++k) {
                const RotatedOffset o = VoteSetup::turned(angle, dx, dy);
                moves[t * area + static_cast<std::size_t>(k)] = o;
                offsets[t * area + static_cast<std::size_t>(k)] = o.dy * sw + o.dx;
                reach = std::max({reach, std::abs(o.dx), std::abs(o.dy)});
            }
        }
    }
    // Bands of output rows, each with the centres of its rows and r rows around them (a table
    // of the whole field would add its size to the run's peak memory).
    constexpr int kBand = 8;
    parallel_for(0, (h + kBand - 1) / kBand, threads, [&](int band) {
        const int y0 = band * kBand, y1 = std::min(h, y0 + kBand);
        const int c0 = std::max(0, y0 - r), c1 = std::min(h, y1 + r);
        std::vector<Centre> centres(static_cast<std::size_t>(c1 - c0) * w);
        for (std::size_t i = static_cast<std::size_t>(c0) * w,
                         end = static_cast<std::size_t>(c1) * w;
             i < end; ++i) {
            const Match& m = v.nnf[i];
            float weight = params.patch_weights.empty() ? 1.0f : params.patch_weights[i];
            if ((params.active != nullptr && !params.active[i]) || m.x < 0 || !(weight > 0.0f)) {
                weight = 0.0f;
            }
            const int table = weight > 0.0f ? angle_index(v.angles, m.angle_rad) : 0;
            const int margin = table == 0 ? r : reach;
            const bool inside =
                m.x - margin >= 0 && m.y - margin >= 0 && m.x + margin < sw && m.y + margin < sh;
            centres[i - static_cast<std::size_t>(c0) * w] =
                Centre{weight, inside ? m.y * sw + m.x : -1, table};
        }
        const int C = kChannels > 0 ? kChannels : v.source.channels();
        const std::size_t stride = static_cast<std::size_t>(C) + 1;  // the sums, then the total
        std::vector<double> sums(static_cast<std::size_t>(w) * stride);
        for (int y = y0; y < y1; ++y) {
            PixelVote<kChannels> pixel(v, y);
            std::fill(sums.begin(), sums.end(), 0.0);
            for (int dy = -r; dy <= r; ++dy) {
                const int cy = y - dy;
                if (cy < 0 || cy >= h) continue;
                const Centre* row = centres.data() + static_cast<std::size_t>(cy - c0) * w;
                for (int dx = -r; dx <= r; ++dx) {
                    const auto k = static_cast<std::size_t>((dy + r) * P + dx + r);
                    // The pixels x whose patch centre x - dx lies in the row.
                    for (int x = std::max(0, dx), x_end = std::min(w, w + dx); x < x_end; ++x) {
                        const Centre& c = row[x - dx];
                        if (!(c.weight > 0.0f)) continue;
                        const std::size_t at = static_cast<std::size_t>(c.table) * area + k;
                        std::int32_t index = c.index + offsets[at];
                        if (c.index < 0) {
                            const Match& m = v.nnf.at(x - dx, cy);
                            int sx = m.x + moves[at].dx, sy = m.y + moves[at].dy;
                            if (params.clamp_source) {
                                sx = std::clamp(sx, 0, sw - 1);
                                sy = std::clamp(sy, 0, sh - 1);
                            }
                            EXEMPLAR_DCHECK(sx >= 0 && sy >= 0 && sx < sw && sy < sh);
                            index = sy * sw + sx;
                        }
                        const float weight =
                            source_weights == nullptr ? c.weight : c.weight * source_weights[index];
                        add_vote<kChannels>(sums.data() + static_cast<std::size_t>(x) * stride,
                                            source + static_cast<std::size_t>(index) * C, weight,
                                            C);
                    }
                }
            }
            for (int x = 0; x < w; ++x) {
                const std::size_t qi = static_cast<std::size_t>(y) * w + x;
                if (params.fixed != nullptr && params.fixed[qi]) continue;
                const double* s = sums.data() + static_cast<std::size_t>(x) * stride;
                std::copy_n(s, C, pixel.acc.begin());
                const double t = pixel.vote_at(x, &s[C]);
                if (t > 0.0) write_vote<kChannels>(pixel.acc, t, C, out.pixel(x, y));
            }
        }
    });
}

template <int kChannels>
void vote_channels(const Nnf& nnf, const Image& source, const VoteParams& params, Image& out,
                   int threads, bool reference) {
    const VoteSetup setup(nnf, source, params, threads, reference);
    // The row vote's source indices are 32-bit.
    const bool small = source.pixel_count() <= static_cast<std::size_t>(INT32_MAX);
    if (reference || setup.angles.empty() || !small) {
        vote_pixels<kChannels>(setup, out, threads);
    } else {
        vote_rows<kChannels>(setup, out, threads);
    }
}

void vote_dispatch(const Nnf& nnf, const Image& source, const VoteParams& params, Image& out,
                   int threads, bool reference) {
    EXEMPLAR_CHECK_EQ(out.width(), nnf.width());
    EXEMPLAR_CHECK_EQ(out.height(), nnf.height());
    EXEMPLAR_CHECK_EQ(out.channels(), source.channels());
    switch (source.channels()) {
        case 1: vote_channels<1>(nnf, source, params, out, threads, reference); break;
        case 3: vote_channels<3>(nnf, source, params, out, threads, reference); break;
        case 4: vote_channels<4>(nnf, source, params, out, threads, reference); break;
        default: vote_channels<0>(nnf, source, params, out, threads, reference); break;
    }
}

}  // namespace

void vote(const Nnf& nnf, const Image& source, const VoteParams& params, Image& out, int threads) {
    vote_dispatch(nnf, source, params, out, threads, /*reference=*/false);
}

void vote_reference(const Nnf& nnf, const Image& source, const VoteParams& params, Image& out,
                    int threads) {
    vote_dispatch(nnf, source, params, out, threads, /*reference=*/true);
}

}  // namespace exemplar::synth
