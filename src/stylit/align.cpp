// Aligning a scan of a painted sheet to its render (Fišer et al. 2016, §8.3.1: "We align a photo
// or scan of the painting with the original rendered image using the alignment marks"). The
// paper gives no method; this is ours: bull's-eye marks found as chains of nested concentric
// contours in an adaptively thresholded image, and a homography from their four centres.

#include "exemplar/stylit/align.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

namespace exemplar {

namespace {

struct Candidate {
    Point2 centre;
    double area = 0.0;  // of the outer contour, px²
    int depth = 0;      // nested concentric contours, the outer one included
};

cv::Mat grey_bytes(const Image& scan) {
    cv::Mat grey(scan.height(), scan.width(), CV_8UC1);
    const int channels = scan.channels();
    const int colour = channels == 2 || channels == 4 ? channels - 1 : channels;
    for (int y = 0; y < scan.height(); ++y) {
        auto* row = grey.ptr<unsigned char>(y);
        for (int x = 0; x < scan.width(); ++x) {
            const float* px = scan.pixel(x, y);
            float sum = 0.0f;
            for (int c = 0; c < colour; ++c) sum += px[c];
            const float v = std::clamp(sum / static_cast<float>(colour), 0.0f, 1.0f);
            row[x] = static_cast<unsigned char>(std::lround(v * 255.0f));
        }
    }
    return grey;
}

Point2 centroid(const std::vector<cv::Point>& contour, double& area) {
    const cv::Moments m = cv::moments(contour);
    area = m.m00;
    if (m.m00 <= 0.0) return {};
    return {m.m10 / m.m00, m.m01 / m.m00};
}

// Bull's-eyes in one binary image (ink = 255): contours whose largest child is concentric, and
// so on down the chain.
std::vector<Candidate> find_candidates(const cv::Mat& binary) {
    std::vector<std::vector<cv::Point>> contours;
    std::vector<cv::Vec4i> hierarchy;
    cv::findContours(binary, contours, hierarchy, cv::RETR_TREE, cv::CHAIN_APPROX_NONE);
    std::vector<double> areas(contours.size());
    std::vector<Point2> centres(contours.size());
    for (std::size_t i = 0; i < contours.size(); ++i) centres[i] = centroid(contours[i], areas[i]);

    std::vector<bool> used(contours.size(), false);
    std::vector<int> order(contours.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return areas[a] > areas[b]; });

    std::vector<Candidate> candidates;
    for (int outer : order) {
        if (used[outer] || areas[outer] < 40.0) continue;
        // Round enough: 4πA/P² is 1 for a disc and ~0.9 for a 2:1 ellipse; paint blobs are lower.
        const double perimeter = cv::arcLength(contours[outer], true);
        if (4.0 * CV_PI * areas[outer] / (perimeter * perimeter) < 0.75) continue;
        const double radius = std::sqrt(areas[outer] / CV_PI);
        std::vector<int> chain = {outer};
        int current = outer;
        while (true) {
            int best = -1;
            for (int child = hierarchy[current][2]; child >= 0; child = hierarchy[child][0]) {
                if (best < 0 || areas[child] > areas[best]) best = child;
            }
            if (best < 0 || areas[best] < 4.0) break;
            const double dx = centres[best].x - centres[outer].x;
            const double dy = centres[best].y - centres[outer].y;
            if (std::sqrt(dx * dx + dy * dy) > 0.12 * radius) break;
            chain.push_back(best);
            current = best;
        }
        if (chain.size() < 3) continue;
        for (int member : chain) used[member] = true;
        // Centre: area-weighted mean of the chain's centroids (the big outer ones dominate).
        Point2 centre;
        double weight = 0.0;
        for (int member : chain) {
            centre.x += areas[member] * centres[member].x;
            centre.y += areas[member] * centres[member].y;
            weight += areas[member];
        }
        candidates.push_back(
            {{centre.x / weight, centre.y / weight}, areas[outer], static_cast<int>(chain.size())});
    }
    return candidates;
}

// One distinguished mark (depth >= 5) and the three plain ones (depth 3 or 4) most like it in
// size, ordered clockwise on screen from the distinguished one.
Result<std::array<Point2, 4>> pick_marks(const std::vector<Candidate>& candidates) {
    std::vector<Candidate> corner, plain;
    for (const Candidate& c : candidates) (c.depth >= 5 ? corner : plain).push_back(c);
    if (corner.empty() || plain.size() < 3) {
        return invalid_argument("found " + std::to_string(corner.size()) + " top-left and " +
                                std::to_string(plain.size()) +
                                " plain alignment marks (need 1 and 3)");
    }
    // The corner mark: the largest; plain marks: closest in area to it.
    const Candidate top_left =
        *std::max_element(corner.begin(), corner.end(),
                          [](const Candidate& a, const Candidate& b) { return a.area < b.area; });
    std::sort(plain.begin(), plain.end(), [&](const Candidate& a, const Candidate& b) {
        return std::abs(std::log(a.area / top_left.area)) <
               std::abs(std::log(b.area / top_left.area));
    });
    std::vector<Candidate> marks = {top_left, plain[0], plain[1], plain[2]};
    for (const Candidate& m : marks) {
        if (std::abs(std::log(m.area / top_left.area)) > std::log(2.5)) {
            return invalid_argument("the alignment marks found differ too much in size");
        }
    }

    Point2 mid;
    for (const Candidate& m : marks) {
        mid.x += m.centre.x / 4.0;
        mid.y += m.centre.y / 4.0;
    }
    const auto angle = [&](const Candidate& m) {
        return std::atan2(m.centre.y - mid.y, m.centre.x - mid.x);
    };
    const double start = angle(top_left);
    // Clockwise on screen (y down) is increasing atan2; measure from the top-left mark.
    std::sort(marks.begin(), marks.end(), [&](const Candidate& a, const Candidate& b) {
        const auto from_start = [&](const Candidate& m) {
            double d = angle(m) - start;
            while (d < 0.0) d += 2.0 * CV_PI;
            return d;
        };
        return from_start(a) < from_start(b);
    });
    return std::array<Point2, 4>{marks[0].centre, marks[1].centre, marks[2].centre,
                                 marks[3].centre};
}

}  // namespace

