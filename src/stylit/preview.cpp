// StyLit's preview mode (Fišer et al. 2016, §8.3.4): half resolution and PCA-compressed LPE
// buffers. The paper also stores textures as integers; that is an engine-level measure left
// out here.

#include "exemplar/stylit/preview.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "exemplar/filters/resample.hpp"

namespace exemplar {

namespace {

Image half(const Image& image, int threads) {
    if (image.empty()) return image;
    return resize(image, (image.width() + 1) / 2, (image.height() + 1) / 2, ResampleFilter::Box,
                  threads);
}

// Adds the weighted guide channels of every pixel of one grid to the running sums.
void accumulate(const std::vector<const Image*>& guides, const std::vector<double>& scales,
                Eigen::VectorXd& sum, Eigen::MatrixXd& products, double& count) {
    const int channels = static_cast<int>(sum.size());
    Eigen::VectorXd v(channels);
    const std::size_t pixels = guides.front()->pixel_count();
    for (std::size_t p = 0; p < pixels; ++p) {
        int k = 0;
        for (std::size_t g = 0; g < guides.size(); ++g) {
            const int c = guides[g]->channels();
            const float* px = guides[g]->data().data() + p * static_cast<std::size_t>(c);
            for (int i = 0; i < c; ++i) v[k++] = scales[g] * px[i];
        }
        sum += v;
        products.selfadjointView<Eigen::Lower>().rankUpdate(v);
        count += 1.0;
    }
}

// Projects the weighted, centred guide channels of one grid on the kept components.
Image project(const std::vector<const Image*>& guides, const std::vector<double>& scales,
              const Eigen::VectorXd& mean, const Eigen::MatrixXd& basis) {
    const int channels = static_cast<int>(mean.size());
    const int kept = static_cast<int>(basis.cols());
    const Image& first = *guides.front();
    Image out(first.width(), first.height(), kept);
    std::vector<std::string> names;
    for (int i = 0; i < kept; ++i) names.push_back("pc" + std::to_string(i));
    out.set_channel_names(names);
    Eigen::VectorXd v(channels);
    for (std::size_t p = 0; p < first.pixel_count(); ++p) {
        int k = 0;
        for (std::size_t g = 0; g < guides.size(); ++g) {
            const int c = guides[g]->channels();
            const float* px = guides[g]->data().data() + p * static_cast<std::size_t>(c);
            for (int i = 0; i < c; ++i) v[k++] = scales[g] * px[i];
        }
        const Eigen::VectorXd y = basis.transpose() * (v - mean);
        float* o = out.data().data() + p * static_cast<std::size_t>(kept);
        for (int i = 0; i < kept; ++i) o[i] = static_cast<float>(y[i]);
    }
    return out;
}

}  // namespace

Result<PreviewInput> make_preview(const SynthesisInput& full, int components, int threads) {
    if (components < 1) {
        return invalid_argument("preview components: " + std::to_string(components) +
                                " is invalid (must be >= 1)");
    }
    if (full.guides.empty()) return invalid_argument("preview needs at least one guide");
    if (!full.target_mask.empty() || !full.source_mask.empty() || !full.source_labels.empty() ||
        !full.target_labels.empty() || !full.source_orientation.empty() ||
        !full.initial_target.empty() || !full.initial_nnf.empty()) {
        return invalid_argument(
            "preview supports only a style and guides (no masks, labels, orientation or "
            "initial images)");
    }

    // Half resolution.
    PreviewInput preview;
    preview.input.style = half(full.style, threads);
    preview.input.style_channel_weights = full.style_channel_weights;
    std::vector<Image> sources, targets;
    std::vector<double> scales;
    for (const GuidePair& guide : full.guides) {
        sources.push_back(half(guide.source, threads));
        targets.push_back(half(guide.target, threads));
        scales.push_back(std::sqrt(static_cast<double>(std::max(guide.weight, 0.0f))));
        preview.channels_before += guide.source.channels();
    }
    std::vector<const Image*> source_ptrs, target_ptrs;
    for (std::size_t g = 0; g < sources.size(); ++g) {
        source_ptrs.push_back(&sources[g]);
        target_ptrs.push_back(&targets[g]);
    }

    // Covariance of the weighted channels over both grids, and its eigenvectors.
    const int channels = preview.channels_before;
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(channels);
    Eigen::MatrixXd products = Eigen::MatrixXd::Zero(channels, channels);
    double count = 0.0;
    accumulate(source_ptrs, scales, sum, products, count);
    accumulate(target_ptrs, scales, sum, products, count);
    const Eigen::VectorXd mean = sum / count;
    Eigen::MatrixXd covariance = products.selfadjointView<Eigen::Lower>();
    covariance = covariance / count - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
    if (solver.info() != Eigen::Success) {
        return Status(ErrorCode::Internal, "preview: PCA of the buffers did not converge");
    }

    // Eigen sorts eigenvalues in increasing order: the last columns are the principal ones.
    const int kept = std::min(components, channels);
    const Eigen::MatrixXd basis = solver.eigenvectors().rightCols(kept).rowwise().reverse();
    const Eigen::VectorXd values = solver.eigenvalues().cwiseMax(0.0);
    const double total = values.sum();
    preview.explained_variance = total > 0.0 ? values.tail(kept).sum() / total : 1.0;
    preview.channels_after = kept;

    preview.input.guides.push_back({"preview (PCA of the buffers)",
                                    project(source_ptrs, scales, mean, basis),
                                    project(target_ptrs, scales, mean, basis),
                                    1.0f,
                                    {}});
    return preview;
}

}  // namespace exemplar
