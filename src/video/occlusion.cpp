// The occlusion function χ of Bénard et al. 2013 §3.1: forward-backward consistency of the
// velocity fields with tolerance ε. The paper compares rendered velocities; the same test on
// estimated flow is the usual occlusion heuristic (e.g. Sundaram et al. 2010), with a larger ε.

#include "exemplar/video/occlusion.hpp"

#include <cmath>
#include <string>

#include "exemplar/core/parallel.hpp"
#include "exemplar/video/warp.hpp"

namespace exemplar::video {

namespace {

Status check_flow(const Image& flow, const char* what) {
    if (flow.empty() || flow.channels() != 2) {
        return invalid_argument(std::string("occlusion: the ") + what +
                                " flow needs 2 channels (u, v) and a non-empty size, got " +
                                std::to_string(flow.channels()) + " channels");
    }
    return Status::ok();
}

}  // namespace

Result<Image> occlusion_mask(const Image& forward, const Image& backward,
                             const OcclusionOptions& options, int threads) {
    if (!(std::isfinite(options.tolerance_sq_px) && options.tolerance_sq_px > 0.0f)) {
        return invalid_argument("occlusion tolerance: " + std::to_string(options.tolerance_sq_px) +
                                " px² is invalid (must be finite and > 0)");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_flow(forward, "forward"));
    EXEMPLAR_RETURN_IF_ERROR(check_flow(backward, "backward"));
    if (!forward.same_size(backward)) {
        return invalid_argument(
            "occlusion: flow sizes differ (forward " + std::to_string(forward.width()) + "x" +
            std::to_string(forward.height()) + ", backward " + std::to_string(backward.width()) +
            "x" + std::to_string(backward.height()) + ")");
    }

    Image mask(forward.width(), forward.height(), 1);
    mask.set_channel_names({"occluded"});
    parallel_for(0, forward.height(), threads, [&](int y) {
        for (int x = 0; x < forward.width(); ++x) {
            // Follow f into frame t+1, then b back: |f(x) + b(x + f(x))|² < ε is consistent.
            const float u = forward.at(x, y, 0), v = forward.at(x, y, 1);
            const float tx = static_cast<float>(x) + u, ty = static_cast<float>(y) + v;
            float bu = 0.0f, bv = 0.0f;
            bool consistent = sample_bilinear(backward, tx, ty, 0, bu) &&
                              sample_bilinear(backward, tx, ty, 1, bv);
            if (consistent) {
                const float du = u + bu, dv = v + bv;
                consistent = du * du + dv * dv < options.tolerance_sq_px;  // false for NaN
            }
            mask.at(x, y, 0) = consistent ? 0.0f : 1.0f;
        }
    });
    return mask;
}

double occluded_fraction(const Image& mask) {
    if (mask.empty()) return 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < mask.pixel_count(); ++i) {
        if (mask.data()[i * static_cast<std::size_t>(mask.channels())] > 0.5f) ++count;
    }
    return static_cast<double>(count) / static_cast<double>(mask.pixel_count());
}

}  // namespace exemplar::video
