// Pattern preprocessing of "Image Space Texture Synthesis for 3D NPR Animation" §4.5: CLAHE,
// optional features, appearance space (Lefebvre and Hoppe 2006) and a Gaussian stack.
// Deviations: the PCA is fitted on every second pixel in x and y (a 4x smaller covariance
// pass; the projection still covers every pixel), and neighbourhoods wrap around, since the
// synthesis treats the pattern as tileable.
#include "exemplar/npr/pattern.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "exemplar/core/parallel.hpp"
#include "exemplar/filters/resample.hpp"
#include "opencv_kernels.hpp"

namespace exemplar::npr {
namespace {

// One channel of `width` x `height` floats, scaled.
Image from_values(const std::vector<float>& values, int width, int height, float scale) {
    Image image(width, height, 1);
    const std::span<float> out = image.data();
    for (std::size_t i = 0; i < values.size(); ++i) out[i] = values[i] * scale;
    return image;
}

// The OpenCV operations (a plugin, loaded on first use), or their error named for the pattern.
Result<const plugin::opencv::Entry*> opencv_kernels() {
    auto opencv = plugin::opencv::kernels();
    if (!opencv.ok())
        return Status(opencv.status().code(), "pattern: " + opencv.status().message());
    return opencv;
}

int wrap(int v, int n) {
    const int r = v % n;
    return r < 0 ? r + n : r;
}

}  // namespace

Status validate(const PatternOptions& options) {
    if (!(options.clahe_clip_limit > 0.0f && options.clahe_clip_limit <= 40.0f))
        return invalid_argument("clahe_clip_limit: " + std::to_string(options.clahe_clip_limit) +
                                " is invalid (must be in (0, 40])");
    if (options.clahe_tiles < 1 || options.clahe_tiles > 64)
        return invalid_argument("clahe_tiles: " + std::to_string(options.clahe_tiles) +
                                " is invalid (must be 1..64)");
    if (options.appearance_dims < 1 || options.appearance_dims > 8)
        return invalid_argument("appearance_dims: " + std::to_string(options.appearance_dims) +
                                " is invalid (must be 1..8)");
    if (options.levels < 1 || options.levels > 6)
        return invalid_argument("levels: " + std::to_string(options.levels) +
                                " is invalid (must be 1..6)");
    return Status::ok();
}

Image to_grey(const Image& image) {
    Image grey(image.width(), image.height(), 1);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const float* p = image.pixel(x, y);
            grey.at(x, y, 0) =
                image.channels() >= 3 ? 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2] : p[0];
        }
    return grey;
}

Result<Image> equalize_clahe(const Image& grey, float clip_limit, int tiles) {
    auto opencv = opencv_kernels();
    if (!opencv.ok()) return opencv.status();
    std::vector<float> equalized(grey.data().size());
    (*opencv)->clahe(grey.data().data(), grey.width(), grey.height(), clip_limit, tiles,
                     equalized.data());
    return from_values(equalized, grey.width(), grey.height(), 1.0f / 255.0f);
}

