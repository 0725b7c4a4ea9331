// Animated scenes: keyframe interpolation, turntables, and the exact motion vectors, occlusion
// masks, orientation and lines of render_frame, against analytic ground truth.

#include "exemplar/render/animation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "exemplar/video/warp.hpp"

namespace exemplar::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

Animation parse(const std::string& json) {
    auto animation = parse_animation(json, "test.json", ".");
    EXPECT_TRUE(animation.ok()) << animation.status().message();
    return animation.ok() ? std::move(animation).value() : Animation{};
}

RenderBuffers frame(const Animation& animation, int t, int w, int h, int threads = 0, int spp = 1) {
    RenderOptions options;
    options.width = w;
    options.height = h;
    options.samples_per_pixel = spp;
    options.max_bounces = 2;
    auto buffers = render_frame(animation, t, options, RunContext(threads));
    EXPECT_TRUE(buffers.ok()) << buffers.status().message();
    return buffers.ok() ? std::move(buffers).value() : RenderBuffers{};
}

// An independent pinhole model (double precision) of a camera at `eye` looking down -z.
struct Pinhole {
    double eye_z, focal;  // focal length in pixels
    int w, h;
    Pinhole(double z, double fov_deg, int width, int height)
        : eye_z(z), focal(0.5 * height / std::tan(fov_deg * kPi / 360.0)), w(width), h(height) {}
    // Unit ray through pixel centre (x, y).
    void ray(int x, int y, double d[3]) const {
        d[0] = (x + 0.5 - 0.5 * w) / focal;
        d[1] = -(y + 0.5 - 0.5 * h) / focal;
        d[2] = -1.0;
        const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + 1.0);
        for (int i = 0; i < 3; ++i) d[i] /= n;
    }
    void project(const double p[3], double& px, double& py) const {
        const double z = eye_z - p[2];
        px = 0.5 * w + focal * p[0] / z;
        py = 0.5 * h - focal * p[1] / z;
    }
};

// Nearest hit of the ray eye + t d with a sphere (centre c, radius r); t < 0 if none.
double hit_sphere(const double eye[3], const double d[3], const double c[3], double r) {
    double oc[3], b = 0.0, cc = 0.0;
    for (int i = 0; i < 3; ++i) {
        oc[i] = eye[i] - c[i];
        b += oc[i] * d[i];
        cc += oc[i] * oc[i];
    }
    const double disc = b * b - (cc - r * r);
    if (disc < 0.0) return -1.0;
    return -b - std::sqrt(disc);
}

TEST(Animation, KeyframesInterpolateLinearlyOrSmoothlyAndHoldOutside) {
    const Animation a = parse(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 40,
                   "interpolation": "smooth",
                   "keyframes": [{"frame": 0, "fov_deg": 30}, {"frame": 10, "fov_deg": 50},
                                 {"frame": 20, "fov_deg": 30}]},
        "materials": [{"name": "m"}],
        "objects": [{"shape": "sphere", "material": "m",
                     "keyframes": [{"frame": 2, "translate": [0, 0, 0], "scale": 1},
                                   {"frame": 6, "translate": [4, -2, 0], "scale": 3}]}]})");
    const ObjectAnimation& o = a.objects.at(0);
    // Linear: halfway between the keys; held before the first and after the last.
    const Vec3 mid = o.to_world({0.0f, 0.0f, 0.0f}, 4.0);
    EXPECT_FLOAT_EQ(mid[0], 2.0f);
    EXPECT_FLOAT_EQ(mid[1], -1.0f);
    EXPECT_FLOAT_EQ(o.to_world({1.0f, 0.0f, 0.0f}, 4.0)[0], 2.0f + 2.0f);  // scale 2
    EXPECT_FLOAT_EQ(o.to_world({0.0f, 0.0f, 0.0f}, -5.0)[0], 0.0f);
    EXPECT_FLOAT_EQ(o.to_world({0.0f, 0.0f, 0.0f}, 9.0)[0], 4.0f);
    // Smooth: passes through the keys, zero slope at the ends (Hermite 3s^2 - 2s^3 there), and
    // the Catmull-Rom tangent at the middle key is (30 - 30) / 20 = 0.
    EXPECT_FLOAT_EQ(a.camera.at(10.0).fov_deg, 50.0f);
    EXPECT_FLOAT_EQ(a.camera.at(0.0).fov_deg, 30.0f);
    EXPECT_NEAR(a.camera.at(2.5).fov_deg, 30.0f + 20.0f * (3 * 0.0625f - 2 * 0.015625f), 1e-4f);
    EXPECT_NEAR(a.camera.at(5.0).fov_deg, 40.0f, 1e-4f);
    EXPECT_NEAR(a.camera.at(15.0).fov_deg, 40.0f, 1e-4f);
    EXPECT_FLOAT_EQ(a.camera.at(-3.0).fov_deg, 30.0f);
    EXPECT_TRUE(a.is_animated());
    // A scene without keys is a still: every frame is the same scene.
    const Animation still = parse(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "materials": [{"name": "m"}], "objects": [{"shape": "quad", "material": "m"}]})");
    EXPECT_FALSE(still.is_animated());
    EXPECT_EQ(still.at(0).meshes[0].positions, still.at(7).meshes[0].positions);
}

