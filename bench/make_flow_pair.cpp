// Writes the frame pair with exact optical flow that the tests use (tests/data/flow/): a
// FlyingChairs-like scene of textured layers, each moved by its own similarity transform. The
// background turns, scales and shifts slightly; three objects (an ellipse, a chair-like polygon,
// a box partly leaving the frame) move 10-25 px and turn, so the pair has occlusions,
// disocclusions and content leaving the frame. Textures: public-domain paintings from
// ../shared/data/style/neural-style (Turner, Van Gogh, Matisse, Munch).
//
// Frame 0 pixel p belongs to the topmost layer covering p; its forward flow is M(p) - p for that
// layer's motion M (exact: evaluated at the pixel centre). Frame 1 at q shows the topmost layer
// whose moved shape covers q, sampled at M^-1(q). Colours are 4x4 supersampled (anti-aliased
// edges); the flow is not averaged.
//
//   make_flow_pair OUT_FOLDER   (writes synthetic-img0.png, synthetic-img1.png, synthetic-gt.flo)

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "exemplar/filters/resample.hpp"
#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "shared_data.hpp"

using namespace exemplar;

namespace {

constexpr int kWidth = 256, kHeight = 192;
constexpr double kPi = 3.14159265358979323846;

struct Vec {
    double x, y;
};

// p -> centre + shift + scale * R(angle) * (p - centre)
struct Motion {
    Vec centre, shift;
    double angle_deg, scale;
    Vec apply(Vec p) const {
        const double a = angle_deg * kPi / 180.0, c = std::cos(a), s = std::sin(a);
        const double dx = p.x - centre.x, dy = p.y - centre.y;
        return {centre.x + shift.x + scale * (c * dx - s * dy),
                centre.y + shift.y + scale * (s * dx + c * dy)};
    }
    Vec invert(Vec q) const {
        const double a = angle_deg * kPi / 180.0, c = std::cos(a), s = std::sin(a);
        const double dx = (q.x - centre.x - shift.x) / scale,
                     dy = (q.y - centre.y - shift.y) / scale;
        return {centre.x + c * dx + s * dy, centre.y - s * dx + c * dy};
    }
};

struct Layer {
    const Image* texture;
    Vec texture_origin;        // texture pixel shown at frame-0 point (0, 0)
    std::vector<Vec> polygon;  // frame-0 outline; empty = the whole plane
    Motion motion;
    bool inside(Vec p) const {  // even-odd rule
        if (polygon.empty()) return true;
        bool in = false;
        for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
            const Vec a = polygon[i], b = polygon[j];
            if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
                in = !in;
            }
        }
        return in;
    }
    std::array<float, 3> colour(Vec p) const {  // bilinear, clamped
        const Image& t = *texture;
        const double u = std::clamp(p.x + texture_origin.x, 0.0, t.width() - 1.001);
        const double v = std::clamp(p.y + texture_origin.y, 0.0, t.height() - 1.001);
        const int x0 = static_cast<int>(u), y0 = static_cast<int>(v);
        const double fx = u - x0, fy = v - y0;
        std::array<float, 3> out{};
        for (int c = 0; c < 3; ++c) {
            const double top = t.at(x0, y0, c) * (1 - fx) + t.at(x0 + 1, y0, c) * fx;
            const double bottom = t.at(x0, y0 + 1, c) * (1 - fx) + t.at(x0 + 1, y0 + 1, c) * fx;
            out[static_cast<std::size_t>(c)] = static_cast<float>(top * (1 - fy) + bottom * fy);
        }
        return out;
    }
};

std::vector<Vec> ellipse(Vec centre, double rx, double ry, double angle_deg) {
    std::vector<Vec> points;
    const double a = angle_deg * kPi / 180.0;
    for (int i = 0; i < 96; ++i) {
        const double t = 2 * kPi * i / 96;
        const double x = rx * std::cos(t), y = ry * std::sin(t);
        points.push_back({centre.x + x * std::cos(a) - y * std::sin(a),
                          centre.y + x * std::sin(a) + y * std::cos(a)});
    }
    return points;
}

