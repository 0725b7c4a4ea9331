// `align_scan` on a synthetic scan of the real painting: the bundled StyLit painting on a sheet
// with marks, warped by a known homography (rotation, scale, perspective), re-lit (gain, offset,
// gamma, a lighting gradient) and noisy, must come back onto the render grid.

#include "exemplar/stylit/align.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "stylit_test_data.hpp"

namespace exemplar {
namespace {

using testing::load_example;

// Counter-based noise in [-1, 1]: deterministic and independent of evaluation order.
float hash_noise(std::uint32_t i) {
    i ^= i >> 16;
    i *= 0x7feb352dU;
    i ^= i >> 15;
    i *= 0x846ca68bU;
    i ^= i >> 16;
    return static_cast<float>(i & 0xffffU) / 32767.5f - 1.0f;
}

float relight(float v, float x_fraction) {
    const float lit = 0.06f + 0.8f * std::pow(std::clamp(v, 0.0f, 1.0f), 1.3f);
    return lit * (0.88f + 0.12f * x_fraction);  // uneven lighting, brighter to the right
}

// Inverse-maps every scan pixel through `sheet_to_scan` (bilinear; outside the sheet: a grey
// scanner lid).
Image warp_to_scan(const Image& sheet, const Homography& sheet_to_scan, int width, int height) {
    // Invert the 3x3 matrix (adjugate / determinant).
    const Homography& h = sheet_to_scan;
    Homography inv = {
        h[4] * h[8] - h[5] * h[7], h[2] * h[7] - h[1] * h[8], h[1] * h[5] - h[2] * h[4],
        h[5] * h[6] - h[3] * h[8], h[0] * h[8] - h[2] * h[6], h[2] * h[3] - h[0] * h[5],
        h[3] * h[7] - h[4] * h[6], h[1] * h[6] - h[0] * h[7], h[0] * h[4] - h[1] * h[3]};
    Image scan(width, height, sheet.channels(), 0.55f);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const Point2 p =
                apply_homography(inv, {static_cast<double>(x), static_cast<double>(y)});
            if (p.x < 0 || p.y < 0 || p.x > sheet.width() - 1 || p.y > sheet.height() - 1) continue;
            const int x0 = std::min(static_cast<int>(p.x), sheet.width() - 2);
            const int y0 = std::min(static_cast<int>(p.y), sheet.height() - 2);
            const float fx = static_cast<float>(p.x - x0), fy = static_cast<float>(p.y - y0);
            for (int c = 0; c < sheet.channels(); ++c) {
                const float top = sheet.at(x0, y0, c) * (1 - fx) + sheet.at(x0 + 1, y0, c) * fx;
                const float bottom =
                    sheet.at(x0, y0 + 1, c) * (1 - fx) + sheet.at(x0 + 1, y0 + 1, c) * fx;
                scan.at(x, y, c) = top * (1 - fy) + bottom * fy;
            }
        }
    }
    return scan;
}

struct Distortion {
    double angle_rad;
    double scale;
    double perspective_x;
    double perspective_y;
};

class AlignScan : public ::testing::TestWithParam<Distortion> {};