TEST(Animation, TurntableTurnsAboutTheVerticalThroughTheOrigin) {
    const Animation a = parse(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "materials": [{"name": "m"}],
        "objects": [{"shape": "quad", "material": "m", "translate": [1, 2, 3],
                     "turntable": {"frames": 48}}]})");
    // A quarter turn after 12 frames, counter-clockwise seen from above: +x goes to -z.
    const Vec3 p = a.objects[0].to_world({1.0f, 0.0f, 0.0f}, 12.0);
    EXPECT_NEAR(p[0], 1.0f, 1e-5f);
    EXPECT_NEAR(p[1], 2.0f, 1e-5f);
    EXPECT_NEAR(p[2], 2.0f, 1e-5f);
    const Vec3 q = a.objects[0].to_world({1.0f, 0.0f, 0.0f}, 48.0);
    EXPECT_NEAR(q[0], 2.0f, 1e-5f);
    EXPECT_NEAR(q[2], 3.0f, 1e-5f);
}

// A fronto-parallel plane translating by 0.05 per frame along x at distance 5 from the eye moves
// by exactly 0.05 * focal / 5 pixels per frame; the black sky does not move.
TEST(Animation, TranslatingPlaneFlowIsExact) {
    const Animation a = parse(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 40},
        "materials": [{"name": "m"}],
        "objects": [{"shape": "quad", "material": "m", "scale": 1.2, "rotate_deg": [90, 0, 0],
                     "keyframes": [{"frame": 0, "translate": [0, 0, 0]},
                                   {"frame": 10, "translate": [0.5, 0, 0]}]}]})");
    const int w = 64, h = 48;
    const RenderBuffers b = frame(a, 5, w, h, 2);
    const Pinhole camera(5.0, 40.0, w, h);
    const double expected = 0.05 * camera.focal / 5.0;
    int on_plane = 0, visible_both = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const bool plane = b.object_id.at(x, y, 0) == 1.0f;
            on_plane += plane ? 1 : 0;
            EXPECT_NEAR(b.forward_flow.at(x, y, 0), plane ? expected : 0.0, 1e-3) << x << "," << y;
            EXPECT_NEAR(b.forward_flow.at(x, y, 1), 0.0, 1e-3);
            EXPECT_NEAR(b.backward_flow.at(x, y, 0), plane ? -expected : 0.0, 1e-3);
            EXPECT_NEAR(b.backward_flow.at(x, y, 1), 0.0, 1e-3);
            // Nothing hides the plane; the sky is hidden where the plane moves in.
            if (plane) {
                EXPECT_EQ(b.occlusion.at(x, y, 0), 0.0f);
                EXPECT_EQ(b.disocclusion.at(x, y, 0), 0.0f);
                ++visible_both;
            }
        }
    }
    EXPECT_GT(on_plane, 500);
    EXPECT_EQ(visible_both, on_plane);
    EXPECT_NEAR(expected, 0.6594, 1e-3);  // sanity of the test's own model
}

