// Layers (Bénard et al. 2013 §4): per-layer solves with the motion extrapolated into each
// layer's background (Fig. 10), composited back to front.

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "exemplar/animate/animate.hpp"
#include "opencv_kernels.hpp"

namespace exemplar::animate {

Result<Image> extrapolate_flow(const Image& flow, const Image& coverage) {
    if (flow.channels() != 2 || coverage.channels() != 1 || !flow.same_size(coverage)) {
        return invalid_argument(
            "extrapolate flow: needs a 2-channel flow and a 1-channel "
            "coverage of the same size");
    }
    const int w = flow.width(), h = flow.height();
    // distanceTransform with labels: every pixel gets the label of its nearest zero pixel;
    // covered pixels are the zeros, each its own label.
    std::vector<std::uint8_t> outside(static_cast<std::size_t>(w) * h);
    int covered = 0;
    for (int y = 0; y < h; ++y) {
        std::uint8_t* row = outside.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            const bool in = coverage.at(x, y, 0) > 0.5f;
            row[x] = in ? 0 : 255;
            covered += in;
        }
    }
    if (covered == 0 || covered == w * h) return flow;
    auto opencv = plugin::opencv::kernels();
    if (!opencv.ok()) {
        return Status(opencv.status().code(), "extrapolate flow: " + opencv.status().message());
    }
    std::vector<int> labels(outside.size());
    (*opencv)->nearest_zero_label(outside.data(), w, h, labels.data());
    // Label k (1-based) is the k-th zero pixel in row-major order.
    std::vector<int> pixel_of_label(static_cast<std::size_t>(covered) + 1, 0);
    int k = 0;
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* row = outside.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            if (row[x] == 0) pixel_of_label[static_cast<std::size_t>(++k)] = y * w + x;
        }
    }
    Image out = flow;
    for (int y = 0; y < h; ++y) {
        const int* label = labels.data() + static_cast<std::size_t>(y) * w;
        for (int x = 0; x < w; ++x) {
            if (coverage.at(x, y, 0) > 0.5f) continue;
            const int p = pixel_of_label[static_cast<std::size_t>(label[x])];
            out.at(x, y, 0) = flow.at(p % w, p / w, 0);
            out.at(x, y, 1) = flow.at(p % w, p / w, 1);
        }
    }
    return out;
}

Result<LayeredResult> animate_layers(const std::vector<Layer>& layers,
                                     const AnimateOptions& options, const RunContext& context) {
    if (layers.empty()) return invalid_argument("layers: none given");
    LayeredResult result;
    AnimateOptions o = options;
    o.keep_frames = true;
    o.on_frame = {};
    const int T = layers.front().input.frame_count;
    for (std::size_t l = 0; l < layers.size(); ++l) {
        const Layer& layer = layers[l];
        const std::string name = "layer " + std::to_string(l);
        if (!layer.coverage) return invalid_argument(name + ": no coverage");
        if (layer.input.frame_count != T) {
            return invalid_argument(name + ": has " + std::to_string(layer.input.frame_count) +
                                    " frames but layer 0 has " + std::to_string(T));
        }
        AnimationInput in = layer.input;
        in.motion = [&layer, &o](int t) -> Result<video::FlowPair> {
            Result<video::FlowPair> pair = Status::ok();
            if (layer.input.motion) {
                pair = layer.input.motion(t);
            } else {
                auto a = layer.input.frame(t);
                if (!a.ok()) return a.status();
                auto b = layer.input.frame(t + 1);
                if (!b.ok()) return b.status();
                pair = video::estimate_flow_pair(*a, *b, o.flow);
            }
            if (!pair.ok()) return pair.status();
            auto c0 = layer.coverage(t);
            if (!c0.ok()) return c0.status();
            auto c1 = layer.coverage(t + 1);
            if (!c1.ok()) return c1.status();
            auto forward = extrapolate_flow(pair->forward, *c0);
            if (!forward.ok()) return forward.status();
            auto backward = extrapolate_flow(pair->backward, *c1);
            if (!backward.ok()) return backward.status();
            return video::FlowPair{std::move(forward).value(), std::move(backward).value()};
        };
        RunContext call(context.threads);
        call.cancel = context.cancel;
        if (context.progress) {
            call.progress = [&](const ProgressEvent& e) {
                ProgressEvent scaled = e;
                scaled.fraction =
                    (static_cast<double>(l) + e.fraction) / static_cast<double>(layers.size());
                context.report(scaled);
            };
        }
        auto r = animate(in, o, call);
        if (!r.ok()) return Status(r.status().code(), name + ": " + r.status().message());
        result.times.flow += r->times.flow;
        result.times.occlusion += r->times.occlusion;
        result.times.forward += r->times.forward;
        result.times.backward += r->times.backward;
        result.times.merge += r->times.merge;
        if (l > 0 && (r->frames[0].width() != result.frames[0].width() ||
                      r->frames[0].height() != result.frames[0].height() ||
                      r->frames[0].channels() != result.frames[0].channels())) {
            return invalid_argument(name +
                                    ": its frames or style output differ in size or "
                                    "channels from layer 0's");
        }
        // Composite over the layers behind.
        if (l == 0) {
            result.frames = r->frames;
        } else {
            for (int t = 0; t < T; ++t) {
                auto alpha = layer.coverage(t);
                if (!alpha.ok()) return alpha.status();
                Image& c = result.frames[static_cast<std::size_t>(t)];
                const Image& f = r->frames[static_cast<std::size_t>(t)];
                if (!alpha->same_size(c) || alpha->channels() != 1) {
                    return invalid_argument(name + ": coverage of frame " + std::to_string(t) +
                                            " is not a 1-channel image of the frames' size");
                }
                const int C = c.channels();
                for (std::size_t p = 0; p < c.pixel_count(); ++p) {
                    const float a = std::clamp(alpha->data()[p], 0.0f, 1.0f);
                    for (int ch = 0; ch < C; ++ch) {
                        const std::size_t j =
                            p * static_cast<std::size_t>(C) + static_cast<std::size_t>(ch);
                        c.data()[j] = a * f.data()[j] + (1.0f - a) * c.data()[j];
                    }
                }
            }
        }
        result.layers.push_back(std::move(r->frames));
    }
    return result;
}

}  // namespace exemplar::animate
