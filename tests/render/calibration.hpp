#pragma once
// Our render of sphere-on-table against the StyLit authors' buffers of the same set-up
// (examples/stylit/source_*.png, 600x456, sRGB-encoded 8-bit): per buffer the mean absolute
// error and PSNR on [0, 1] after sRGB encoding. Used by the calibration test and by
// bench/render_calibrate.

#include <cmath>
#include <string>
#include <vector>

#include "exemplar/filters/resample.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/render/render.hpp"

namespace exemplar::render::testing {

struct BufferError {
    std::string ours;       ///< Our buffer's name.
    std::string reference;  ///< The StyLit file's name (source_<name>.png).
    double mean_abs = 0.0;  ///< Mean absolute error over pixels and channels, values in [0, 1].
    double psnr_db = 0.0;
    double our_mean = 0.0, reference_mean = 0.0;
};

/// Compares the light buffers with `<reference_dir>/source_{fullgi,dirdif,dirspc,indirb}.png`,
/// resized (area average) to the render's size.
inline Result<std::vector<BufferError>> calibration_errors(const RenderBuffers& buffers,
                                                           const std::string& reference_dir) {
    const std::vector<std::pair<const Image*, std::pair<std::string, std::string>>> pairs = {
        {&buffers.fullgi, {"fullgi", "fullgi"}},
        {&buffers.direct_diffuse, {"direct_diffuse", "dirdif"}},
        {&buffers.direct_specular, {"direct_specular", "dirspc"}},
        {&buffers.indirect_diffuse, {"indirect_diffuse", "indirb"}}};
    std::vector<BufferError> errors;
    for (const auto& [image, names] : pairs) {
        auto reference = load_image(reference_dir + "/source_" + names.second + ".png");
        if (!reference.ok()) return reference.status();
        Image ref = extract_channels(*reference, 0, 3);
        if (!ref.same_size(*image)) {
            ref = resize(ref, image->width(), image->height(), ResampleFilter::Box, 1);
        }
        const Image ours = encode_srgb(*image);
        BufferError e{names.first, names.second};
        double abs_sum = 0.0, sq_sum = 0.0, our_sum = 0.0, ref_sum = 0.0;
        for (std::size_t i = 0; i < ours.size(); ++i) {
            const double d = static_cast<double>(ours.data()[i]) - ref.data()[i];
            abs_sum += std::abs(d);
            sq_sum += d * d;
            our_sum += ours.data()[i];
            ref_sum += ref.data()[i];
        }
        const auto n = static_cast<double>(ours.size());
        e.mean_abs = abs_sum / n;
        e.psnr_db = 10.0 * std::log10(1.0 / std::max(sq_sum / n, 1e-12));
        e.our_mean = our_sum / n;
        e.reference_mean = ref_sum / n;
        errors.push_back(e);
    }
    return errors;
}

}  // namespace exemplar::render::testing