// A unit sphere spinning 10 degrees per frame: each visible point's flow is its analytic rotation
// projected by the camera (the mesh is a fine tessellation, so a small tolerance).
TEST(Animation, RotatingSphereFlowMatchesTheAnalyticMotion) {
    const Animation a = parse(R"({
        "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov_deg": 40},
        "materials": [{"name": "m"}],
        "objects": [{"shape": "sphere", "material": "m", "subdivisions": 256,
                     "turntable": {"frames": 36}}]})");
    const int w = 64, h = 64;
    const RenderBuffers b = frame(a, 3, w, h, 2);
    const Pinhole camera(4.0, 40.0, w, h);
    const double eye[3] = {0.0, 0.0, 4.0}, centre[3] = {0.0, 0.0, 0.0};
    int checked = 0;
    double worst = 0.0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            double d[3];
            camera.ray(x, y, d);
            const double t = hit_sphere(eye, d, centre, 1.0);
            if (t < 0.0) {
                EXPECT_EQ(b.object_id.at(x, y, 0), 0.0f);
                continue;
            }
            const double p[3] = {eye[0] + t * d[0], eye[1] + t * d[1], eye[2] + t * d[2]};
            // Away from the silhouette (where the facets and the sphere differ most).
            if (-(p[0] * d[0] + p[1] * d[1] + p[2] * d[2]) < 0.4) continue;
            for (int dir : {1, -1}) {
                const double angle = dir * 10.0 * kPi / 180.0;  // counter-clockwise from above
                const double c = std::cos(angle), s = std::sin(angle);
                const double q[3] = {c * p[0] + s * p[2], p[1], -s * p[0] + c * p[2]};
                double px = 0.0, py = 0.0;
                camera.project(q, px, py);
                const Image& flow = dir > 0 ? b.forward_flow : b.backward_flow;
                const double eu = flow.at(x, y, 0) - (px - (x + 0.5));
                const double ev = flow.at(x, y, 1) - (py - (y + 0.5));
                worst = std::max(worst, std::hypot(eu, ev));
            }
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000);
    EXPECT_LT(worst, 0.05) << "largest end-point error in pixels";
}

