// TCIA solver (Bénard et al. 2013 §3.3, §4.1) on top of the engine's public API: coarse-to-fine
// outer loop, forward then backward sweeps per level, one exemplar::synthesize call per frame and
// level (levels = 1), offsets advected along the motion and randomly merged with the frame's own
// previous solution (between two keys by a draw fixed per point: a gradual hand-over),
// keyframes copied in when a sweep reaches them.

#include "exemplar/animate/animate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>

#include "exemplar/animate/lines.hpp"
#include "exemplar/animate/offsets.hpp"
#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/filters/structure_tensor.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "exemplar/video/warp.hpp"

namespace exemplar::animate {

namespace {

using Clock = std::chrono::steady_clock;

// Cell of the hand-over's dot screen, in patches of the finest level (measured with 2, 3 and
// 4: docs/video.md, "Keyframe terms").
constexpr float kDissolveCellPatches = 3.0f;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

bool finite_non_negative(float v) {
    return std::isfinite(v) && v >= 0.0f;
}

// The flow field on a level's grid: area-averaged and scaled to the level's pixels.
Image flow_at(const Image& flow, int w, int h) {
    if (flow.width() == w && flow.height() == h) return flow;
    Image out = resize(flow, w, h, ResampleFilter::Box, 1);
    const float sx = static_cast<float>(w) / flow.width();
    const float sy = static_cast<float>(h) / flow.height();
    for (std::size_t i = 0; i < out.pixel_count(); ++i) {
        out.data()[2 * i] *= sx;
        out.data()[2 * i + 1] *= sy;
    }
    return out;
}

// A visibility mask (1 = χ holds) on a level's grid: visible only where every covered
// full-resolution pixel is (conservative at occlusion boundaries).
Image visibility_at(const Image& visible, int w, int h) {
    if (visible.width() == w && visible.height() == h) return visible;
    Image out = resize(visible, w, h, ResampleFilter::Box, 1);
    for (float& v : out.data()) v = v > 0.999f ? 1.0f : 0.0f;
    return out;
}

// 1 − occlusion mask.
Result<Image> visibility(const Image& forward, const Image& backward, float tolerance,
                         int threads) {
    auto occluded = video::occlusion_mask(forward, backward, {tolerance}, threads);
    if (!occluded.ok()) return occluded.status();
    Image out = std::move(occluded).value();
    for (float& v : out.data()) v = 1.0f - v;
    out.set_channel_names({"visible"});
    return out;
}

// Everything of one pyramid level.
struct LevelData {
    int w = 0, h = 0;
    Image style_input, style_output;           // S, Ŝ
    Image style_orientation;                   // empty unless orientation is on
    std::vector<Image> frames;                 // I_t
    std::vector<Image> forward;                // f_t (t → t+1), t < T−1
    std::vector<Image> backward;               // b_t (t → t−1), t > 0
    std::vector<Image> visible_prev;           // χ⁻_t, t > 0
    std::vector<Image> visible_next;           // χ⁺_t, t < T−1
    std::vector<Image> key_images, key_masks;  // at this level; mask all 1 for full keys
    // The source of the engine: the style and every painted keyframe side by side (Bénard §4:
    // keys are also style pairs), S and I_k likewise; slot 0 is the style, slot 1 + k key k.
    // Without keys the atlas is the style itself and the mask is empty.
    Image atlas_output, atlas_input, atlas_mask, atlas_orientation, atlas_lines;
    std::vector<Image> lines;  // D(I_t) / d_max, empty without lines
    std::vector<AtlasSlot> slots;
    // Ribbons (empty when off or without keys): per frame, offsets into the last / next key's
    // slot at the pixel's corresponding position there ("no match" where there is none).
    std::vector<Nnf> ribbon_prev, ribbon_next;
    // Per frame strictly between two keys: the merges' fixed draw (the dot screen at the pixel's
    // position in the last key's frame, carried along the motion); empty elsewhere.
    std::vector<Image> dissolve;
};

// Per-channel mean of an image (fills the temporal guide where it has no weight, so that the
// guide's value range stays the style's).
std::vector<float> channel_means(const Image& image) {
    std::vector<double> sum(static_cast<std::size_t>(image.channels()), 0.0);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        for (int c = 0; c < image.channels(); ++c) {
            sum[static_cast<std::size_t>(c)] +=
                image.data()[i * static_cast<std::size_t>(image.channels()) +
                             static_cast<std::size_t>(c)];
        }
    }
    std::vector<float> out(sum.size());
    for (std::size_t c = 0; c < sum.size(); ++c) {
        out[c] = static_cast<float>(sum[c] / static_cast<double>(image.pixel_count()));
    }
    return out;
}

class Solver {
public:
    Solver(const AnimationInput& in, const AnimateOptions& options, const RunContext& context)
        : in_(in), options_(options), context_(context) {}

