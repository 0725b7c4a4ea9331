#include "level_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"
#include "exemplar/filters/resample.hpp"
#include "guide_pca.hpp"
#include "patch_distance.hpp"

namespace exemplar::synth {

namespace {

int footprint_radius(int patch_size, bool rotated) {
    const int r = patch_size / 2;
    return rotated ? static_cast<int>(std::ceil(static_cast<float>(r) * std::sqrt(2.0f))) : r;
}

// An input at one pyramid depth: the input itself at depth 0 (no copy), else resampled from it
// as gaussian_pyramid does (every level from full resolution). Built when a level starts and
// dropped when it ends, so no run holds the pyramids of all its inputs.
class AtDepth {
public:
    AtDepth(const Image& full, int depth, float ratio, ResampleFilter filter, int threads)
        : full_(&full) {
        if (depth == 0 || full.empty()) return;
        resized_ = resize(full, pyramid_level_size(full.width(), ratio, depth),
                          pyramid_level_size(full.height(), ratio, depth), filter, threads);
    }
    const Image& get() const { return resized_.empty() ? *full_ : resized_; }
    /// The image for a level to own: the resampled one moved out (no copy), else the input's
    /// copy. get() is empty afterwards at depth > 0.
    Image take() { return resized_.empty() ? *full_ : std::move(resized_); }

private:
    const Image* full_;
    Image resized_;
};

bool same_channel(const Image& a, int ca, const Image& b, int cb) {
    if (!a.same_size(b)) return false;
    const auto na = static_cast<std::size_t>(a.channels());
    const auto nb = static_cast<std::size_t>(b.channels());
    for (std::size_t i = 0; i < a.pixel_count(); ++i) {
        if (a.data()[i * na + static_cast<std::size_t>(ca)] !=
            b.data()[i * nb + static_cast<std::size_t>(cb)]) {
            return false;
        }
    }
    return true;
}

bool constant_channel(const Image& image, int c, float value) {
    const auto n = static_cast<std::size_t>(image.channels());
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        if (image.data()[i * n + static_cast<std::size_t>(c)] != value) return false;
    }
    return true;
}

// The guides with the channels that cannot change any distance taken out, exactly: a channel
// that holds one constant on both sides (or has weight 0) adds 0 to every distance and is
// dropped; a channel equal to an earlier one on both sides adds the same squared differences
// and is merged into it (the weights add). Guides with a weight map keep all their channels.
// Fewer bytes per pixel make every patch distance cheaper (docs/PERFORMANCE.md).
std::vector<ReducedGuide> reduce_guide_channels(const std::vector<GuidePair>& guides) {
    struct Kept {
        std::size_t guide;
        int channel;
        float weight;
    };
    std::vector<Kept> kept;
    for (std::size_t g = 0; g < guides.size(); ++g) {
        const GuidePair& p = guides[g];
        for (int c = 0; c < p.source.channels(); ++c) {
            if (p.target_weight_map.empty() && !p.source.empty()) {
                const float v = p.source.data()[static_cast<std::size_t>(c)];
                if (p.weight == 0.0f ||
                    (constant_channel(p.source, c, v) && constant_channel(p.target, c, v))) {
                    continue;
                }
                auto twin = std::find_if(kept.begin(), kept.end(), [&](const Kept& k) {
                    const GuidePair& q = guides[k.guide];
                    return q.target_weight_map.empty() &&
                           same_channel(q.source, k.channel, p.source, c) &&
                           same_channel(q.target, k.channel, p.target, c);
                });
                if (twin != kept.end()) {
                    twin->weight += p.weight;
                    continue;
                }
            }
            kept.push_back(Kept{g, c, p.weight});
        }
    }
    // Keep one channel if nothing is left (the target size comes from the guides).
    if (kept.empty() && !guides.empty()) kept.push_back(Kept{0, 0, guides[0].weight});
    std::vector<ReducedGuide> out;
    for (std::size_t g = 0; g < guides.size(); ++g) {
        std::vector<int> channels;
        ReducedGuide r;
        for (const Kept& k : kept) {
            if (k.guide != g) continue;
            channels.push_back(k.channel);
            r.weights.push_back(k.weight);
        }
        if (channels.empty()) continue;
        r.weight_map = &guides[g].target_weight_map;
        bool all = static_cast<int>(channels.size()) == guides[g].source.channels();
        for (std::size_t i = 0; all && i < channels.size(); ++i) {
            all = channels[i] == static_cast<int>(i);
        }
        if (all) {
            r.whole = &guides[g];  // no copy: the input's channels as they are
        } else {
            r.own_source = select_channels(guides[g].source, channels);
            r.own_target = select_channels(guides[g].target, channels);
        }
        out.push_back(std::move(r));
    }
    return out;
}

std::vector<float> channel0(const Image& image) {
    std::vector<float> out(image.pixel_count());
    for (std::size_t i = 0; i < out.size(); ++i) {
        out[i] = image.data()[i * static_cast<std::size_t>(image.channels())];
    }
    return out;
}

}  // namespace