// A sphere passing in front of a wall: wall pixels behind the sphere's next position are
// occluded in t+1, wall pixels behind its previous position were hidden in t-1; compared with
// the analytic visibility away from the sphere's outline.
TEST(Animation, OcclusionMasksFlagTheRegionsTheSphereCoversAndUncovers) {
    const Animation a = parse(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 40},
        "sky": [1, 1, 1],
        "materials": [{"name": "m"}],
        "objects": [{"shape": "sphere", "material": "m", "scale": 0.5, "subdivisions": 128,
                     "keyframes": [{"frame": 0, "translate": [-1, 0, 0]},
                                   {"frame": 10, "translate": [1, 0, 0]}]},
                    {"shape": "quad", "material": "m", "scale": 4, "rotate_deg": [90, 0, 0],
                     "translate": [0, 0, -2]}]})");
    const int w = 80, h = 60;
    const RenderBuffers b = frame(a, 5, w, h, 2);
    const Pinhole camera(5.0, 40.0, w, h);
    const double eye[3] = {0.0, 0.0, 5.0};
    int occluded = 0, disoccluded = 0, wall = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            double d[3];
            camera.ray(x, y, d);
            const double now[3] = {0.0, 0.0, 0.0};  // sphere centre at frame 5
            if (hit_sphere(eye, d, now, 0.5) >= 0.0) {
                // Sphere pixels facing the camera stay visible (a translation).
                const double t = hit_sphere(eye, d, now, 0.5);
                const double n_dot_v = -((eye[0] + t * d[0]) * d[0] + (eye[1] + t * d[1]) * d[1] +
                                         (eye[2] + t * d[2] - 0.0) * d[2]) /
                                       0.5;
                if (n_dot_v > 0.5) {
                    EXPECT_EQ(b.occlusion.at(x, y, 0), 0.0f) << x << "," << y;
                    EXPECT_EQ(b.disocclusion.at(x, y, 0), 0.0f) << x << "," << y;
                }
                continue;
            }
            // The wall point (static) and the sphere's centre at t+1 and t-1.
            const double t = (eye[2] + 2.0) / -d[2];
            const double p[3] = {t * d[0], t * d[1], eye[2] + t * d[2]};
            if (std::fabs(p[0]) > 3.9 || std::fabs(p[1]) > 3.9) continue;
            ++wall;
            for (int step : {1, -1}) {
                const double c[3] = {0.2 * step, 0.0, 0.0};
                // Distance of the sphere centre from the eye-to-wall-point line.
                double e[3], len = 0.0;
                for (int i = 0; i < 3; ++i) {
                    e[i] = p[i] - eye[i];
                    len += e[i] * e[i];
                }
                len = std::sqrt(len);
                double along = 0.0, dist2 = 0.0;
                for (int i = 0; i < 3; ++i) along += (c[i] - eye[i]) * e[i] / len;
                for (int i = 0; i < 3; ++i) {
                    const double r = c[i] - eye[i] - along * e[i] / len;
                    dist2 += r * r;
                }
                const double dist = std::sqrt(dist2);
                if (std::fabs(dist - 0.5) < 0.02) continue;  // the outline: facets vs sphere
                const bool hidden = dist < 0.5;
                const Image& mask = step > 0 ? b.occlusion : b.disocclusion;
                EXPECT_EQ(mask.at(x, y, 0), hidden ? 1.0f : 0.0f) << x << "," << y << " " << step;
                if (hidden) (step > 0 ? occluded : disoccluded) += 1;
            }
        }
    }
    EXPECT_GT(wall, 2000);
    EXPECT_GT(occluded, 10);  // the strip the sphere moves onto
    EXPECT_GT(disoccluded, 10);
}

Animation spot_turntable() {
    auto spot = builtin_animation("spot-on-table");
    EXPECT_TRUE(spot.ok()) << spot.status().message();
    Animation a = std::move(spot).value();
    a.objects.at(0).turntable_frames = 24.0f;  // 15 degrees per frame
    return a;
}

// Following the forward flow of frame t and then the backward flow of frame t+1 returns to the
// start on pixels that are not occluded (the round trip the TCIA consistency test χ makes).
TEST(Animation, ForwardAndBackwardFlowsAreConsistentOnVisiblePixels) {
    const Animation a = spot_turntable();
    const int w = 120, h = 91;
    const RenderBuffers now = frame(a, 4, w, h, 2), next = frame(a, 5, w, h, 2);
    std::vector<double> errors;
    int occluded = 0, spot_pixels = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (now.object_id.at(x, y, 0) != 1.0f) continue;  // the cow moves; the rest is still
            ++spot_pixels;
            if (now.occlusion.at(x, y, 0) > 0.5f) {
                ++occluded;
                continue;
            }
            const float fx = now.forward_flow.at(x, y, 0), fy = now.forward_flow.at(x, y, 1);
            float bx = 0.0f, by = 0.0f;
            ASSERT_TRUE(video::sample_bilinear(next.backward_flow, static_cast<float>(x) + fx,
                                               static_cast<float>(y) + fy, 0, bx));
            ASSERT_TRUE(video::sample_bilinear(next.backward_flow, static_cast<float>(x) + fx,
                                               static_cast<float>(y) + fy, 1, by));
            errors.push_back(std::hypot(fx + bx, fy + by));
        }
    }
    ASSERT_GT(spot_pixels, 800);
    ASSERT_GT(errors.size(), 700u);
    EXPECT_GT(occluded, 0);  // a turning cow hides some of itself
    std::sort(errors.begin(), errors.end());
    EXPECT_LT(errors[errors.size() / 2], 0.05) << "median round trip (px)";
    EXPECT_LT(errors[errors.size() * 9 / 10], 0.3) << "90th percentile round trip (px)";
    // The flow is not trivially zero: the cow turns by 15 degrees.
    double mean_motion = 0.0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (now.object_id.at(x, y, 0) == 1.0f)
                mean_motion +=
                    std::hypot(now.forward_flow.at(x, y, 0), now.forward_flow.at(x, y, 1));
        }
    }
    EXPECT_GT(mean_motion / spot_pixels, 1.0);
}