Point2 apply_homography(const Homography& h, Point2 p) {
    const double w = h[6] * p.x + h[7] * p.y + h[8];
    return {(h[0] * p.x + h[1] * p.y + h[2]) / w, (h[3] * p.x + h[4] * p.y + h[5]) / w};
}

Result<std::array<Point2, 4>> find_marks(const Image& scan) {
    if (scan.empty()) return invalid_argument("the scan is empty");
    cv::Mat grey = grey_bytes(scan);
    cv::GaussianBlur(grey, grey, cv::Size(3, 3), 0.0);

    // Local thresholds at a few window sizes (marks are 2-8% of the sheet), then a global one.
    const int side = std::min(scan.width(), scan.height());
    Status last = invalid_argument("no alignment marks found");
    for (const double fraction : {0.08, 0.16, 0.04, 0.0}) {
        cv::Mat binary;
        if (fraction > 0.0) {
            const int block = std::max(3, static_cast<int>(fraction * side) | 1);
            cv::adaptiveThreshold(grey, binary, 255, cv::ADAPTIVE_THRESH_MEAN_C,
                                  cv::THRESH_BINARY_INV, block, 12.0);
        } else {
            cv::threshold(grey, binary, 0, 255, cv::THRESH_BINARY_INV | cv::THRESH_OTSU);
        }
        auto marks = pick_marks(find_candidates(binary));
        if (marks.ok()) return marks;
        last = marks.status();
    }
    return Status(last.code(), "scan: " + last.message());
}

Result<AlignedScan> align_scan(const Image& scan, const SheetLayout& layout) {
    auto marks = find_marks(scan);
    if (!marks.ok()) return marks.status();

    std::vector<cv::Point2f> from, to;
    const std::array<Point2, 4> expected = layout.mark_centres();
    for (std::size_t i = 0; i < 4; ++i) {
        from.emplace_back(static_cast<float>(expected[i].x), static_cast<float>(expected[i].y));
        to.emplace_back(static_cast<float>((*marks)[i].x), static_cast<float>((*marks)[i].y));
    }
    const cv::Mat h = cv::getPerspectiveTransform(from, to, cv::DECOMP_LU);
    if (h.empty() || !std::isfinite(h.at<double>(2, 2)) || std::abs(cv::determinant(h)) < 1e-12) {
        return invalid_argument("scan: the alignment marks are degenerate (collinear?)");
    }

    AlignedScan aligned;
    for (int i = 0; i < 9; ++i) aligned.render_to_scan[i] = h.at<double>(i / 3, i % 3);
    aligned.marks = *marks;

    // Resample every channel on the render grid (dst -> src through h: WARP_INVERSE_MAP).
    aligned.image = Image(layout.render_width, layout.render_height, scan.channels());
    aligned.image.set_channel_names(scan.channel_names());
    cv::Mat plane(scan.height(), scan.width(), CV_32FC1);
    cv::Mat warped;
    for (int c = 0; c < scan.channels(); ++c) {
        for (int y = 0; y < scan.height(); ++y) {
            auto* row = plane.ptr<float>(y);
            for (int x = 0; x < scan.width(); ++x) row[x] = scan.at(x, y, c);
        }
        cv::warpPerspective(plane, warped, h, cv::Size(layout.render_width, layout.render_height),
                            cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
        for (int y = 0; y < layout.render_height; ++y) {
            const auto* row = warped.ptr<float>(y);
            for (int x = 0; x < layout.render_width; ++x) aligned.image.at(x, y, c) = row[x];
        }
    }
    return aligned;
}

}  // namespace exemplar
