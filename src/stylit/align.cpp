// Aligning a scan of a painted sheet to its render (Fišer et al. 2016, §8.3.1: "We align a photo
// or scan of the painting with the original rendered image using the alignment marks"). The
// paper gives no method; this is ours: bull's-eye marks found as chains of nested concentric
// contours in an adaptively thresholded image, and a homography from their four centres. The
// image operations are OpenCV's, through its plugin (src/plugin/opencv_kernels.hpp).

#include "exemplar/stylit/align.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "opencv_kernels.hpp"

namespace exemplar {

namespace {

struct Candidate {
    Point2 centre;
    double area = 0.0;  // of the outer contour, px²
    int depth = 0;      // nested concentric contours, the outer one included
};

namespace cvk = plugin::opencv;

std::vector<std::uint8_t> grey_bytes(const Image& scan) {
    std::vector<std::uint8_t> grey(static_cast<std::size_t>(scan.width()) * scan.height());
    const int channels = scan.channels();
    const int colour = channels == 2 || channels == 4 ? channels - 1 : channels;
    for (int y = 0; y < scan.height(); ++y) {
        std::uint8_t* row = grey.data() + static_cast<std::size_t>(y) * scan.width();
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

Point2 centroid(const cvk::Contour& contour) {
    if (contour.m00 <= 0.0) return {};
    return {contour.m10 / contour.m00, contour.m01 / contour.m00};
}

// Bull's-eyes in one binary image (ink = 255): contours whose largest child is concentric, and
// so on down the chain.
std::vector<Candidate> find_candidates(const std::vector<cvk::Contour>& contours) {
    std::vector<double> areas(contours.size());
    std::vector<Point2> centres(contours.size());
    for (std::size_t i = 0; i < contours.size(); ++i) {
        areas[i] = contours[i].m00;
        centres[i] = centroid(contours[i]);
    }

    std::vector<bool> used(contours.size(), false);
    std::vector<int> order(contours.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return areas[a] > areas[b]; });

    std::vector<Candidate> candidates;
    for (int outer : order) {
        if (used[outer] || areas[outer] < 40.0) continue;
        // Round enough: 4πA/P² is 1 for a disc and ~0.9 for a 2:1 ellipse; paint blobs are lower.
        const double perimeter = contours[outer].perimeter;
        if (4.0 * std::numbers::pi * areas[outer] / (perimeter * perimeter) < 0.75) continue;
        const double radius = std::sqrt(areas[outer] / std::numbers::pi);
        std::vector<int> chain = {outer};
        int current = outer;
        while (true) {
            int best = -1;
            for (int child = contours[current].first_child; child >= 0;
                 child = contours[child].next) {
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
            while (d < 0.0) d += 2.0 * std::numbers::pi;
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
    auto opencv = cvk::kernels();
    if (!opencv.ok()) return Status(opencv.status().code(), "scan: " + opencv.status().message());
    const int width = scan.width(), height = scan.height();
    std::vector<std::uint8_t> grey = grey_bytes(scan);
    (*opencv)->blur3(grey.data(), width, height);

    // Local thresholds at a few window sizes (marks are 2-8% of the sheet), then a global one.
    const int side = std::min(scan.width(), scan.height());
    Status last = invalid_argument("no alignment marks found");
    for (const double fraction : {0.08, 0.16, 0.04, 0.0}) {
        std::vector<std::uint8_t> binary(grey.size());
        if (fraction > 0.0) {
            const int block = std::max(3, static_cast<int>(fraction * side) | 1);
            (*opencv)->adaptive_threshold(grey.data(), width, height, block, 12.0, binary.data());
        } else {
            (*opencv)->otsu_threshold(grey.data(), width, height, binary.data());
        }
        std::vector<cvk::Contour> contours;
        (*opencv)->contours(binary.data(), width, height, &contours);
        auto marks = pick_marks(find_candidates(contours));
        if (marks.ok()) return marks;
        last = marks.status();
    }
    return Status(last.code(), "scan: " + last.message());
}

Result<AlignedScan> align_scan(const Image& scan, const SheetLayout& layout) {
    auto marks = find_marks(scan);
    if (!marks.ok()) return marks.status();

    auto opencv = cvk::kernels();  // loaded by find_marks
    float from[8], to[8];
    const std::array<Point2, 4> expected = layout.mark_centres();
    for (std::size_t i = 0; i < 4; ++i) {
        from[2 * i] = static_cast<float>(expected[i].x);
        from[2 * i + 1] = static_cast<float>(expected[i].y);
        to[2 * i] = static_cast<float>((*marks)[i].x);
        to[2 * i + 1] = static_cast<float>((*marks)[i].y);
    }
    AlignedScan aligned;
    double determinant = 0.0;
    if (!(*opencv)->perspective(from, to, aligned.render_to_scan.data(), &determinant) ||
        !std::isfinite(aligned.render_to_scan[8]) || std::abs(determinant) < 1e-12) {
        return invalid_argument("scan: the alignment marks are degenerate (collinear?)");
    }
    aligned.marks = *marks;

    // Resample every channel on the render grid (dst -> src through h: WARP_INVERSE_MAP).
    aligned.image = Image(layout.render_width, layout.render_height, scan.channels());
    aligned.image.set_channel_names(scan.channel_names());
    const int w = layout.render_width, h = layout.render_height;
    std::vector<float> plane(static_cast<std::size_t>(scan.width()) * scan.height());
    std::vector<float> warped(static_cast<std::size_t>(w) * h);
    for (int c = 0; c < scan.channels(); ++c) {
        for (int y = 0; y < scan.height(); ++y) {
            for (int x = 0; x < scan.width(); ++x) plane[y * scan.width() + x] = scan.at(x, y, c);
        }
        (*opencv)->warp_perspective(plane.data(), scan.width(), scan.height(),
                                    aligned.render_to_scan.data(), w, h, warped.data());
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) aligned.image.at(x, y, c) = warped[y * w + x];
        }
    }
    return aligned;
}

}  // namespace exemplar