std::vector<std::uint8_t> source_validity(int w, int h, int fr, const Image& mask) {
    std::vector<std::uint8_t> valid(static_cast<std::size_t>(w) * h, 0);
    // Summed-area table of pixels outside the mask.
    std::vector<int> outside(static_cast<std::size_t>(w + 1) * (h + 1), 0);
    if (!mask.empty()) {
        for (int y = 0; y < h; ++y) {
            int row = 0;
            for (int x = 0; x < w; ++x) {
                row += mask.at(x, y, 0) > 0.5f ? 0 : 1;
                outside[static_cast<std::size_t>(y + 1) * (w + 1) + x + 1] =
                    outside[static_cast<std::size_t>(y) * (w + 1) + x + 1] + row;
            }
        }
    }
    auto sum = [&](int x0, int y0, int x1, int y1) {  // inclusive bounds
        const auto at = [&](int x, int y) {
            return outside[static_cast<std::size_t>(y) * (w + 1) + x];
        };
        return at(x1 + 1, y1 + 1) - at(x0, y1 + 1) - at(x1 + 1, y0) + at(x0, y0);
    };
    // Every pixel is a centre; a patch over the border reads the border pixels repeated, so
    // only its footprint clipped to the image must lie in the mask.
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (mask.empty() || sum(std::max(0, x - fr), std::max(0, y - fr),
                                    std::min(w - 1, x + fr), std::min(h - 1, y + fr)) == 0) {
                valid[static_cast<std::size_t>(y) * w + x] = 1;
            }
        }
    }
    return valid;
}

void target_size(const SynthesisInput& in, int& w, int& h) {
    if (!in.guides.empty()) {
        w = in.guides.front().target.width();
        h = in.guides.front().target.height();
    } else if (!in.initial_target.empty()) {
        w = in.initial_target.width();
        h = in.initial_target.height();
    } else {
        w = in.target_width;
        h = in.target_height;
    }
}

int automatic_levels(int min_side, int patch_size, float ratio) {
    int levels = 1;
    while (pyramid_level_size(min_side, ratio, levels) >= 5 * patch_size) ++levels;
    return levels;
}

int max_levels(int min_side, int patch_size, float ratio, bool rotated) {
    const int need = 2 * footprint_radius(patch_size, rotated) + 1;
    int levels = 0;
    while (levels < 32 && pyramid_level_size(min_side, ratio, levels) >= need) ++levels;
    return levels;
}

LevelBuilder::LevelBuilder(const SynthesisInput& in, const SynthesisOptions& options, int levels,
                           int threads)
    : input_(in), options_(options), levels_(levels), threads_(threads) {
    target_size(in, tw_, th_);
    // Guides: as given, or compressed to fewer channels (projection and pyramid are both linear,
    // so compressing the finest level equals compressing every level). Levels are resampled
    // from these full-resolution images when they are built.
    for (const GuidePair& g : in.guides) compression_.channels_before += g.source.channels();
    compression_.channels_after = compression_.channels_before;
    if (auto compressed = compress_guides(in.guides, options.guide_pca, threads)) {
        compression_.channels_after = compressed->kept;
        compression_.explained_variance = compressed->explained_variance;
        ReducedGuide r;
        r.own_source = std::move(compressed->source);
        r.own_target = std::move(compressed->target);
        r.weight_map = &no_map_;
        r.weights.assign(static_cast<std::size_t>(compressed->kept), 1.0f);
        guides_.push_back(std::move(r));
    } else {
        guides_ = reduce_guide_channels(in.guides);
    }
    // The finest level of every image is exactly the input (no resampling round-off).
}

void LevelBuilder::release_inputs() {
    guides_.clear();
    guides_.shrink_to_fit();
    released_ = true;
}