TEST(Animation, FramesAreIdenticalForOneAndTwoThreads) {
    const Animation a = spot_turntable();
    const RenderBuffers one = frame(a, 2, 48, 36, 1, 2), two = frame(a, 2, 48, 36, 2, 2);
    const auto la = one.layers(), lb = two.layers();
    ASSERT_EQ(la.size(), 17u);
    ASSERT_EQ(la.size(), lb.size());
    for (std::size_t i = 0; i < la.size(); ++i) {
        ASSERT_EQ(la[i].first, lb[i].first);
        ASSERT_EQ(la[i].second->size(), lb[i].second->size());
        EXPECT_TRUE(std::equal(la[i].second->data().begin(), la[i].second->data().end(),
                               lb[i].second->data().begin()))
            << la[i].first;
    }
}

// Orientation runs along the outline: on a sphere seen head-on it is perpendicular to the
// direction from the image centre (a circle's tangent), in [0, pi), counter-clockwise.
TEST(Animation, OrientationIsTheScreenTangentAlongTheOutline) {
    const Animation a = parse(R"({
        "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov_deg": 40},
        "materials": [{"name": "m"}],
        "objects": [{"shape": "sphere", "material": "m", "subdivisions": 128}]})");
    const int w = 64, h = 64;
    const RenderBuffers b = frame(a, 0, w, h);
    int checked = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (b.object_id.at(x, y, 0) != 1.0f) continue;
            const double rx = x + 0.5 - 32.0, ry = -(y + 0.5 - 32.0);  // y up
            if (std::hypot(rx, ry) < 4.0) continue;                    // head-on: undefined
            const double angle = b.orientation.at(x, y, 0);
            ASSERT_GE(angle, 0.0);
            ASSERT_LT(angle, kPi);
            // The tangent of the circle through this pixel: perpendicular to (rx, ry).
            const double dot = std::cos(angle) * rx + std::sin(angle) * ry;
            EXPECT_LT(std::fabs(dot) / std::hypot(rx, ry), 0.02) << x << "," << y;
            ++checked;
        }
    }
    EXPECT_GT(checked, 500);
}

// Lines: the outline of a sphere in front of a wall is marked on the sphere's side, the inside of
// the sphere and the open wall are not.
TEST(Animation, LinesMarkTheNearSideOfSilhouettes) {
    const Animation a = parse(R"({
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 40},
        "materials": [{"name": "m"}],
        "objects": [{"shape": "sphere", "material": "m", "scale": 0.8},
                    {"shape": "quad", "material": "m", "scale": 4, "rotate_deg": [90, 0, 0],
                     "translate": [0, 0, -2]}]})");
    const int w = 64, h = 64;
    const RenderBuffers b = frame(a, 0, w, h);
    int outline = 0;
    for (int y = 1; y + 1 < h; ++y) {
        for (int x = 1; x + 1 < w; ++x) {
            const float id = b.object_id.at(x, y, 0);
            bool border = false;
            for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
                border = border || b.object_id.at(x + dx, y + dy, 0) != id;
            const bool expected = id == 1.0f && border;
            EXPECT_EQ(b.lines.at(x, y, 0), expected ? 1.0f : 0.0f) << x << "," << y;
            outline += expected ? 1 : 0;
        }
    }
    EXPECT_GT(outline, 60);
}

