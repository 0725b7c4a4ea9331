// OpenCV's operations behind opencv_kernels.hpp, built as the plugin libexemplar_opencv.so (the
// header says why). It links no exemplar library: plain buffers in and out.

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "opencv_kernels.hpp"

namespace exemplar::plugin::opencv {
namespace {

// Headers over the caller's buffers (no copies).
cv::Mat bytes(const std::uint8_t* data, int width, int height) {
    return cv::Mat(height, width, CV_8UC1, const_cast<std::uint8_t*>(data));
}
cv::Mat floats(const float* data, int width, int height, int channels = 1) {
    return cv::Mat(height, width, CV_32FC(channels), const_cast<float*>(data));
}

void dis_flow(const std::uint8_t* from, const std::uint8_t* to, int width, int height, int preset,
              float* flow) {
    static constexpr int kPresets[] = {cv::DISOpticalFlow::PRESET_ULTRAFAST,
                                       cv::DISOpticalFlow::PRESET_FAST,
                                       cv::DISOpticalFlow::PRESET_MEDIUM};
    cv::Ptr<cv::DISOpticalFlow> dis = cv::DISOpticalFlow::create(kPresets[preset]);
    cv::Mat out;
    dis->calc(bytes(from, width, height), bytes(to, width, height), out);
    out.copyTo(floats(flow, width, height, 2));
}

void distance_to_zero(const std::uint8_t* binary, int width, int height, float* distance) {
    cv::Mat out = floats(distance, width, height);
    cv::distanceTransform(bytes(binary, width, height), out, cv::DIST_L2, cv::DIST_MASK_PRECISE,
                          CV_32F);
}

void nearest_zero_label(const std::uint8_t* binary, int width, int height, int* labels) {
    cv::Mat distance;
    cv::Mat out(height, width, CV_32SC1, labels);
    cv::distanceTransform(bytes(binary, width, height), distance, out, cv::DIST_L2, cv::DIST_MASK_5,
                          cv::DIST_LABEL_PIXEL);
}

void clahe(const float* grey, int width, int height, double clip_limit, int tiles,
           float* equalized) {
    cv::Mat grey_bytes;
    floats(grey, width, height).convertTo(grey_bytes, CV_8U, 255.0, 0.5);
    cv::Mat out;
    cv::createCLAHE(clip_limit, cv::Size(tiles, tiles))->apply(grey_bytes, out);
    out.convertTo(floats(equalized, width, height), CV_32F);
}

void sobel(const float* image, int width, int height, float* dx, float* dy) {
    const cv::Mat in = floats(image, width, height);
    cv::Mat out_x = floats(dx, width, height), out_y = floats(dy, width, height);
    cv::Sobel(in, out_x, CV_32F, 1, 0, 3, 0.25);
    cv::Sobel(in, out_y, CV_32F, 0, 1, 3, 0.25);
}

void edge_distance(const float* image, int width, int height, float* distance) {
    cv::Mat image_bytes, edges, not_edges;
    floats(image, width, height).convertTo(image_bytes, CV_8U, 255.0, 0.5);
    cv::Canny(image_bytes, edges, 50, 150);
    cv::bitwise_not(edges, not_edges);
    cv::Mat out = floats(distance, width, height);
    cv::distanceTransform(not_edges, out, cv::DIST_L2, cv::DIST_MASK_PRECISE);
}

void blur3(std::uint8_t* grey, int width, int height) {
    cv::Mat mat = bytes(grey, width, height);
    cv::GaussianBlur(mat, mat, cv::Size(3, 3), 0.0);
}

void adaptive_threshold(const std::uint8_t* grey, int width, int height, int block, double offset,
                        std::uint8_t* binary) {
    cv::Mat out = bytes(binary, width, height);
    cv::adaptiveThreshold(bytes(grey, width, height), out, 255, cv::ADAPTIVE_THRESH_MEAN_C,
                          cv::THRESH_BINARY_INV, block, offset);
}

void otsu_threshold(const std::uint8_t* grey, int width, int height, std::uint8_t* binary) {
    cv::Mat out = bytes(binary, width, height);
    cv::threshold(bytes(grey, width, height), out, 0, 255, cv::THRESH_BINARY_INV | cv::THRESH_OTSU);
}

void contours(const std::uint8_t* binary, int width, int height, std::vector<Contour>* out) {
    std::vector<std::vector<cv::Point>> found;
    std::vector<cv::Vec4i> hierarchy;
    // A copy: the caller's buffer is const, and older OpenCV wrote into findContours' input.
    cv::findContours(bytes(binary, width, height).clone(), found, hierarchy, cv::RETR_TREE,
                     cv::CHAIN_APPROX_NONE);
    out->assign(found.size(), Contour{});
    for (std::size_t i = 0; i < found.size(); ++i) {
        const cv::Moments m = cv::moments(found[i]);
        (*out)[i] = {m.m00,           m.m10,          m.m01, cv::arcLength(found[i], true),
                     hierarchy[i][0], hierarchy[i][2]};
    }
}

bool perspective(const float from[8], const float to[8], double homography[9],
                 double* determinant) {
    std::vector<cv::Point2f> src, dst;
    for (int i = 0; i < 4; ++i) {
        src.emplace_back(from[2 * i], from[2 * i + 1]);
        dst.emplace_back(to[2 * i], to[2 * i + 1]);
    }
    const cv::Mat h = cv::getPerspectiveTransform(src, dst, cv::DECOMP_LU);
    if (h.empty()) return false;
    for (int i = 0; i < 9; ++i) homography[i] = h.at<double>(i / 3, i % 3);
    *determinant = cv::determinant(h);
    return true;
}

void warp_perspective(const float* plane, int width, int height, const double homography[9],
                      int out_width, int out_height, float* out) {
    const cv::Mat h(3, 3, CV_64F, const_cast<double*>(homography));
    cv::Mat warped = floats(out, out_width, out_height);
    cv::warpPerspective(floats(plane, width, height), warped, h, cv::Size(out_width, out_height),
                        cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
}

constexpr Entry kEntry{kPlugin.abi_version, &dis_flow, &distance_to_zero,
                       &nearest_zero_label, &clahe,    &sobel,
                       &edge_distance,      &blur3,    &adaptive_threshold,
                       &otsu_threshold,     &contours, &perspective,
                       &warp_perspective};

}  // namespace
}  // namespace exemplar::plugin::opencv

// The plugin's one exported symbol (opencv::kPlugin); also linked into libexemplar.so and
// the Python module, where opencv::kernels() calls it directly.
extern "C" __attribute__((visibility("default"))) const exemplar::plugin::opencv::Entry*
exemplar_opencv_entry() {
    return &exemplar::plugin::opencv::kEntry;
}
