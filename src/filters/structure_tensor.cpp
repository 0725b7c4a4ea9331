// Structure tensor orientation (Granlund and Knutsson 1995), used by Bénard et al. 2013 §3.1 for
// the orientation fields O(I_t) and O(S). The paper interpolates tensors rather than angles; we
// return the tensor as an image so that callers can resample it before taking the angle.

#include "exemplar/filters/structure_tensor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"
#include "exemplar/filters/resample.hpp"

namespace exemplar {

namespace {

Image grey(const Image& image) {
    Image out(image.width(), image.height(), 1);
    const auto n = static_cast<std::ptrdiff_t>(image.pixel_count());
    const int channels = image.channels();
    const float* in = image.data().data();
    float* o = out.data().data();
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const float* p = in + i * channels;
        o[i] = channels >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
    }
    return out;
}

}  // namespace

Image structure_tensor(const Image& image, const StructureTensorOptions& options, int threads) {
    EXEMPLAR_CHECK(std::isfinite(options.gradient_sigma_px) && options.gradient_sigma_px >= 0.0f);
    EXEMPLAR_CHECK(std::isfinite(options.integration_sigma_px) &&
                   options.integration_sigma_px >= 0.0f);
    if (image.empty()) return {};

    // Gradient outer products of the pre-smoothed grey image.
    const Image g = gaussian_blur(grey(image), options.gradient_sigma_px, threads);
    const int w = g.width(), h = g.height();
    Image tensor(w, h, 3);
    parallel_for(0, h, threads, [&](int y) {
        const int ym = std::max(y - 1, 0), yp = std::min(y + 1, h - 1);
        for (int x = 0; x < w; ++x) {
            const int xm = std::max(x - 1, 0), xp = std::min(x + 1, w - 1);
            const float gx = 0.5f * (g.at(xp, y, 0) - g.at(xm, y, 0));
            const float gy = 0.5f * (g.at(x, yp, 0) - g.at(x, ym, 0));
            float* t = tensor.pixel(x, y);
            t[0] = gx * gx;
            t[1] = gx * gy;
            t[2] = gy * gy;
        }
    });

    // Integrate over the neighbourhood.
    Image smoothed = gaussian_blur(tensor, options.integration_sigma_px, threads);
    smoothed.set_channel_names({"xx", "xy", "yy"});
    return smoothed;
}

Image orientation_from_tensor(const Image& tensor, int threads) {
    EXEMPLAR_CHECK_EQ(tensor.channels(), 3);
    Image angle(tensor.width(), tensor.height(), 1);
    angle.set_channel_names({"angle"});
    const float pi = std::numbers::pi_v<float>;
    parallel_for(0, tensor.height(), threads, [&](int y) {
        for (int x = 0; x < tensor.width(); ++x) {
            const float* t = tensor.pixel(x, y);
            // Gradient direction (dominant eigenvector) in y-down coordinates; the structure
            // runs perpendicular to it. Flipping y turns it into the on-screen CCW angle.
            const float gradient = 0.5f * std::atan2(2.0f * t[1], t[0] - t[2]);
            float along = -(gradient + 0.5f * pi);
            if (t[1] == 0.0f && t[0] == t[2]) along = 0.0f;  // isotropic: no orientation
            along = std::fmod(along, pi);
            if (along <= 0.0f) along += pi;  // also turns -0 into π, folded to 0 below
            if (along >= pi) along -= pi;
            angle.at(x, y, 0) = along;
        }
    });
    return angle;
}

Image coherence_from_tensor(const Image& tensor, int threads) {
    EXEMPLAR_CHECK_EQ(tensor.channels(), 3);
    Image coherence(tensor.width(), tensor.height(), 1);
    coherence.set_channel_names({"coherence"});
    parallel_for(0, tensor.height(), threads, [&](int y) {
        for (int x = 0; x < tensor.width(); ++x) {
            const float* t = tensor.pixel(x, y);
            const float trace = t[0] + t[2];
            const float difference = std::hypot(t[0] - t[2], 2.0f * t[1]);  // λ1 − λ2
            coherence.at(x, y, 0) = trace > 1e-12f ? std::min(difference / trace, 1.0f) : 0.0f;
        }
    });
    return coherence;
}

Image orientation_field(const Image& image, const StructureTensorOptions& options, int threads) {
    return orientation_from_tensor(structure_tensor(image, options, threads), threads);
}

}  // namespace exemplar