Result<Pattern> prepare_pattern(const Image& pattern, const PatternOptions& options, int min_size,
                                int threads) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (pattern.empty()) return invalid_argument("pattern: is empty");
    if (pattern.width() < min_size || pattern.height() < min_size)
        return invalid_argument("pattern: " + std::to_string(pattern.width()) + "x" +
                                std::to_string(pattern.height()) +
                                " is too small (needs at least " + std::to_string(min_size) + "x" +
                                std::to_string(min_size) + " for the patch size)");
    const int width = pattern.width();
    const int height = pattern.height();

    // Equalize the histogram, so that a threshold t inks about a fraction t of the screen
    Pattern result;
    Image grey = to_grey(pattern);
    for (float& v : grey.data()) v = std::clamp(v, 0.0f, 1.0f);
    if (options.equalize) {
        auto equalized = equalize_clahe(grey, options.clahe_clip_limit, options.clahe_tiles);
        if (!equalized.ok()) return equalized.status();
        result.screen = std::move(equalized).value();
    } else {
        result.screen = grey;
    }

    // Feature channels P' = pattern + optional features
    std::vector<Image> channels{result.screen};
    const float* screen = result.screen.data().data();
    const std::size_t pixels = result.screen.data().size();
    std::vector<float> dx, dy;
    if (options.gradients || options.structure_tensor || options.edge_distance) {
        auto opencv = opencv_kernels();
        if (!opencv.ok()) return opencv.status();
        if (options.gradients || options.structure_tensor) {
            dx.resize(pixels);
            dy.resize(pixels);
            (*opencv)->sobel(screen, width, height, dx.data(), dy.data());
        }
        if (options.edge_distance) {
            std::vector<float> distance(pixels);
            (*opencv)->edge_distance(screen, width, height, distance.data());
            double max_distance = 0.0;
            for (const float d : distance) max_distance = std::max(max_distance, double{d});
            channels.push_back(
                from_values(distance, width, height,
                            max_distance > 0.0 ? static_cast<float>(1.0 / max_distance) : 0.f));
        }
    }
    if (options.gradients) {
        channels.push_back(from_values(dx, width, height, 1.0f));
        channels.push_back(from_values(dy, width, height, 1.0f));
    }
    if (options.structure_tensor) {
        // Scaled by 4 so that a unit step's products are of the order of the other channels
        const auto product = [&](const std::vector<float>& a, const std::vector<float>& b) {
            std::vector<float> out(pixels);
            for (std::size_t i = 0; i < pixels; ++i) out[i] = a[i] * b[i];
            return from_values(out, width, height, 4.0f);
        };
        channels.push_back(product(dx, dx));
        channels.push_back(product(dx, dy));
        channels.push_back(product(dy, dy));
    }
    std::vector<const Image*> pointers;
    for (const Image& c : channels) pointers.push_back(&c);
    result.features = concat_channels(pointers);
    const int feature_channels = result.features.channels();

    // Gaussian-weighted 5x5 neighbourhoods (sigma 1 px), wrapped
    const int dims = 25 * feature_channels;
    float weights[25];
    for (int j = 0; j < 25; ++j) {
        const int ox = j % 5 - 2, oy = j / 5 - 2;
        weights[j] = std::exp(-0.5f * static_cast<float>(ox * ox + oy * oy));
    }
    const auto neighbourhood = [&](int x, int y, Eigen::VectorXd& out) {
        for (int j = 0; j < 25; ++j) {
            const float* p =
                result.features.pixel(wrap(x + j % 5 - 2, width), wrap(y + j / 5 - 2, height));
            for (int c = 0; c < feature_channels; ++c)
                out[j * feature_channels + c] = static_cast<double>(weights[j] * p[c]);
        }
    };

    // PCA of the neighbourhoods of every second pixel (one thread: the sum order is fixed)
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(dims);
    Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(dims, dims);
    Eigen::VectorXd n(dims);
    int samples = 0;
    for (int y = 0; y < height; y += 2)
        for (int x = 0; x < width; x += 2) {
            neighbourhood(x, y, n);
            mean += n;
            covariance.selfadjointView<Eigen::Lower>().rankUpdate(n);
            ++samples;
        }
    mean /= samples;
    const Eigen::MatrixXd second_moment = covariance.selfadjointView<Eigen::Lower>();
    covariance = second_moment / samples - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
    const int kept = std::min(options.appearance_dims, dims);
    // Eigen sorts eigenvalues ascending; the principal axes are the last columns
    Eigen::MatrixXd axes(dims, kept);
    double total = 0.0, explained = 0.0;
    for (int i = 0; i < dims; ++i) total += std::max(0.0, solver.eigenvalues()[i]);
    for (int k = 0; k < kept; ++k) {
        Eigen::VectorXd axis = solver.eigenvectors().col(dims - 1 - k);
        // Fix the sign so that the largest component is positive (eigenvector signs are
        // arbitrary; this keeps the output independent of the solver's internals)
        Eigen::Index largest = 0;
        axis.cwiseAbs().maxCoeff(&largest);
        if (axis[largest] < 0.0) axis = -axis;
        axes.col(k) = axis;
        explained += std::max(0.0, solver.eigenvalues()[dims - 1 - k]);
    }
    result.explained_variance = total > 0.0 ? static_cast<float>(explained / total) : 1.0f;

    // Project every pixel's neighbourhood
    Image appearance(width, height, kept);
    parallel_for(0, height, threads, [&](int y) {
        Eigen::VectorXd v(dims);
        for (int x = 0; x < width; ++x) {
            neighbourhood(x, y, v);
            const Eigen::VectorXd projected = axes.transpose() * (v - mean);
            for (int k = 0; k < kept; ++k)
                appearance.at(x, y, k) = static_cast<float>(projected[k]);
        }
    });

    // Gaussian stack: level l blurred at the scale 2^l (sigma 2^(l-1) px)
    result.stack.push_back(appearance);
    for (int level = 1; level < options.levels; ++level)
        result.stack.push_back(gaussian_blur(appearance, std::ldexp(1.0f, level - 1), threads));
    return result;
}

}  // namespace exemplar::npr