// One OBJ mesh (one object id) in a temporary folder.
Animation mesh_scene(const std::string& obj, const std::string& camera) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("exemplar_lines_" +
                      std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir);
    std::ofstream((dir / "mesh.obj").string()) << obj;
    auto a = parse_animation(R"({"camera": )" + camera + R"(, "materials": [{"name": "m"}],
        "objects": [{"shape": "mesh", "file": "mesh.obj", "material": "m"}]})",
                             "lines.json", dir.string());
    std::filesystem::remove_all(dir);
    EXPECT_TRUE(a.ok()) << a.status().message();
    return a.ok() ? std::move(a).value() : Animation{};
}

// Two parts of one mesh (same object id): a small square 1 unit in front of a large one. The
// depth step is marked on the near part only; the flat interiors are not.
TEST(Animation, LinesMarkDepthStepsWithinOneObject) {
    const Animation a =
        mesh_scene(R"(v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
v -0.4 -0.4 1
v 0.4 -0.4 1
v 0.4 0.4 1
v -0.4 0.4 1
f 1 2 3 4
f 5 6 7 8
)",
                   R"({"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 30})");
    const int w = 64, h = 64;
    const RenderBuffers b = frame(a, 0, w, h);
    int steps = 0;
    for (int y = 1; y + 1 < h; ++y) {
        for (int x = 1; x + 1 < w; ++x) {
            if (b.object_id.at(x, y, 0) != 1.0f) continue;
            const bool front = b.depth.at(x, y, 0) < 4.5f;
            bool next_to_back = false, next_to_sky = false;
            for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                next_to_sky = next_to_sky || b.object_id.at(x + dx, y + dy, 0) == 0.0f;
                next_to_back = next_to_back || b.depth.at(x + dx, y + dy, 0) > 4.5f;
            }
            const bool expected = next_to_sky || (front && next_to_back);
            EXPECT_EQ(b.lines.at(x, y, 0), expected ? 1.0f : 0.0f) << x << "," << y;
            steps += front && next_to_back ? 1 : 0;
        }
    }
    EXPECT_GT(steps, 40);
}

// A cube with shared vertices (so its shading normals are smooth across the edges): the edges
// between its visible faces are creases by the facet normals.
TEST(Animation, LinesMarkTheCreasesOfACube) {
    const Animation a =
        mesh_scene(R"(v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 4 8 7 3
f 1 5 8 4
f 2 3 7 6
)",
                   R"({"position": [3, 2.5, 4], "look_at": [0, 0, 0], "fov_deg": 40})");
    const int w = 80, h = 80;
    const RenderBuffers b = frame(a, 0, w, h);
    // Which face of the cube the ray through a pixel centre hits (the axis of the largest
    // coordinate of the hit point), from the depth buffer and an independent camera model.
    const double eye[3] = {3.0, 2.5, 4.0};
    double f[3] = {-3.0, -2.5, -4.0};
    const double fl = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (double& c : f) c /= fl;
    double r[3] = {f[1] * 0.0 - f[2] * 1.0, f[2] * 0.0 - f[0] * 0.0, f[0] * 1.0 - f[1] * 0.0};
    const double rl = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (double& c : r) c /= rl;
    const double u[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2],
                         r[0] * f[1] - r[1] * f[0]};
    const double t = std::tan(20.0 * kPi / 180.0);
    const auto face = [&](int x, int y) {
        if (b.object_id.at(x, y, 0) != 1.0f) return -1;
        const double sx = (2.0 * (x + 0.5) / w - 1.0) * t, sy = (1.0 - 2.0 * (y + 0.5) / h) * t;
        double d[3], len = 0.0;
        for (int i = 0; i < 3; ++i) {
            d[i] = f[i] + sx * r[i] + sy * u[i];
            len += d[i] * d[i];
        }
        int best = 0;
        double p[3];
        for (int i = 0; i < 3; ++i) {
            p[i] = eye[i] + b.depth.at(x, y, 0) * d[i] / std::sqrt(len);
            if (std::fabs(p[i]) > std::fabs(p[best])) best = i;
        }
        return best;
    };
    int creases = 0;
    for (int y = 1; y + 1 < h; ++y) {
        for (int x = 1; x + 1 < w; ++x) {
            const int own = face(x, y);
            if (own < 0) continue;
            bool edge = false, sky = false;
            for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const int other = face(x + dx, y + dy);
                sky = sky || other < 0;
                if (other >= 0 && other != own) {
                    edge = true;
                    // At least one side of every crease is marked.
                    EXPECT_TRUE(b.lines.at(x, y, 0) == 1.0f ||
                                b.lines.at(x + dx, y + dy, 0) == 1.0f)
                        << x << "," << y;
                }
            }
            if (!edge && !sky) {
                EXPECT_EQ(b.lines.at(x, y, 0), 0.0f) << x << "," << y;
            }
            creases += edge ? 1 : 0;
        }
    }
    EXPECT_GT(creases, 60);
}

