// StyLit's preview mode (Fišer et al. 2016, §8.3.4): half resolution and PCA-compressed LPE
// buffers. The paper also stores textures as integers; that is an engine-level measure left
// out here.

#include "exemplar/stylit/preview.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "exemplar/core/parallel.hpp"
#include "exemplar/filters/measures.hpp"
#include "exemplar/filters/resample.hpp"

namespace exemplar {

namespace {

// Half a size, odd sizes rounding up.
int half_size(int size) {
    return (size + 1) / 2;
}

// Writes the 2x2 average of `image` around half-resolution pixel (x, y), times `scale`, to
// `out` (the last row or column of an odd size averages itself).
void half_pixel(const Image& image, int x, int y, float scale, float* out) {
    const int x1 = std::min(2 * x + 1, image.width() - 1);
    const int y1 = std::min(2 * y + 1, image.height() - 1);
    const float* a = image.pixel(2 * x, 2 * y);
    const float* b = image.pixel(x1, 2 * y);
    const float* c = image.pixel(2 * x, y1);
    const float* d = image.pixel(x1, y1);
    const float weight = 0.25f * scale;
    for (int i = 0; i < image.channels(); ++i) out[i] = weight * (a[i] + b[i] + c[i] + d[i]);
}

// The image at half resolution (2x2 area average).
Image half(const Image& image, int threads) {
    Image out(half_size(image.width()), half_size(image.height()), image.channels());
    out.set_channel_names(image.channel_names());
    parallel_for(0, out.height(), threads, [&](int y) {
        for (int x = 0; x < out.width(); ++x) half_pixel(image, x, y, 1.0f, out.pixel(x, y));
    });
    return out;
}

using PixelMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Writes the guide channels of one grid at half resolution, each guide scaled by its factor,
// to rows [first, first + pixels) of `stacked` (one row per half-resolution pixel, the
// guides' channels side by side).
void stack_half(const std::vector<const Image*>& guides, const std::vector<float>& scales,
                Eigen::Index first, PixelMatrix& stacked, int threads) {
    const int width = half_size(guides.front()->width());
    parallel_for(0, half_size(guides.front()->height()), threads, [&](int y) {
        for (int x = 0; x < width; ++x) {
            float* row = stacked.row(first + static_cast<Eigen::Index>(y) * width + x).data();
            for (std::size_t g = 0; g < guides.size(); ++g) {
                half_pixel(*guides[g], x, y, scales[g], row);
                row += guides[g]->channels();
            }
        }
    });
}

// Image of `width` x `height` whose pixels are rows [first, first + width * height) of `rows`.
Image unstack(const PixelMatrix& rows, Eigen::Index first, int width, int height) {
    const int kept = static_cast<int>(rows.cols());
    Image out(width, height, kept);
    std::vector<std::string> names;
    for (int i = 0; i < kept; ++i) names.push_back("pc" + std::to_string(i));
    out.set_channel_names(names);
    const auto values = rows.middleRows(first, static_cast<Eigen::Index>(width) * height);
    Eigen::Map<PixelMatrix>(out.data().data(), values.rows(), kept) = values;
    return out;
}

}  // namespace

SynthesisOptions preview_synthesis_options(const SynthesisOptions& full) {
    SynthesisOptions preview = full;
    if (preview.usage == UsageStrategy::ErrorBudget) preview.usage = UsageStrategy::None;
    preview.em_iterations = std::min(preview.em_iterations, kPreviewEmIterations);
    preview.search_iterations = std::min(preview.search_iterations, kPreviewSearchIterations);
    return preview;
}

Result<PreviewSimilarity> compare_preview(const Image& preview, const Image& full, int blur_factor,
                                          int threads) {
    if (preview.empty() || full.empty()) return invalid_argument("compare preview: empty image");
    if (preview.channels() != full.channels()) {
        return invalid_argument("compare preview: the preview has " +
                                std::to_string(preview.channels()) + " channels, the result " +
                                std::to_string(full.channels()));
    }
    if (full.width() < preview.width() || full.height() < preview.height()) {
        return invalid_argument("compare preview: the full result is smaller than the preview");
    }
    if (blur_factor < 1) {
        return invalid_argument("compare preview: blur factor " + std::to_string(blur_factor) +
                                " is invalid (must be >= 1)");
    }
    const int w = preview.width(), h = preview.height();
    const Image reduced = full.width() == w && full.height() == h
                              ? full
                              : resize(full, w, h, ResampleFilter::Box, threads);
    PreviewSimilarity similarity;
    const double full_energy = gradient_energy(reduced);
    similarity.texture_ratio = full_energy > 0.0 ? gradient_energy(preview) / full_energy : 1.0;

    const int bw = std::max(1, w / blur_factor), bh = std::max(1, h / blur_factor);
    const Image a = resize(preview, bw, bh, ResampleFilter::Box, threads);
    const Image b = resize(reduced, bw, bh, ResampleFilter::Box, threads);
    const int colour = std::min(3, a.channels());
    double sum = 0.0;
    for (int y = 0; y < bh; ++y) {
        for (int x = 0; x < bw; ++x) {
            for (int c = 0; c < colour; ++c) sum += std::abs(a.at(x, y, c) - b.at(x, y, c));
        }
    }
    similarity.colour_difference = sum / (static_cast<double>(bw) * bh * colour);
    return similarity;
}

Result<PreviewInput> make_preview(const Image& style, std::span<const PreviewGuide> guides,
                                  int components, int threads) {
    if (components < 1) {
        return invalid_argument("preview components: " + std::to_string(components) +
                                " is invalid (must be >= 1)");
    }
    if (guides.empty()) return invalid_argument("preview needs at least one guide");
    for (const PreviewGuide& guide : guides) {
        const Image& first = *guides.front().source;
        const Image& first_target = *guides.front().target;
        if (guide.source->channels() != guide.target->channels() ||
            guide.source->width() != first.width() || guide.source->height() != first.height() ||
            guide.target->width() != first_target.width() ||
            guide.target->height() != first_target.height()) {
            return invalid_argument(
                "preview: the guides differ in size or channels (validate the input first)");
        }
    }

    // Half resolution; the guides go straight into one matrix of pixel rows.
    PreviewInput preview;
    preview.input.style = half(style, threads);
    std::vector<const Image*> sources, targets;
    std::vector<float> scales;
    for (const PreviewGuide& guide : guides) {
        sources.push_back(guide.source);
        targets.push_back(guide.target);
        scales.push_back(std::sqrt(std::max(guide.weight, 0.0f)));
        preview.channels_before += guide.source->channels();
    }
    const int source_width = half_size(sources.front()->width());
    const int source_height = half_size(sources.front()->height());
    const int target_width = half_size(targets.front()->width());
    const int target_height = half_size(targets.front()->height());

    // Covariance of the weighted channels over both grids, and its eigenvectors.
    const int channels = preview.channels_before;
    const Eigen::Index source_pixels = static_cast<Eigen::Index>(source_width) * source_height;
    const Eigen::Index target_pixels = static_cast<Eigen::Index>(target_width) * target_height;
    PixelMatrix stacked(source_pixels + target_pixels, channels);
    stack_half(sources, scales, 0, stacked, threads);
    stack_half(targets, scales, source_pixels, stacked, threads);
    const Eigen::RowVectorXd mean = stacked.cast<double>().colwise().mean();
    stacked.rowwise() -= mean.cast<float>();
    const Eigen::MatrixXd covariance =
        (stacked.transpose() * stacked).cast<double>() / static_cast<double>(stacked.rows());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
    if (solver.info() != Eigen::Success) {
        return Status(ErrorCode::Internal, "preview: PCA of the buffers did not converge");
    }

    // Eigen sorts eigenvalues in increasing order: the last columns are the principal ones.
    const int kept = std::min(components, channels);
    const Eigen::MatrixXf basis =
        solver.eigenvectors().rightCols(kept).rowwise().reverse().cast<float>();
    const Eigen::VectorXd values = solver.eigenvalues().cwiseMax(0.0);
    const double total = values.sum();
    preview.explained_variance = total > 0.0 ? values.tail(kept).sum() / total : 1.0;
    preview.channels_after = kept;

    const PixelMatrix projected = stacked * basis;
    preview.input.guides.push_back({"preview (PCA of the buffers)",
                                    unstack(projected, 0, source_width, source_height),
                                    unstack(projected, source_pixels, target_width, target_height),
                                    1.0f,
                                    {}});
    return preview;
}

Result<PreviewInput> make_preview(const SynthesisInput& full, int components, int threads) {
    if (!full.target_mask.empty() || !full.source_mask.empty() || !full.source_labels.empty() ||
        !full.target_labels.empty() || !full.source_orientation.empty() ||
        !full.initial_target.empty() || !full.initial_nnf.empty()) {
        return invalid_argument(
            "preview supports only a style and guides (no masks, labels, orientation or "
            "initial images)");
    }
    std::vector<PreviewGuide> guides;
    for (const GuidePair& guide : full.guides)
        guides.push_back({&guide.source, &guide.target, guide.weight});
    auto preview = make_preview(full.style, guides, components, threads);
    if (preview.ok()) preview->input.style_channel_weights = full.style_channel_weights;
    return preview;
}

}  // namespace exemplar
