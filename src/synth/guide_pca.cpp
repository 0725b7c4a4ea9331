#include "guide_pca.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "exemplar/core/parallel.hpp"

namespace exemplar::synth {

namespace {

// Fixed pieces for the parallel sums, so that their order (and the result) does not depend on
// the thread count.
constexpr int kPieces = 64;

struct Moments {
    Eigen::VectorXd sum;
    Eigen::MatrixXd outer;
    double count = 0.0;
};

// The weighted channels of pixel i of one side, stacked guide after guide.
void stacked_pixel(const std::vector<const Image*>& images, const std::vector<double>& scales,
                   std::size_t i, Eigen::VectorXd& out) {
    Eigen::Index c = 0;
    for (std::size_t g = 0; g < images.size(); ++g) {
        const int C = images[g]->channels();
        const float* p = images[g]->data().data() + i * static_cast<std::size_t>(C);
        for (int k = 0; k < C; ++k) out[c++] = scales[g] * static_cast<double>(p[k]);
    }
}

Moments moments(const std::vector<const Image*>& images, const std::vector<double>& scales,
                int channels, int threads) {
    const std::size_t n = images.front()->pixel_count();
    std::vector<Moments> parts(kPieces);
    parallel_for(0, kPieces, threads, [&](int piece) {
        Moments& m = parts[static_cast<std::size_t>(piece)];
        m.sum = Eigen::VectorXd::Zero(channels);
        m.outer = Eigen::MatrixXd::Zero(channels, channels);
        Eigen::VectorXd x(channels);
        const std::size_t i0 = n * static_cast<std::size_t>(piece) / kPieces;
        const std::size_t i1 = n * static_cast<std::size_t>(piece + 1) / kPieces;
        for (std::size_t i = i0; i < i1; ++i) {
            stacked_pixel(images, scales, i, x);
            m.sum += x;
            m.outer.selfadjointView<Eigen::Lower>().rankUpdate(x);
        }
        m.count = static_cast<double>(i1 - i0);
    });
    Moments total{Eigen::VectorXd::Zero(channels), Eigen::MatrixXd::Zero(channels, channels), 0};
    for (const Moments& m : parts) {
        total.sum += m.sum;
        total.outer += m.outer;
        total.count += m.count;
    }
    return total;
}

Image project(const std::vector<const Image*>& images, const std::vector<double>& scales,
              const Eigen::VectorXd& mean, const Eigen::MatrixXd& basis, int threads) {
    const Image& first = *images.front();
    const auto kept = static_cast<int>(basis.cols());
    Image out(first.width(), first.height(), kept);
    const std::size_t n = first.pixel_count();
    parallel_for(0, kPieces, threads, [&](int piece) {
        // Both vectors are allocated once per piece, not per pixel.
        Eigen::VectorXd x(basis.rows());
        Eigen::VectorXd y(kept);
        const std::size_t i0 = n * static_cast<std::size_t>(piece) / kPieces;
        const std::size_t i1 = n * static_cast<std::size_t>(piece + 1) / kPieces;
        for (std::size_t i = i0; i < i1; ++i) {
            stacked_pixel(images, scales, i, x);
            x -= mean;
            y.noalias() = basis.transpose() * x;
            float* p = out.data().data() + i * static_cast<std::size_t>(kept);
            for (int k = 0; k < kept; ++k) p[k] = static_cast<float>(y[k]);
        }
    });
    return out;
}

}  // namespace

std::optional<CompressedGuides> compress_guides(const std::vector<GuidePair>& guides,
                                                double keep_variance, int threads) {
    if (!(keep_variance > 0.0) || guides.empty()) return std::nullopt;
    std::vector<const Image*> sources, targets;
    std::vector<double> scales;
    int channels = 0;
    for (const GuidePair& g : guides) {
        if (!g.target_weight_map.empty()) return std::nullopt;
        sources.push_back(&g.source);
        targets.push_back(&g.target);
        scales.push_back(std::sqrt(std::max(0.0, static_cast<double>(g.weight))));
        channels += g.source.channels();
    }
    if (channels < 2) return std::nullopt;

    // Covariance of the weighted channels over both grids.
    Moments m = moments(sources, scales, channels, threads);
    const Moments t = moments(targets, scales, channels, threads);
    m.sum += t.sum;
    m.outer += t.outer;
    m.count += t.count;
    const Eigen::VectorXd mean = m.sum / m.count;
    const Eigen::MatrixXd second = m.outer.selfadjointView<Eigen::Lower>();
    const Eigen::MatrixXd covariance = second / m.count - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
    if (solver.info() != Eigen::Success) return std::nullopt;

    // Eigenvalues come in increasing order: take them from the back until enough is kept.
    const Eigen::VectorXd values = solver.eigenvalues().cwiseMax(0.0);
    const double total = values.sum();
    if (!(total > 0.0)) return std::nullopt;
    const double goal = std::min(1.0, keep_variance) * total * (1.0 - 1e-12);
    int kept = 0;
    double explained = 0.0;
    while (kept < channels && explained < goal) explained += values[channels - 1 - kept++];
    if (kept >= channels) return std::nullopt;

    const Eigen::MatrixXd basis = solver.eigenvectors().rightCols(kept).rowwise().reverse();
    CompressedGuides out;
    out.source = project(sources, scales, mean, basis, threads);
    out.target = project(targets, scales, mean, basis, threads);
    out.channels_before = channels;
    out.kept = kept;
    out.explained_variance = explained / total;
    return out;
}

}  // namespace exemplar::synth