// Frame 0 (moved = false) or frame 1, 4x4 supersampled.
Image render(const std::vector<Layer>& layers, bool moved) {
    Image frame(kWidth, kHeight, 3);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            std::array<double, 3> sum{};
            for (int sy = 0; sy < 4; ++sy) {
                for (int sx = 0; sx < 4; ++sx) {
                    const Vec q{x + (sx + 0.5) / 4 - 0.5, y + (sy + 0.5) / 4 - 0.5};
                    for (auto layer = layers.rbegin(); layer != layers.rend(); ++layer) {
                        const Vec p = moved ? layer->motion.invert(q) : q;
                        if (!layer->inside(p)) continue;
                        const auto c = layer->colour(p);
                        for (int k = 0; k < 3; ++k) sum[static_cast<std::size_t>(k)] += c[k];
                        break;
                    }
                }
            }
            for (int k = 0; k < 3; ++k) frame.at(x, y, k) = static_cast<float>(sum[k] / 16.0);
        }
    }
    return frame;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: make_flow_pair OUT_FOLDER\n");
        return 2;
    }
    const std::string out = argv[1];
    std::vector<Image> textures;
    for (const char* name :
         {"shipwreck.jpg", "starry_night.jpg", "woman-with-hat-matisse.jpg", "the_scream.jpg"}) {
        const std::string file = bench::shared_data(std::string("style/neural-style/") + name);
        if (!bench::shared_data_present(file)) return 1;
        auto image = load_image(file);
        if (!image.ok()) {
            std::fprintf(stderr, "%s\n", image.status().message().c_str());
            return 1;
        }
        // About 1.5 texture pixels per frame pixel: brush strokes at a few pixels' scale.
        textures.push_back(resize(*image, image->width() * 2 / 5, image->height() * 2 / 5,
                                  ResampleFilter::Gaussian));
    }
    std::vector<Layer> layers = {
        {&textures[0], {40, 30}, {}, {{128, 96}, {3.0, -2.0}, 1.5, 1.02}},
        {&textures[1], {120, 40}, ellipse({75, 70}, 48, 30, 20), {{75, 70}, {17, 8}, 6, 1.0}},
        {&textures[2],
         {20, 60},
         // a chair seen from the side: back and rear leg, seat, front leg
         {{140, 30},
          {152, 30},
          {152, 80},
          {200, 80},
          {200, 170},
          {188, 170},
          {188, 118},
          {152, 118},
          {152, 170},
          {140, 170}},
         {{170, 110}, {-21, 9}, -8, 1.04}},
        {&textures[3],
         {150, 200},
         {{200, 10}, {250, 14}, {247, 58}, {197, 54}},
         {{224, 34}, {24, -6}, 3, 1.0}},
    };
    Image flow(kWidth, kHeight, 2);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const Vec p{static_cast<double>(x), static_cast<double>(y)};
            for (auto layer = layers.rbegin(); layer != layers.rend(); ++layer) {
                if (!layer->inside(p)) continue;
                const Vec q = layer->motion.apply(p);
                flow.at(x, y, 0) = static_cast<float>(q.x - p.x);
                flow.at(x, y, 1) = static_cast<float>(q.y - p.y);
                break;
            }
        }
    }
    flow.set_channel_names({"u", "v"});
    for (const auto& [image, name] : {std::pair{render(layers, false), "img0.png"},
                                      std::pair{render(layers, true), "img1.png"}}) {
        const Status st = save_image(image, out + "/synthetic-" + name);
        if (!st.is_ok()) {
            std::fprintf(stderr, "%s\n", st.message().c_str());
            return 1;
        }
    }
    const Status st = save_flo(flow, out + "/synthetic-gt.flo");
    if (!st.is_ok()) {
        std::fprintf(stderr, "%s\n", st.message().c_str());
        return 1;
    }
    return 0;
}