// The bundled turntable example: Spot turns once in its 48 frames.
TEST(Animation, TheTurntableExampleTurnsSpotOnce) {
    auto a = load_animation(EXEMPLAR_SOURCE_DIR "/examples/render/spot-turntable.json");
    ASSERT_TRUE(a.ok()) << a.status().message();
    EXPECT_TRUE(a->is_animated());
    ASSERT_TRUE(a->frames.has_value());
    EXPECT_EQ(a->frames->first, 0);
    EXPECT_EQ(a->frames->second, 47);
    const Scene first = a->at(0), turned = a->at(48);
    ASSERT_EQ(first.meshes.size(), turned.meshes.size());
    for (std::size_t i = 0; i < first.meshes[0].positions.size(); i += 97) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(first.meshes[0].positions[i][c], turned.meshes[0].positions[i][c], 1e-4f);
        }
    }
    EXPECT_NE(a->at(12).meshes[0].positions[0], first.meshes[0].positions[0]);
}

TEST(Animation, BadKeyframesAreNamed) {
    const auto error = [](const std::string& object, const std::string& extra = "") {
        const std::string json = R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},)" +
                                 extra + R"("materials": [{"name": "m"}], "objects": [)" + object +
                                 "]}";
        auto a = parse_animation(json, "anim.json", ".");
        return a.ok() ? std::string("(parsed)") : a.status().message();
    };
    const std::string sphere = R"({"shape": "sphere", "material": "m", )";
    EXPECT_EQ(error(sphere + R"("keyframes": [{"frame": 3}, {"frame": 3}]})"),
              "anim.json: objects[0].keyframes[1].frame: must be larger than the previous "
              "keyframe's");
    EXPECT_EQ(error(sphere + R"("keyframes": [{"frame": 0, "spin": 1}]})")
                  .rfind("anim.json: objects[0].keyframes[0].spin: unknown key", 0),
              0u);
    EXPECT_EQ(error(sphere + R"("keyframes": [{"translate": [0, 0, 0]}]})"),
              "anim.json: objects[0].keyframes[0].frame: missing (required)");
    EXPECT_EQ(error(sphere + R"("interpolation": "cubic"})"),
              "anim.json: objects[0].interpolation: \"cubic\" is invalid (must be linear or "
              "smooth)");
    EXPECT_EQ(error(sphere + R"("turntable": {"degrees": 90}})"),
              "anim.json: objects[0].turntable.frames: missing (required)");
    EXPECT_EQ(error(sphere + R"("keyframes": []})"),
              "anim.json: objects[0].keyframes: must be a non-empty array");
    EXPECT_EQ(error(R"({"shape": "sphere", "material": "m"})", R"("frames": [5, 2],)")
                  .rfind("anim.json: frames: [5,2] is "
                         "invalid",
                         0),
              0u);
    // A keyframed camera that looks at itself.
    auto camera = parse_animation(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0],
        "keyframes": [{"frame": 0, "position": [0, 0, 5]}, {"frame": 4, "position": [0, 0, 0]}]},
        "materials": [{"name": "m"}], "objects": [{"shape": "sphere", "material": "m"}]})",
                                  "cam.json", ".");
    ASSERT_FALSE(camera.ok());
    EXPECT_EQ(camera.status().message(),
              "cam.json: camera.keyframes[1].look_at: equals the camera position");
}

}  // namespace
}  // namespace exemplar::render
