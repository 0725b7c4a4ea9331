#pragma once
// The OpenCV operations exemplar uses, behind a plain-buffer interface: DIS optical flow
// (video), distance transforms (animate, npr), CLAHE, Sobel and Canny (npr), thresholds,
// contours and perspective warps (stylit's scan alignment). They live in one plugin,
// libexemplar_opencv.so (opencv_plugin.cpp), the only binary of the `exemplar` command that
// links OpenCV's core, imgproc, calib3d and video modules: together about 12 MB resident
// (opencv_video pulls opencv_dnn, protobuf, LAPACK) that every process, `exemplar stylize`
// included, paid before main() ran. libexemplar.so and the Python module link it in.
//
// Buffers are row-major and tightly packed (`width` values per row, or `2 * width` for flow);
// the caller allocates the outputs. Both sides are compiled from this header by one build;
// kPlugin.abi_version rejects a plugin from another build.

#include <cstdint>
#include <vector>

#include "exemplar/core/status.hpp"
#include "plugin_loader.hpp"

namespace exemplar::plugin::opencv {

/// Raise abi_version whenever the types below change.
inline constexpr PluginSpec kPlugin{"libexemplar_opencv.so", "exemplar_opencv_entry", 1, "OpenCV"};

/// One contour of a binary image (cv::findContours, RETR_TREE, CHAIN_APPROX_NONE): its moments
/// m00 (area), m10, m01, its closed perimeter, and the hierarchy links (indices, -1 = none).
struct Contour {
    double m00 = 0.0, m10 = 0.0, m01 = 0.0;
    double perimeter = 0.0;
    int next = -1, first_child = -1;
};

/// What the plugin's entry point returns; `abi_version` first (plugin_loader.hpp).
struct Entry {
    int abi_version;
    /// DIS optical flow (preset: 0 ultrafast, 1 fast, 2 medium) from 8-bit grey `from` to `to`:
    /// (dx, dy) per pixel into `flow`.
    void (*dis_flow)(const std::uint8_t* from, const std::uint8_t* to, int width, int height,
                     int preset, float* flow);
    /// Exact Euclidean distance of every pixel to the nearest zero pixel (DIST_MASK_PRECISE).
    void (*distance_to_zero)(const std::uint8_t* binary, int width, int height, float* distance);
    /// For every pixel, the label of its nearest zero pixel (5x5 chamfer distance): label k is
    /// the k-th zero pixel in row-major order, from 1.
    void (*nearest_zero_label)(const std::uint8_t* binary, int width, int height, int* labels);
    /// CLAHE of grey values in [0, 1] (rounded to 8 bits), as 8-bit values 0..255 in floats.
    void (*clahe)(const float* grey, int width, int height, double clip_limit, int tiles,
                  float* equalized);
    /// 3x3 Sobel derivatives in x and y, scaled by 0.25.
    void (*sobel)(const float* image, int width, int height, float* dx, float* dy);
    /// Distance of every pixel to the nearest Canny edge (thresholds 50, 150) of the image in
    /// [0, 1] rounded to 8 bits.
    void (*edge_distance)(const float* image, int width, int height, float* distance);
    /// 3x3 Gaussian blur (sigma from the size), in place.
    void (*blur3)(std::uint8_t* grey, int width, int height);
    /// Inverted binary (255 = darker): against the mean of a `block` window minus `offset`.
    void (*adaptive_threshold)(const std::uint8_t* grey, int width, int height, int block,
                               double offset, std::uint8_t* binary);
    /// Inverted binary at Otsu's threshold.
    void (*otsu_threshold)(const std::uint8_t* grey, int width, int height, std::uint8_t* binary);
    /// Every contour of a binary image, with its hierarchy.
    void (*contours)(const std::uint8_t* binary, int width, int height,
                     std::vector<Contour>* contours);
    /// The homography (row-major 3x3) taking the four points `from` (x, y pairs) to `to` and
    /// its determinant; false if it cannot be computed.
    bool (*perspective)(const float from[8], const float to[8], double homography[9],
                        double* determinant);
    /// Bilinear resampling of one plane on an `out_width` x `out_height` grid through
    /// `homography` (output to input), borders replicated.
    void (*warp_perspective)(const float* plane, int width, int height, const double homography[9],
                             int out_width, int out_height, float* out);
};

/// The OpenCV operations: linked in, or the plugin loaded on first use. Unsupported
/// `OpenCV is not available (libexemplar_opencv.so: <reason>)` without it.
Result<const Entry*> kernels();

}  // namespace exemplar::plugin::opencv