TEST_P(AlignScan, RecoversTheKnownHomographyOnTheRealPainting) {
    const Image painting = load_example("source_style.png");
    ASSERT_FALSE(painting.empty());
    const SheetLayout layout = sheet_layout(painting.width(), painting.height());
    auto sheet = make_sheet(painting, layout);
    ASSERT_TRUE(sheet.ok()) << sheet.status().message();

    // Sheet -> scan: rotate and scale about the sheet centre, tilt, and move into the canvas.
    const Distortion d = GetParam();
    const double cx = sheet->width() / 2.0, cy = sheet->height() / 2.0;
    const double c = std::cos(d.angle_rad) * d.scale, s = std::sin(d.angle_rad) * d.scale;
    const int width = static_cast<int>(sheet->width() * d.scale * 1.25);
    const int height = static_cast<int>(sheet->height() * d.scale * 1.35);
    const Homography affine = {
        c, -s, width / 2.0 - c * cx + s * cy, s, c, height / 2.0 - s * cx - c * cy, 0, 0, 1};
    // Perspective about the canvas centre: x' = x / (1 + px (x - w/2) + py (y - h/2)), same for y.
    const double px = d.perspective_x, py = d.perspective_y;
    const Homography tilt = {1 - px * width / 2,
                             -py * width / 2,
                             (px * width + py * height) / 2 * width / 2,
                             -px * height / 2,
                             1 - py * height / 2,
                             (px * width + py * height) / 2 * height / 2,
                             px,
                             py,
                             1 - (px * width + py * height) / 2};
    Homography sheet_to_scan{};
    for (int r = 0; r < 3; ++r) {
        for (int k = 0; k < 3; ++k) {
            for (int m = 0; m < 3; ++m)
                sheet_to_scan[r * 3 + k] += tilt[r * 3 + m] * affine[m * 3 + k];
        }
    }
    Image scan = warp_to_scan(*sheet, sheet_to_scan, width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int k = 0; k < scan.channels(); ++k) {
                const auto i = static_cast<std::uint32_t>((y * width + x) * scan.channels() + k);
                const float v = relight(scan.at(x, y, k), static_cast<float>(x) / width) +
                                0.03f * hash_noise(i);
                scan.at(x, y, k) = std::clamp(v, 0.0f, 1.0f);
            }
        }
    }

    auto aligned = align_scan(scan, layout);
    ASSERT_TRUE(aligned.ok()) << aligned.status().message();

    // The render's corners land where the true transform puts them (< 1 px).
    const double m = layout.margin_px;
    double worst = 0.0;
    for (const Point2 corner : {Point2{-0.5, -0.5}, Point2{painting.width() - 0.5, -0.5},
                                Point2{painting.width() - 0.5, painting.height() - 0.5},
                                Point2{-0.5, painting.height() - 0.5}}) {
        const Point2 truth = apply_homography(sheet_to_scan, {corner.x + m, corner.y + m});
        const Point2 found = apply_homography(aligned->render_to_scan, corner);
        worst = std::max(worst, std::hypot(found.x - truth.x, found.y - truth.y));
    }
    EXPECT_LT(worst, 0.5);  // measured 0.13..0.18 px
    RecordProperty("corner_error_px", std::to_string(worst));

    // The aligned scan matches the re-lit painting (interior: the lighting gradient is a
    // function of scan x, so compare against the painting re-lit through the true transform).
    Image expected = painting;
    for (int y = 0; y < painting.height(); ++y) {
        for (int x = 0; x < painting.width(); ++x) {
            const Point2 at = apply_homography(sheet_to_scan, {x + m, y + m});
            for (int k = 0; k < painting.channels(); ++k) {
                expected.at(x, y, k) =
                    relight(painting.at(x, y, k), static_cast<float>(at.x / width));
            }
        }
    }
    const double error = testing::mean_abs_diff(aligned->image, expected);
    const double psnr = testing::peak_snr(aligned->image, expected);
    std::printf("corner error %.3f px, mean abs error %.4f, PSNR %.2f dB\n", worst, error, psnr);
    EXPECT_LT(error, 0.03);  // measured 0.014..0.018
    EXPECT_GT(psnr, 29.0);   // measured 32..35 dB
}

INSTANTIATE_TEST_SUITE_P(Scans, AlignScan,
                         ::testing::Values(Distortion{0.14, 1.3, 6e-5, -4e-5},
                                           Distortion{-0.4, 0.9, -5e-5, 3e-5},
                                           Distortion{3.0, 1.6, 2e-5, 5e-5}),
                         [](const ::testing::TestParamInfo<Distortion>& param) {
                             return "Scan" + std::to_string(param.index);
                         });

TEST(AlignScanErrors, APaintingWithoutMarksIsRejectedWithWhatWasFound) {
    const Image painting = load_example("source_style.png", 2);
    auto aligned = align_scan(painting, sheet_layout(painting.width(), painting.height()));
    ASSERT_FALSE(aligned.ok());
    EXPECT_NE(aligned.status().message().find("alignment marks"), std::string::npos)
        << aligned.status().message();
}

}  // namespace
}  // namespace exemplar