    Result<AnimationResult> run();

private:
    Status load();
    void build_level(int level, LevelData& L) const;
    void build_ribbons(LevelData& L) const;
    void build_dissolve(LevelData& L) const;
    // Merge of the forward pass's field `a` and the backward pass's `b` at frame t of level L,
    // biased toward the nearest key: the fixed draw between two keys, a fresh one elsewhere.
    Nnf biased_merge(const LevelData& L, int t, const Nnf& a, const Nnf& b,
                     std::uint64_t key) const;
    // Solves frame t on level L. `neighbour` is t − 1 (forward) or t + 1 (backward), or −1.
    Status solve_frame(const LevelData& L, int level, int t, int neighbour, bool backward_sweep,
                       const Nnf& initial, std::uint64_t key);
    float forward_probability(int t) const;
    void report(std::string_view stage, int level, int frame, double call_fraction) const;

    const AnimationInput& in_;
    const AnimateOptions& options_;
    const RunContext& context_;
    int T_ = 0, W_ = 0, H_ = 0, levels_ = 1;
    std::vector<Image> frames_, forward_, backward_, visible_prev_, visible_next_;
    std::vector<Image> line_distance_;     // D(I_t) / d_max per frame, full resolution
    Image style_line_distance_;            // D(S) / d_max
    std::vector<const Keyframe*> key_of_;  // per frame, nullptr if none
    std::vector<const Keyframe*> keys_;    // by frame
    std::vector<int> slot_of_;             // per frame: atlas slot of its key, or -1
    std::vector<Nnf> nnf_;
    std::vector<Image> out_;
    std::vector<float> fill_;
    AnimationResult result_;
    double total_work_ = 1.0, done_work_ = 0.0, call_work_ = 0.0;
    bool finest_ = false;
};

float Solver::forward_probability(int t) const {
    int last = -1, next = -1;
    for (int k = t - 1; k >= 0 && last < 0; --k) {
        if (key_of_[static_cast<std::size_t>(k)] != nullptr) last = k;
    }
    for (int k = t + 1; k < T_ && next < 0; ++k) {
        if (key_of_[static_cast<std::size_t>(k)] != nullptr) next = k;
    }
    if (last < 0 || next < 0) return 0.5f;
    return static_cast<float>(next - t) / static_cast<float>(next - last);
}

void Solver::report(std::string_view stage, int level, int frame, double call_fraction) const {
    if (!context_.progress) return;
    context_.report(
        ProgressEvent{stage, level, levels_, frame, T_,
                      std::min(1.0, (done_work_ + call_fraction * call_work_) / total_work_)});
}

Status Solver::load() {
    T_ = in_.frame_count;
    const int threads = context_.threads;
    auto start = Clock::now();
    frames_.resize(static_cast<std::size_t>(T_));
    for (int t = 0; t < T_; ++t) {
        auto frame = in_.frame(t);
        if (!frame.ok()) return frame.status();
        Image& f = frames_[static_cast<std::size_t>(t)];
        f = std::move(frame).value();
        if (t == 0) {
            W_ = f.width();
            H_ = f.height();
        } else if (f.width() != W_ || f.height() != H_) {
            return invalid_argument("frame " + std::to_string(t) + ": is " + size_str(f) +
                                    " but frame 0 is " + size_str(frames_[0]));
        }
        if (f.channels() != in_.style_input.channels()) {
            return invalid_argument(
                "frame " + std::to_string(t) + ": has " + std::to_string(f.channels()) +
                " channels but the style input has " + std::to_string(in_.style_input.channels()));
        }
    }
    if (in_.lines) {
        auto style = line_distance(in_.style_lines, options_.line_max_distance_px);
        if (!style.ok()) return style.status();
        style_line_distance_ = std::move(style).value();
        line_distance_.resize(static_cast<std::size_t>(T_));
        for (int t = 0; t < T_; ++t) {
            auto lines = in_.lines(t);
            if (!lines.ok()) return lines.status();
            if (lines->width() != W_ || lines->height() != H_) {
                return invalid_argument("lines " + std::to_string(t) + ": are " + size_str(*lines) +
                                        " but the frames are " + size_str(frames_[0]));
            }
            auto d = line_distance(*lines, options_.line_max_distance_px);
            if (!d.ok()) return d.status();
            line_distance_[static_cast<std::size_t>(t)] = std::move(d).value();
        }
    }
    key_of_.assign(static_cast<std::size_t>(T_), nullptr);
    for (const Keyframe& k : in_.keyframes) {
        if (k.image.width() != W_ || k.image.height() != H_) {
            return invalid_argument("keyframe " + std::to_string(k.frame) + ": is " +
                                    size_str(k.image) + " but the frames are " +
                                    size_str(frames_[0]));
        }
        if (!k.mask.empty() && !k.mask.same_size(k.image)) {
            return invalid_argument("keyframe " + std::to_string(k.frame) + ": mask is " +
                                    size_str(k.mask) + " but the frames are " +
                                    size_str(frames_[0]));
        }
        key_of_[static_cast<std::size_t>(k.frame)] = &k;
    }
    slot_of_.assign(static_cast<std::size_t>(T_), -1);
    for (int t = 0; t < T_; ++t) {
        if (const Keyframe* k = key_of_[static_cast<std::size_t>(t)]) {
            keys_.push_back(k);
            slot_of_[static_cast<std::size_t>(t)] = static_cast<int>(keys_.size());
        }
    }

    // Motion: given or estimated, then χ±.
    forward_.assign(static_cast<std::size_t>(T_), Image());
    backward_.assign(static_cast<std::size_t>(T_), Image());
    for (int t = 0; t + 1 < T_; ++t) {
        report("motion", 0, t, 0.0);
        if (context_.cancelled()) return cancelled();
        auto pair = in_.motion ? in_.motion(t)
                               : video::estimate_flow_pair(frames_[static_cast<std::size_t>(t)],
                                                           frames_[static_cast<std::size_t>(t + 1)],
                                                           options_.flow);
        if (!pair.ok()) return pair.status();
        const std::string what = "motion " + std::to_string(t) + "->" + std::to_string(t + 1);
        for (const Image* flow : {&pair->forward, &pair->backward}) {
            if (flow->channels() != 2) {
                return invalid_argument(what + ": flow has " + std::to_string(flow->channels()) +
                                        " channels (must be 2: u, v)");
            }
            if (flow->width() != W_ || flow->height() != H_) {
                return invalid_argument(what + ": flow is " + size_str(*flow) +
                                        " but the frames are " + size_str(frames_[0]));
            }
        }
        forward_[static_cast<std::size_t>(t)] = std::move(pair->forward);
        backward_[static_cast<std::size_t>(t + 1)] = std::move(pair->backward);
    }
    result_.times.flow = seconds_since(start);

    start = Clock::now();
    const float tolerance = options_.occlusion_tolerance_sq_px > 0.0f
                                ? options_.occlusion_tolerance_sq_px
                                : (in_.motion ? 2.0f : 8.0f);
    visible_prev_.assign(static_cast<std::size_t>(T_), Image());
    visible_next_.assign(static_cast<std::size_t>(T_), Image());
    for (int t = 0; t + 1 < T_; ++t) {
        const auto i = static_cast<std::size_t>(t);
        auto next = visibility(forward_[i], backward_[i + 1], tolerance, threads);
        if (!next.ok()) return next.status();
        visible_next_[i] = std::move(next).value();
        auto prev = visibility(backward_[i + 1], forward_[i], tolerance, threads);
        if (!prev.ok()) return prev.status();
        visible_prev_[i + 1] = std::move(prev).value();
    }
    result_.times.occlusion = seconds_since(start);
    return Status::ok();
}

void Solver::build_level(int level, LevelData& L) const {
    const int depth = levels_ - 1 - level;
    const int threads = context_.threads;
    L.w = pyramid_level_size(W_, 0.5f, depth);
    L.h = pyramid_level_size(H_, 0.5f, depth);
    const int sw = pyramid_level_size(in_.style_input.width(), 0.5f, depth);
    const int sh = pyramid_level_size(in_.style_input.height(), 0.5f, depth);
    L.style_input = resize(in_.style_input, sw, sh, ResampleFilter::Gaussian, threads);
    L.style_output = resize(in_.style_output, sw, sh, ResampleFilter::Gaussian, threads);
    const auto n = static_cast<std::size_t>(T_);
    L.frames.resize(n);
    L.forward.resize(n);
    L.backward.resize(n);
    L.visible_prev.resize(n);
    L.visible_next.resize(n);
    L.key_images.resize(n);
    L.key_masks.resize(n);
    if (!line_distance_.empty()) L.lines.resize(n);
    parallel_for(0, T_, threads, [&](int t) {
        const auto i = static_cast<std::size_t>(t);
        L.frames[i] = resize(frames_[i], L.w, L.h, ResampleFilter::Gaussian, 1);
        if (!L.lines.empty()) {
            L.lines[i] = resize(line_distance_[i], L.w, L.h, ResampleFilter::Gaussian, 1);
        }
        if (!forward_[i].empty()) L.forward[i] = flow_at(forward_[i], L.w, L.h);
        if (!backward_[i].empty()) L.backward[i] = flow_at(backward_[i], L.w, L.h);
        if (!visible_prev_[i].empty())
            L.visible_prev[i] = visibility_at(visible_prev_[i], L.w, L.h);
        if (!visible_next_[i].empty())
            L.visible_next[i] = visibility_at(visible_next_[i], L.w, L.h);
        if (const Keyframe* k = key_of_[i]) {
            L.key_images[i] = resize(k->image, L.w, L.h, ResampleFilter::Gaussian, 1);
            L.key_masks[i] = k->mask.empty() ? Image(L.w, L.h, 1, 1.0f)
                                             : resize(k->mask, L.w, L.h, ResampleFilter::Box, 1);
        }
    });

    // The atlas: style, then a 1-pixel gap (outside the mask, so no patch straddles two slots)
    // and each key; unpainted key pixels are outside the mask and hold the style's mean.
    L.slots = {AtlasSlot{0, sw, sh}};
    Image style_orientation, style_lines;
    if (options_.orientation) style_orientation = orientation_field(L.style_input, {}, threads);
    if (!L.lines.empty()) {
        style_lines = resize(style_line_distance_, sw, sh, ResampleFilter::Gaussian, threads);
    }
    if (keys_.empty()) {
        L.atlas_output = L.style_output;
        L.atlas_input = L.style_input;
        L.atlas_orientation = style_orientation;
        L.atlas_lines = style_lines;
        return;
    }
    int aw = sw, ah = sh;
    for (std::size_t k = 0; k < keys_.size(); ++k) {
        L.slots.push_back(AtlasSlot{aw + 1, L.w, L.h});
        aw += 1 + L.w;
        ah = std::max(ah, L.h);
    }
    const std::vector<float> out_fill = channel_means(L.style_output);
    const std::vector<float> in_fill = channel_means(L.style_input);
    auto filled = [&](int channels, const std::vector<float>& fill) {
        Image im(aw, ah, channels);
        for (std::size_t p = 0; p < im.pixel_count(); ++p) {
            std::copy(fill.begin(), fill.end(),
                      im.data().begin() + static_cast<long>(p) * channels);
        }
        return im;
    };
    L.atlas_output = filled(L.style_output.channels(), out_fill);
    L.atlas_input = filled(L.style_input.channels(), in_fill);
    L.atlas_mask = Image(aw, ah, 1, 0.0f);
    if (options_.orientation) L.atlas_orientation = Image(aw, ah, 1, 0.0f);
    if (!L.lines.empty()) L.atlas_lines = Image(aw, ah, 1, 1.0f);
    auto paste = [](const Image& from, Image& to, int x0, int x, int y) {
        std::copy_n(from.pixel(x, y), from.channels(), to.pixel(x0 + x, y));
    };
    for (int y = 0; y < sh; ++y) {
        for (int x = 0; x < sw; ++x) {
            paste(L.style_output, L.atlas_output, 0, x, y);
            paste(L.style_input, L.atlas_input, 0, x, y);
            L.atlas_mask.at(x, y, 0) = 1.0f;
            if (options_.orientation) paste(style_orientation, L.atlas_orientation, 0, x, y);
            if (!L.lines.empty()) paste(style_lines, L.atlas_lines, 0, x, y);
        }
    }
    for (std::size_t k = 0; k < keys_.size(); ++k) {
        const auto f = static_cast<std::size_t>(keys_[k]->frame);
        const int x0 = L.slots[k + 1].x0;
        Image frame_orientation;
        if (options_.orientation) frame_orientation = orientation_field(L.frames[f], {}, threads);
        for (int y = 0; y < L.h; ++y) {
            for (int x = 0; x < L.w; ++x) {
                paste(L.frames[f], L.atlas_input, x0, x, y);
                if (options_.orientation) paste(frame_orientation, L.atlas_orientation, x0, x, y);
                if (!L.lines.empty()) paste(L.lines[f], L.atlas_lines, x0, x, y);
                if (L.key_masks[f].at(x, y, 0) < 0.999f) continue;  // unpainted: not a source
                paste(L.key_images[f], L.atlas_output, x0, x, y);
                L.atlas_mask.at(x0 + x, y, 0) = 1.0f;
            }
        }
    }
}

// Ribbons (Bénard §4.1): each key's painted pixels, as identity offsets into its atlas slot,
// followed along the motion to the frames up to the next key on either side (advect_nnf, so
// χ = 0 ends a ribbon). The engine tries them as extra candidates (candidate_nnfs): a pixel
// can jump straight to the corresponding key patch, and propagation spreads it to neighbours.
void Solver::build_ribbons(LevelData& L) const {
    if (!options_.ribbons || keys_.empty()) return;
    const int aw = L.atlas_output.width(), ah = L.atlas_output.height();
    const auto n = static_cast<std::size_t>(T_);
    // One direction: `step` = +1 follows keys forward in time (ribbon_prev), −1 backward.
    auto follow = [&](int step, std::vector<Nnf>& ribbons) {
        ribbons.assign(n, Nnf());
        int slot = -1;
        for (int k = 0; k < T_; ++k) {
            const int t = step > 0 ? k : T_ - 1 - k;
            const auto i = static_cast<std::size_t>(t);
            const int from = t - step;
            Nnf field;
            if (from >= 0 && from < T_ && !ribbons[static_cast<std::size_t>(from)].empty()) {
                field = advect_nnf(ribbons[static_cast<std::size_t>(from)],
                                   step > 0 ? L.backward[i] : L.forward[i],
                                   step > 0 ? L.visible_prev[i] : L.visible_next[i], aw, ah);
                const AtlasSlot& s = L.slots[static_cast<std::size_t>(slot)];
                for (Match& m : field.matches()) {
                    if (m.x >= 0 && (m.x < s.x0 || m.x >= s.x0 + s.width || m.y >= s.height)) {
                        m = Match{-1, -1, 0.0f, 0.0f};
                    }
                }
            }
            if (key_of_[i] != nullptr) {
                slot = slot_of_[i];
                const int x0 = L.slots[static_cast<std::size_t>(slot)].x0;
                if (field.empty()) {
                    field = Nnf(L.w, L.h);
                    for (Match& m : field.matches()) m = Match{-1, -1, 0.0f, 0.0f};
                }
                for (int y = 0; y < L.h; ++y) {
                    for (int x = 0; x < L.w; ++x) {
                        if (L.key_masks[i].at(x, y, 0) >= 0.999f) {
                            field.at(x, y) = Match{x0 + x, y, 0.0f, 0.0f};
                        }
                    }
                }
            }
            ribbons[i] = std::move(field);
        }
    };
    follow(+1, L.ribbon_prev);
    follow(-1, L.ribbon_next);
}

// The hand-over between two keys (Bénard §4.1, "bias towards the closest keyframe"): frame t
// takes the backward pass's offsets with probability (t − t_l)/(t_n − t_l). Drawn afresh per
// frame and pixel that choice is salt-and-pepper noise that the frame's optimization collapses
// to the majority (measured on the finest level, keys 0 and 7: the merge at frame 4 holds 60%
// offsets into key 7, the solved frame 91%; at frame 3 39%, solved 8%), so the whole frame
// snaps from one key to the other where the probability crosses 1/2. Instead all the frames
// between two keys share one draw per point, followed along the motion from the last key and
// taken from a clustered-dot screen whose cells are kDissolveCellPatches patches wide: a pixel
// switches to the next key once the probability passes 1 − its draw, so the switched set only
// grows, in dots that the optimization keeps, at about the same pace in every part of the frame.
void Solver::build_dissolve(LevelData& L) const {
    const auto n = static_cast<std::size_t>(T_);
    L.dissolve.assign(n, Image());
    if (keys_.size() < 2) return;
    // The same dots on every level (the cell scaled with the level).
    const Image screen =
        dot_screen(L.w, L.h,
                   kDissolveCellPatches * static_cast<float>(options_.synthesis.patch_size) *
                       static_cast<float>(L.w) / static_cast<float>(W_),
                   hash_keys(options_.synthesis.seed, 0xD1));
    // Per pixel its position in the last key's frame as a match into that frame; "no match" once
    // the motion loses it (disoccluded since the key): the last key never saw the point, the
    // forward pass has no painting of it to keep, and it takes the next key's at once (draw 1).
    Nnf carried;
    for (int t = keys_.front()->frame; t < keys_.back()->frame; ++t) {
        const auto i = static_cast<std::size_t>(t);
        if (key_of_[i] != nullptr) {
            carried = Nnf(L.w, L.h);
            for (int y = 0; y < L.h; ++y) {
                for (int x = 0; x < L.w; ++x) carried.at(x, y) = Match{x, y, 0.0f, 0.0f};
            }
            continue;
        }
        carried = advect_nnf(carried, L.backward[i], L.visible_prev[i], L.w, L.h);
        Image& draw = L.dissolve[i];
        draw = Image(L.w, L.h, 1);
        for (int y = 0; y < L.h; ++y) {
            for (int x = 0; x < L.w; ++x) {
                const Match& m = carried.at(x, y);
                draw.at(x, y, 0) = m.x < 0 ? 1.0f : screen.at(m.x, m.y, 0);
            }
        }
    }
}

Nnf Solver::biased_merge(const LevelData& L, int t, const Nnf& a, const Nnf& b,
                         std::uint64_t key) const {
    const Image& draw = L.dissolve[static_cast<std::size_t>(t)];
    if (draw.empty()) return random_merge(a, b, forward_probability(t), key);
    return threshold_merge(a, b, forward_probability(t), draw);
}

Status Solver::solve_frame(const LevelData& L, int level, int t, int neighbour, bool backward_sweep,
                           const Nnf& initial, std::uint64_t key) {
    const auto i = static_cast<std::size_t>(t);
    auto merge_start = Clock::now();
    SynthesisInput s;
    s.style = L.atlas_output;
    s.source_mask = L.atlas_mask;
    s.guides.push_back({"input", L.atlas_input, L.frames[i], options_.input_weight, {}});
    if (!L.lines.empty()) {
        s.guides.push_back({"lines", L.atlas_lines, L.lines[i], options_.line_weight, {}});
    }
    // With keyframes g_∂in replaces g_tc (Bénard §4.1): g_tc favours the key visited last.
    const bool derivative = neighbour >= 0 && !keys_.empty() &&
                            options_.input_derivative_weight > 0.0f &&
                            !nnf_[static_cast<std::size_t>(neighbour)].empty();
    if (derivative) {
        const auto n = static_cast<std::size_t>(neighbour);
        auto guide = input_derivative_guide(L.frames[i], L.frames[n], nnf_[n], L.atlas_input,
                                            neighbour < t ? L.backward[i] : L.forward[i],
                                            neighbour < t ? L.visible_prev[i] : L.visible_next[i]);
        if (!guide.ok()) return guide.status();
        s.guides.push_back({"input-derivative", L.atlas_input, std::move(guide->target),
                            options_.input_derivative_weight, std::move(guide->weight)});
    } else if (neighbour >= 0 && options_.temporal_weight > 0.0f) {
        // g_tc: the neighbour's output pulled along the motion, weighted by χ (and by whether
        // the sample fell inside the frame). Where χ = 0 the guide takes the frame's own
        // current solution (the coarser level's, upsampled, or the forward sweep's) instead of
        // a zero weight: the term then only reinforces that solution, which is what the paper
        // initializes such pixels with, and the engine keeps its cheapest distance kernel (with a
        // per-pixel weight map the solve takes 23% longer at equal results). Only the
        // coarsest level's forward sweep, which has no own solution yet, uses the weight map.
        const auto n = static_cast<std::size_t>(neighbour);
        const Image& flow = neighbour < t ? L.backward[i] : L.forward[i];
        const Image& visible = neighbour < t ? L.visible_prev[i] : L.visible_next[i];
        auto warped = video::backward_warp(out_[n], flow, 1);
        if (!warped.ok()) return warped.status();
        Image own;
        if (!out_[i].empty()) own = resize(out_[i], L.w, L.h, ResampleFilter::Gaussian, 1);
        Image weight = visible;
        const int C = warped->image.channels();
        for (std::size_t p = 0; p < weight.pixel_count(); ++p) {
            weight.data()[p] *= warped->valid.data()[p];
            if (weight.data()[p] > 0.0f) continue;
            for (int c = 0; c < C; ++c) {
                const std::size_t j = p * static_cast<std::size_t>(C) + static_cast<std::size_t>(c);
                warped->image.data()[j] =
                    own.empty() ? fill_[static_cast<std::size_t>(c)] : own.data()[j];
            }
        }
        if (!own.empty()) weight = Image();
        s.guides.push_back({"temporal", L.atlas_output, std::move(warped->image),
                            options_.temporal_weight, std::move(weight)});
    }
    const bool keyed = key_of_[i] != nullptr;
    s.initial_nnf = initial;
    for (const std::vector<Nnf>* ribbons : {&L.ribbon_prev, &L.ribbon_next}) {
        if (!ribbons->empty() && !(*ribbons)[i].empty()) s.candidate_nnfs.push_back((*ribbons)[i]);
    }
    if (keyed) {
        s.guides.push_back({"keyframe", L.atlas_output, L.key_images[i], options_.keyframe_weight,
                            key_of_[i]->mask.empty() ? Image() : L.key_masks[i]});
        // Painted pixels start from the key itself in the atlas (exact reproduction).
        const AtlasSlot& slot = L.slots[static_cast<std::size_t>(slot_of_[i])];
        if (s.initial_nnf.empty()) s.initial_nnf = Nnf(L.w, L.h);
        for (int y = 0; y < L.h; ++y) {
            for (int x = 0; x < L.w; ++x) {
                if (L.key_masks[i].at(x, y, 0) >= 0.999f) {
                    s.initial_nnf.at(x, y) = Match{slot.x0 + x, y, 0.0f, 0.0f};
                } else if (initial.empty()) {
                    s.initial_nnf.at(x, y) = Match{-1, -1, 0.0f, 0.0f};
                }
            }
        }
    }
    if (options_.orientation) {
        s.source_orientation = L.atlas_orientation;
        s.target_orientation = orientation_field(L.frames[i], {}, context_.threads);
    }

    SynthesisOptions o = options_.synthesis;
    o.levels = 1;
    o.style_weight = options_.output_weight;
    o.seed = key & ((std::uint64_t{1} << 53) - 1);  // the engine takes seeds up to 2^53
    if (!finest_) {
        o.finest_em_iterations = o.em_iterations;
        o.final_pass_iterations = 0;
    }
    if (backward_sweep) o.finest_em_iterations = options_.backward_em_iterations;
    result_.times.merge += seconds_since(merge_start);

    RunContext call(context_.threads);
    call.cancel = context_.cancel;
    const std::string_view stage = backward_sweep ? "backward" : "forward";
    if (context_.progress) {
        call.progress = [&](const ProgressEvent& e) { report(stage, level, t, e.fraction); };
    }
    auto start = Clock::now();
    auto r = synthesize(std::move(s), o, call);
    (backward_sweep ? result_.times.backward : result_.times.forward) += seconds_since(start);
    if (!r.ok()) return r.status();
    done_work_ += call_work_;

    merge_start = Clock::now();
    Image image = std::move(r->image);
    if (keyed) {
        // Hard constraint: the painted pixels replace the synthesized ones.
        const Image& k = L.key_images[i];
        const Image& m = L.key_masks[i];
        const int C = image.channels();
        for (std::size_t p = 0; p < image.pixel_count(); ++p) {
            const float a = std::clamp(m.data()[p], 0.0f, 1.0f);
            for (int c = 0; c < C; ++c) {
                const std::size_t j = p * static_cast<std::size_t>(C) + static_cast<std::size_t>(c);
                image.data()[j] =
                    a >= 1.0f ? k.data()[j] : a * k.data()[j] + (1 - a) * image.data()[j];
            }
        }
    }
    out_[i] = std::move(image);
    nnf_[i] = std::move(r->nnf);
    result_.times.merge += seconds_since(merge_start);
    return Status::ok();
}

Result<AnimationResult> Solver::run() {
    EXEMPLAR_RETURN_IF_ERROR(validate(in_, options_));
    EXEMPLAR_RETURN_IF_ERROR(load());
    const int threads = context_.threads;

    // Levels: as many as requested while the coarsest frame and style keep 3 patches per side.
    const int min_side = std::min({W_, H_, in_.style_input.width(), in_.style_input.height()});
    levels_ = options_.levels;
    const int need = 3 * options_.synthesis.patch_size;
    while (levels_ > 1 && pyramid_level_size(min_side, 0.5f, levels_ - 1) < need) --levels_;

    // Work of one frame on each level (pixels), for progress.
    const int backward_calls = (T_ - 1) + (T_ > 1 && key_of_.back() != nullptr ? 1 : 0);
    total_work_ = 0.0;
    for (int l = 0; l < levels_; ++l) {
        const int d = levels_ - 1 - l;
        total_work_ += static_cast<double>(pyramid_level_size(W_, 0.5f, d)) *
                       pyramid_level_size(H_, 0.5f, d) * options_.sweeps * (T_ + backward_calls);
    }

    nnf_.assign(static_cast<std::size_t>(T_), Nnf());
    out_.assign(static_cast<std::size_t>(T_), Image());
    std::vector<Nnf> coarse;  // previous level's solutions
    std::vector<AtlasSlot> coarse_slots;
    const std::uint64_t seed = options_.synthesis.seed;
    for (int level = 0; level < levels_; ++level) {
        auto start = Clock::now();
        LevelData L;
        build_level(level, L);
        build_ribbons(L);
        build_dissolve(L);
        fill_ = channel_means(L.style_output);
        const int sw = L.atlas_output.width(), sh = L.atlas_output.height();
        finest_ = level == levels_ - 1;
        call_work_ = static_cast<double>(L.w) * L.h;
        result_.times.merge += seconds_since(start);

        for (int sweep = 0; sweep < options_.sweeps; ++sweep) {
            const bool last_sweep = sweep == options_.sweeps - 1;
            // Forward sweep: advected from t − 1, merged with the frame's own solution (the
            // coarser level's, upsampled, or the previous backward sweep's).
            for (int t = 0; t < T_; ++t) {
                if (context_.cancelled()) return cancelled();
                const auto i = static_cast<std::size_t>(t);
                start = Clock::now();
                Nnf own;
                if (sweep > 0) {
                    own = nnf_[i];
                } else if (level > 0) {
                    own = upsample_nnf(coarse[i], coarse_slots, L.w, L.h, L.slots);
                }
                Nnf initial = own;
                if (t > 0) {
                    Nnf advected =
                        advect_nnf(nnf_[i - 1], L.backward[i], L.visible_prev[i], sw, sh);
                    initial = own.empty() ? std::move(advected)
                                          : random_merge(advected, own, 0.5f,
                                                         hash_keys(seed, 0xF0, level, sweep, i));
                }
                result_.times.merge += seconds_since(start);
                EXEMPLAR_RETURN_IF_ERROR(solve_frame(L, level, t, t - 1, false, initial,
                                                     hash_keys(seed, level, sweep, 2 * i)));
            }
            // Backward sweep: the forward solution merged with the advected one of t + 1,
            // biased toward the nearest keyframe.
            for (int t = T_ - 1; t >= 0; --t) {
                if (context_.cancelled()) return cancelled();
                const auto i = static_cast<std::size_t>(t);
                if (t < T_ - 1 || key_of_[i] != nullptr) {
                    start = Clock::now();
                    Nnf initial = nnf_[i];
                    if (t < T_ - 1) {
                        Nnf advected =
                            advect_nnf(nnf_[i + 1], L.forward[i], L.visible_next[i], sw, sh);
                        initial = biased_merge(L, t, nnf_[i], advected,
                                               hash_keys(seed, 0xB0, level, sweep, i));
                    }
                    result_.times.merge += seconds_since(start);
                    EXEMPLAR_RETURN_IF_ERROR(solve_frame(L, level, t, t < T_ - 1 ? t + 1 : -1, true,
                                                         initial,
                                                         hash_keys(seed, level, sweep, 2 * i + 1)));
                }
                if (finest_ && last_sweep) {
                    if (options_.on_frame) EXEMPLAR_RETURN_IF_ERROR(options_.on_frame(t, out_[i]));
                }
            }
        }
        coarse = nnf_;
        coarse_slots = L.slots;
    }
    if (options_.keep_frames) result_.frames = std::move(out_);
    report("done", levels_ - 1, T_ - 1, 0.0);
    (void)threads;
    return std::move(result_);
}

}  // namespace

