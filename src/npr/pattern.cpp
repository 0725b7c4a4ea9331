// Pattern preprocessing of "Image Space Texture Synthesis for 3D NPR Animation" §4.5: CLAHE,
// optional features, appearance space (Lefebvre and Hoppe 2006) and a Gaussian stack.
// Deviations: the PCA is fitted on every second pixel in x and y (a 4x smaller covariance
// pass; the projection still covers every pixel), and neighbourhoods wrap around, since the
// synthesis treats the pattern as tileable.
#include "exemplar/npr/pattern.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "exemplar/core/parallel.hpp"
#include "exemplar/filters/resample.hpp"

namespace exemplar::npr {
namespace {

cv::Mat to_mat(const Image& grey) {
    cv::Mat mat(grey.height(), grey.width(), CV_32F);
    for (int y = 0; y < grey.height(); ++y)
        for (int x = 0; x < grey.width(); ++x) mat.at<float>(y, x) = grey.at(x, y, 0);
    return mat;
}

Image from_mat(const cv::Mat& mat, float scale) {
    Image image(mat.cols, mat.rows, 1);
    for (int y = 0; y < mat.rows; ++y)
        for (int x = 0; x < mat.cols; ++x) image.at(x, y, 0) = mat.at<float>(y, x) * scale;
    return image;
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

Image equalize_clahe(const Image& grey, float clip_limit, int tiles) {
    cv::Mat bytes;
    to_mat(grey).convertTo(bytes, CV_8U, 255.0, 0.5);
    cv::Mat equalized;
    cv::createCLAHE(clip_limit, cv::Size(tiles, tiles))->apply(bytes, equalized);
    cv::Mat floats;
    equalized.convertTo(floats, CV_32F);
    return from_mat(floats, 1.0f / 255.0f);
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
    result.screen = options.equalize
                        ? equalize_clahe(grey, options.clahe_clip_limit, options.clahe_tiles)
                        : grey;

    // Feature channels P' = pattern + optional features
    std::vector<Image> channels{result.screen};
    const cv::Mat screen_mat = to_mat(result.screen);
    cv::Mat dx, dy;
    if (options.gradients || options.structure_tensor) {
        cv::Sobel(screen_mat, dx, CV_32F, 1, 0, 3, 0.25);
        cv::Sobel(screen_mat, dy, CV_32F, 0, 1, 3, 0.25);
    }
    if (options.edge_distance) {
        cv::Mat bytes, edges, not_edges, distance;
        screen_mat.convertTo(bytes, CV_8U, 255.0, 0.5);
        cv::Canny(bytes, edges, 50, 150);
        cv::bitwise_not(edges, not_edges);
        cv::distanceTransform(not_edges, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
        double max_distance = 0.0;
        cv::minMaxLoc(distance, nullptr, &max_distance);
        channels.push_back(
            from_mat(distance, max_distance > 0.0 ? static_cast<float>(1.0 / max_distance) : 0.f));
    }
    if (options.gradients) {
        channels.push_back(from_mat(dx, 1.0f));
        channels.push_back(from_mat(dy, 1.0f));
    }
    if (options.structure_tensor) {
        // Scaled by 4 so that a unit step's products are of the order of the other channels
        channels.push_back(from_mat(dx.mul(dx), 4.0f));
        channels.push_back(from_mat(dx.mul(dy), 4.0f));
        channels.push_back(from_mat(dy.mul(dy), 4.0f));
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