Level LevelBuilder::build(int index, int patch_size) const {
    EXEMPLAR_DCHECK(!released_);  // release_inputs() ends the builder's use
    const int d = depth(index);
    // This level's inputs, resampled from full resolution (the inputs themselves when finest).
    const float ratio = options_.pyramid_ratio;
    using RF = ResampleFilter;
    const auto at = [&](const Image& full, RF filter) {
        return AtDepth(full, d, ratio, filter, threads_);
    };
    AtDepth style_at = at(input_.style, RF::Gaussian);
    const AtDepth initial_at = at(input_.initial_target, RF::Gaussian);
    std::vector<AtDepth> source_guides, target_guides, weight_maps;
    for (const ReducedGuide& g : guides_) {
        source_guides.push_back(at(g.source(), RF::Gaussian));
        target_guides.push_back(at(g.target(), RF::Gaussian));
        weight_maps.push_back(at(*g.weight_map, RF::Gaussian));
    }
    const Image& initial = initial_at.get();
    Level L;
    L.index = index;
    L.patch_size = patch_size > 0 ? patch_size : options_.patch_size;
    L.radius = L.patch_size / 2;
    L.source_style = style_at.take();
    const Image& style = L.source_style;
    L.sw = style.width();
    L.sh = style.height();
    L.style_channels = style.channels();
    const bool rotated = !input_.source_orientation.empty();

    // Target size at this level comes from the pyramids (guides, initial target) or the formula.
    if (!target_guides.empty()) {
        L.tw = target_guides.front().get().width();
        L.th = target_guides.front().get().height();
    } else if (!initial.empty()) {
        L.tw = initial.width();
        L.th = initial.height();
    } else {
        L.tw = pyramid_level_size(tw_, ratio, d);
        L.th = pyramid_level_size(th_, ratio, d);
    }

    // Feature images: style then guides, as 8-bit codes with per-channel weights. A channel's
    // code covers its values on both sides (the style's B' stays inside the range of A', as
    // votes average A' values; an initial target may widen it).
    const int S = L.style_channels;
    int F = S;
    for (const AtDepth& g : source_guides) F += g.get().channels();
    L.source_features = FeatureImage(L.sw, L.sh, F);
    L.target_features = FeatureImage(L.tw, L.th, F);
    L.quantizers.resize(static_cast<std::size_t>(F));
    L.channel_weight.assign(static_cast<std::size_t>(F), 0.0f);
    auto set_channel = [&](int c, float weight, const Image& a, int ac, const Image& b, int bc) {
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        for (const auto& [image, channel] : {std::pair{&a, ac}, std::pair{&b, bc}}) {
            if (image->empty()) continue;
            const int C = image->channels();
            for (std::size_t i = 0; i < image->pixel_count(); ++i) {
                const float v = image->data()[i * static_cast<std::size_t>(C) +
                                              static_cast<std::size_t>(channel)];
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
        }
        const ChannelQuantizer q = quantizer_for_range(lo, hi);
        L.quantizers[static_cast<std::size_t>(c)] = q;
        L.channel_weight[static_cast<std::size_t>(c)] = weight * q.step * q.step;
    };
    auto encode = [this](const Image& image, int channel, const ChannelQuantizer& q,
                         FeatureImage& out, int c) {
        const int C = image.channels();
        parallel_for(0, image.height(), threads_, [&](int y) {
            const std::size_t row = static_cast<std::size_t>(y) * image.width();
            for (std::size_t i = row; i < row + static_cast<std::size_t>(image.width()); ++i) {
                out.pixel(i)[c] = q.code(image.data()[i * static_cast<std::size_t>(C) +
                                                      static_cast<std::size_t>(channel)]);
            }
        });
    };
    for (int c = 0; c < S; ++c) {
        const float w = input_.style_channel_weights.empty()
                            ? 1.0f
                            : input_.style_channel_weights[static_cast<std::size_t>(c)];
        set_channel(c, options_.style_weight * w, style, c, initial, c);
        encode(style, c, L.quantizers[static_cast<std::size_t>(c)], L.source_features, c);
    }
    const bool any_map = std::any_of(weight_maps.begin(), weight_maps.end(),
                                     [](const AtDepth& m) { return !m.get().empty(); });
    if (any_map) L.target_weights = Image(L.tw, L.th, F, 1.0f);
    int offset = S;
    for (std::size_t g = 0; g < guides_.size(); ++g) {
        const Image& sg = source_guides[g].get();
        const Image& tg = target_guides[g].get();
        const Image& map = weight_maps[g].get();
        const int C = sg.channels();
        for (int c = 0; c < C; ++c) {
            const int fc = offset + c;
            set_channel(fc, guides_[g].weights[static_cast<std::size_t>(c)], sg, c, tg, c);
            const ChannelQuantizer& q = L.quantizers[static_cast<std::size_t>(fc)];
            encode(sg, c, q, L.source_features, fc);
            encode(tg, c, q, L.target_features, fc);
        }
        if (!map.empty()) {
            for (std::size_t i = 0; i < tg.pixel_count(); ++i) {
                for (int c = 0; c < C; ++c) {
                    L.target_weights.data()[i * F + offset + c] = map.data()[i];
                }
            }
        }
        offset += C;
    }
    L.row_weight.clear();
    for (int p = 0; p < L.patch_size; ++p) {
        L.row_weight.insert(L.row_weight.end(), L.channel_weight.begin(), L.channel_weight.end());
    }
    L.row_weight.resize(L.row_weight.size() + kSsdSlack, 0.0f);
    if (any_map) {
        const auto nf = static_cast<std::size_t>(F);
        L.target_pixel_weight.assign(L.target_weights.pixel_count() * nf + kSsdSlack, 0.0f);
        for (std::size_t i = 0; i < L.target_weights.pixel_count() * nf; ++i) {
            L.target_pixel_weight[i] = L.channel_weight[i % nf] * L.target_weights.data()[i];
        }
    }

    if (options_.falloff_sigma_px > 0.0f) {
        const float s2 = 2.0f * options_.falloff_sigma_px * options_.falloff_sigma_px;
        for (int dy = -L.radius; dy <= L.radius; ++dy) {
            for (int dx = -L.radius; dx <= L.radius; ++dx) {
                L.pixel_weight.push_back(std::exp(-static_cast<float>(dx * dx + dy * dy) / s2));
            }
        }
    }

    // Source validity; a mask that leaves no room at a coarse level is dropped on that level.
    const int fr = footprint_radius(L.patch_size, rotated);
    L.source_valid = source_validity(L.sw, L.sh, fr, at(input_.source_mask, RF::Box).get());
    if (std::count(L.source_valid.begin(), L.source_valid.end(), 1) == 0) {
        L.source_valid = source_validity(L.sw, L.sh, fr, Image());
    }
    if (rotated) {
        L.source_angle = channel0(at(input_.source_orientation, RF::Nearest).get());
        L.target_angle = channel0(at(input_.target_orientation, RF::Nearest).get());
        // Rounded rotations: each step's offset pattern once (patches up to 15x15, the rotated
        // distance's fast path; larger ones compute their offsets per distance).
        const int n = input_.orientation_steps;
        if (n > 0) {
            L.orientation_steps = n;
            L.step_angle.resize(static_cast<std::size_t>(n));
            const std::size_t area = static_cast<std::size_t>(L.patch_size) * L.patch_size;
            if (L.patch_size <= 15) L.step_offsets.resize(area * static_cast<std::size_t>(n));
            for (int k = 0; k < n; ++k) {
                const float angle = 6.28318531f * static_cast<float>(2 * k <= n ? k : k - n) /
                                    static_cast<float>(n);
                L.step_angle[static_cast<std::size_t>(k)] = angle;
                if (!L.step_offsets.empty()) {
                    rotated_offsets(L, angle,
                                    L.step_offsets.data() + area * static_cast<std::size_t>(k));
                }
                for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                    const RotatedOffset o = rotate_offset(dx, dy, std::cos(angle), std::sin(angle));
                    L.step_moves.push_back(o.dx);
                    L.step_moves.push_back(o.dy);
                }
            }
            if (input_.rotate_target_patches && L.patch_size <= 15) {
                L.step_target_offsets.resize(area * static_cast<std::size_t>(n));
                for (int k = 0; k < n; ++k) {
                    rotated_target_offsets(
                        L, L.step_angle[static_cast<std::size_t>(k)],
                        L.step_target_offsets.data() + area * static_cast<std::size_t>(k));
                }
            }
        }
    }

    // Target: every pixel is a patch centre. A patch reaching over the border of either image
    // reads that image's border pixels repeated (patch_distance's clamped path; sources as
    // source_validity allows), and votes only inside the target. So a border pixel is voted by
    // (r + 1) x P patches, not by the P of a single column (a corner by (r + 1)², not 1): one
    // bad match no longer shows as a streak along the border, and a border patch can still
    // match the same border of the exemplar (the identity stays exact). Restricted to the mask
    // dilated by the patch radius; fixed pixels are outside the mask.
    const std::size_t nt = static_cast<std::size_t>(L.tw) * L.th;
    L.target_active.assign(nt, 1);
    const AtDepth target_mask = at(input_.target_mask, RF::Box);
    if (!target_mask.get().empty()) {
        const Image& m = target_mask.get();
        L.target_fixed.assign(nt, 1);
        for (std::size_t i = 0; i < nt; ++i) L.target_fixed[i] = m.data()[i] > 0.5f ? 0 : 1;
        if (std::count(L.target_fixed.begin(), L.target_fixed.end(), 0) == 0) {
            // The hole vanished at this coarse level: keep the smallest blob of it.
            for (std::size_t i = 0; i < nt; ++i) L.target_fixed[i] = m.data()[i] > 0.0f ? 0 : 1;
        }
        for (int y = 0; y < L.th; ++y) {
            for (int x = 0; x < L.tw; ++x) {
                bool near = false;
                for (int dy = -L.radius; dy <= L.radius && !near; ++dy) {
                    for (int dx = -L.radius; dx <= L.radius && !near; ++dx) {
                        const int xx = x + dx, yy = y + dy;
                        near = xx >= 0 && yy >= 0 && xx < L.tw && yy < L.th &&
                               !L.target_fixed[L.target_index(xx, yy)];
                    }
                }
                if (!near) L.target_active[L.target_index(x, y)] = 0;
            }
        }
    }
    if (!initial.empty()) L.fixed_style = initial;

    // Label groups: one per label value that occurs among the active target pixels. A level on
    // which some group has no valid source patch (coarse levels of small regions) drops labels.
    L.valid_by_group.assign(1, {});
    const AtDepth source_labels = at(input_.source_labels, RF::Nearest);
    const AtDepth target_labels = at(input_.target_labels, RF::Nearest);
    if (!source_labels.get().empty()) {
        std::map<long, int> group_of;
        std::vector<int> tl(nt), sl(static_cast<std::size_t>(L.sw) * L.sh);
        for (std::size_t i = 0; i < nt; ++i) {
            const long v = std::lround(target_labels.get().data()[i]);
            auto it = group_of.emplace(v, static_cast<int>(group_of.size())).first;
            tl[i] = it->second;
        }
        std::vector<std::vector<int>> groups(group_of.size());
        for (std::size_t i = 0; i < sl.size(); ++i) {
            auto it = group_of.find(std::lround(source_labels.get().data()[i]));
            sl[i] = it == group_of.end() ? -1 : it->second;
            if (sl[i] >= 0 && L.source_valid[i]) {
                groups[static_cast<std::size_t>(sl[i])].push_back(static_cast<int>(i));
            }
        }
        std::vector<std::uint8_t> used(groups.size(), 0);
        for (std::size_t i = 0; i < nt; ++i) {
            if (L.target_active[i]) used[static_cast<std::size_t>(tl[i])] = 1;
        }
        bool complete = true;
        for (std::size_t g = 0; g < groups.size(); ++g) complete &= !used[g] || !groups[g].empty();
        if (complete) {
            // Source patches of labels the target does not use are never candidates.
            for (std::size_t i = 0; i < sl.size(); ++i) {
                if (sl[i] < 0) L.source_valid[i] = 0;
            }
            L.target_label = std::move(tl);
            L.source_label = std::move(sl);
            L.valid_by_group = std::move(groups);
            return L;
        }
    }
    for (std::size_t i = 0; i < L.source_valid.size(); ++i) {
        if (L.source_valid[i]) L.valid_by_group[0].push_back(static_cast<int>(i));
    }
    return L;
}

void set_target_style(Level& level, const Image& style, int threads) {
    EXEMPLAR_CHECK_EQ(style.width(), level.tw);
    EXEMPLAR_CHECK_EQ(style.channels(), level.style_channels);
    const int S = level.style_channels;
    const auto w = static_cast<std::size_t>(style.width());
    parallel_for(0, style.height(), threads, [&](int y) {
        const std::size_t row = static_cast<std::size_t>(y) * w;
        for (std::size_t i = row; i < row + w; ++i) {
            std::uint8_t* out = level.target_features.pixel(i);
            const float* in = style.data().data() + i * static_cast<std::size_t>(S);
            for (int c = 0; c < S; ++c)
                out[c] = level.quantizers[static_cast<std::size_t>(c)].code(in[c]);
        }
    });
}

}  // namespace exemplar::synth