AnimateOptions::AnimateOptions() : synthesis(animate_default_synthesis_options()) {}

SynthesisOptions animate_default_synthesis_options() {
    SynthesisOptions o;
    o.usage = UsageStrategy::OccurrencePenalty;
    o.em_iterations = 3;
    o.finest_em_iterations = 2;
    o.search_iterations = 3;
    o.warm_search_iterations = 2;
    o.final_pass_iterations = 1;
    // Whole-patch votes: the temporal-coherence measurements of docs/video.md were made with
    // them (the narrow final vote is measured on still images only).
    o.final_vote_size = 0;
    return o;
}

SynthesisOptions animate_synthesis_options(Quality quality) {
    SynthesisOptions o = animate_default_synthesis_options();
    switch (quality) {
        case Quality::Fast:
            o.em_iterations = 2;
            o.search_iterations = 2;
            o.warm_search_iterations = 1;
            o.final_pass_iterations = 0;
            break;
        case Quality::Default: break;
        case Quality::Best:
            o.em_iterations = 4;
            o.search_iterations = 4;
            o.warm_search_iterations = 3;
            break;
    }
    return o;
}

Status validate(const AnimationInput& in, const AnimateOptions& options) {
    if (in.style_input.empty()) return invalid_argument("style input: is empty");
    if (in.style_output.empty()) return invalid_argument("style output: is empty");
    if (!in.style_input.same_size(in.style_output)) {
        return invalid_argument("style output: is " + size_str(in.style_output) +
                                " but the style input is " + size_str(in.style_input));
    }
    if (in.frame_count < 1) return invalid_argument("frames: none given");
    if (!in.frame) return invalid_argument("frames: no frame source");
    const std::pair<const char*, float> weights[] = {
        {"output-weight", options.output_weight},
        {"input-weight", options.input_weight},
        {"temporal-weight", options.temporal_weight},
        {"input-derivative-weight", options.input_derivative_weight},
        {"keyframe-weight", options.keyframe_weight},
        {"line-weight", options.line_weight}};
    for (const auto& [name, value] : weights) {
        if (!finite_non_negative(value)) {
            return invalid_argument(std::string(name) + ": " + std::to_string(value) +
                                    " is invalid (must be >= 0)");
        }
    }
    if (options.levels < 1 || options.levels > 8) {
        return invalid_argument("levels: " + std::to_string(options.levels) +
                                " is invalid (must be 1..8)");
    }
    if (options.backward_em_iterations < 1 || options.backward_em_iterations > 20) {
        return invalid_argument(
            "backward-em-iterations: " + std::to_string(options.backward_em_iterations) +
            " is invalid (must be 1..20)");
    }
    if (options.sweeps < 1 || options.sweeps > 8) {
        return invalid_argument("sweeps: " + std::to_string(options.sweeps) +
                                " is invalid (must be 1..8)");
    }
    if (!finite_non_negative(options.occlusion_tolerance_sq_px)) {
        return invalid_argument(
            "occlusion-tolerance: " + std::to_string(options.occlusion_tolerance_sq_px) +
            " is invalid (must be >= 0 px^2, 0 = automatic)");
    }
    EXEMPLAR_RETURN_IF_ERROR(exemplar::validate(options.synthesis));
    if (in.style_lines.empty() != !in.lines) {
        return invalid_argument(
            "lines: give both the style's line drawing and the frames' lines, or neither");
    }
    if (!in.style_lines.empty() && !in.style_lines.same_size(in.style_input)) {
        return invalid_argument("style lines: are " + size_str(in.style_lines) +
                                " but the style input is " + size_str(in.style_input));
    }
    if (!(std::isfinite(options.line_max_distance_px) && options.line_max_distance_px > 0.0f)) {
        return invalid_argument(
            "line-max-distance: " + std::to_string(options.line_max_distance_px) +
            " is invalid (must be > 0 px)");
    }
    std::vector<char> seen(static_cast<std::size_t>(in.frame_count), 0);
    for (const Keyframe& k : in.keyframes) {
        const std::string name = "keyframe " + std::to_string(k.frame);
        if (k.frame < 0 || k.frame >= in.frame_count) {
            return invalid_argument(name + ": outside the frames 0.." +
                                    std::to_string(in.frame_count - 1));
        }
        if (seen[static_cast<std::size_t>(k.frame)]++) {
            return invalid_argument(name + ": given twice");
        }
        if (k.image.empty()) return invalid_argument(name + ": image is empty");
        if (k.image.channels() != in.style_output.channels()) {
            return invalid_argument(name + ": has " + std::to_string(k.image.channels()) +
                                    " channels but the style output has " +
                                    std::to_string(in.style_output.channels()));
        }
        if (!k.mask.empty() && k.mask.channels() != 1) {
            return invalid_argument(name + ": mask has " + std::to_string(k.mask.channels()) +
                                    " channels (must be 1)");
        }
    }
    return Status::ok();
}

Result<AnimationResult> animate(const AnimationInput& input, const AnimateOptions& options,
                                const RunContext& context) {
    Solver solver(input, options, context);
    return solver.run();
}

}  // namespace exemplar::animate
