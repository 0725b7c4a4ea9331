// Fits the sphere-on-table set-up (camera, wall, light, exposure, materials) to the StyLit
// authors' buffers by coordinate descent on the mean absolute error of our sRGB-encoded buffers
// (tests/render/calibration.hpp). Small renders with a fixed seed make the objective
// deterministic. Prints the fitted scene JSON. The first sphere-on-table.json started from it;
// the current albedos, sky and light came from descents over render_calibrate (docs/render.md).
//
//   render_fit [rounds]

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "calibration.hpp"
#include "exemplar/render/scene.hpp"

namespace {

using namespace exemplar;

struct Param {
    const char* name;
    double value, step, lo, hi;
};

// Scene JSON from the parameters (see examples/render/sphere-on-table.json for the meaning).
std::string scene_json(const std::vector<Param>& p) {
    auto v = [&](const char* name) {
        for (const Param& q : p) {
            if (std::string(q.name) == name) return q.value;
        }
        std::abort();
    };
    const double pi = 3.14159265358979;
    const double az = v("light_azimuth_deg") * pi / 180, el = v("light_elevation_deg") * pi / 180;
    const double r = v("light_distance");
    const double lx = r * std::cos(el) * std::sin(az), ly = 1 + r * std::sin(el),
                 lz = -r * std::cos(el) * std::cos(az);
    const double e = v("camera_elevation_deg") * pi / 180, d = v("camera_distance");
    char text[4096];
    std::snprintf(
        text, sizeof text,
        R"({"camera": {"position": [0, %.4f, %.4f], "look_at": [%.4f, %.4f, 0], "fov_deg": %.3f},
 "sky": [%.4f, %.4f, %.4f],
 "lights": [{"center": [%.4f, %.4f, %.4f], "look_at": [0, 1, 0], "width": %.4f, "height": %.4f,
             "roll_deg": %.3f, "radiance": [%.4f, %.4f, %.4f]}],
 "materials": [
   {"name": "red", "diffuse": [%.4f, %.4f, %.4f], "specular": [%.4f, %.4f, %.4f], "exponent": %.2f},
   {"name": "white", "diffuse": [%.4f, %.4f, %.4f]}],
 "objects": [
   {"name": "sphere", "shape": "sphere", "material": "red", "translate": [0, 1, 0]},
   {"name": "table", "shape": "quad", "material": "white", "scale": [30, 1, 30]},
   {"name": "wall", "shape": "quad", "material": "white", "scale": [30, 1, 15],
    "rotate_deg": [90, %.3f, 0], "translate": [0, 15, %.4f]}]})",
        1 + d * std::sin(e), d * std::cos(e), v("look_x"), v("look_y"), v("fov_deg"), v("sky"),
        v("sky"), v("sky") * v("sky_blue"), lx, ly, lz, v("light_width"), v("light_height"),
        v("light_roll_deg"), v("radiance"), v("radiance"), v("radiance"), v("red_diffuse"),
        v("red_other"), v("red_other"), v("specular"), v("specular"), v("specular"), v("exponent"),
        v("white"), v("white"), v("white"), v("wall_yaw_deg"), -v("wall_distance"));
    return text;
}

// Weighted error of the buffers selected by `weights` (fullgi, dirdif, dirspc, indirb).
double objective(const std::vector<Param>& p, const std::vector<double>& weights, int bounces) {
    auto scene = render::parse_scene(scene_json(p), "fit", ".");
    if (!scene.ok()) {
        std::fprintf(stderr, "%s\n", scene.status().message().c_str());
        std::exit(1);
    }
    render::RenderOptions options;
    options.width = 120;
    options.height = 91;
    options.samples_per_pixel = bounces > 1 ? 24 : 12;
    options.max_bounces = bounces;
    auto buffers = render::render(*scene, options, RunContext(0));
    auto errors =
        render::testing::calibration_errors(*buffers, EXEMPLAR_SOURCE_DIR "/examples/stylit");
    double sum = 0;
    for (std::size_t i = 0; i < weights.size(); ++i) sum += weights[i] * (*errors)[i].mean_abs;
    return sum;
}

void descend(std::vector<Param>& p, const std::vector<std::string>& names,
             const std::vector<double>& weights, int bounces, int rounds) {
    double best = objective(p, weights, bounces);
    for (int round = 0; round < rounds; ++round) {
        for (const std::string& name : names) {
            Param* found = nullptr;
            for (Param& candidate : p) {
                if (name == candidate.name) found = &candidate;
            }
            if (found == nullptr) std::abort();
            Param& q = *found;
            for (double direction : {1.0, -1.0}) {
                while (true) {
                    const double old = q.value;
                    q.value = std::fmin(q.hi, std::fmax(q.lo, old + direction * q.step));
                    const double e = q.value == old ? best : objective(p, weights, bounces);
                    if (e < best - 1e-6) {
                        best = e;
                    } else {
                        q.value = old;
                        break;
                    }
                }
            }
        }
        for (Param& q : p) q.step *= 0.6;
        std::fprintf(stderr, "round %d: %.5f\n", round, best);
    }
}

}  // namespace

int main(int argc, char** argv) {
    const int rounds = argc > 1 ? std::atoi(argv[1]) : 6;
    std::vector<Param> p = {
        {"camera_elevation_deg", 12, 1, 0, 30},
        {"camera_distance", 5.9, 0.1, 3, 12},
        {"look_x", -0.05, 0.02, -1, 1},
        {"look_y", 0.15, 0.02, -1, 1},
        {"fov_deg", 36, 0.5, 15, 70},
        {"wall_distance", 6.25, 0.3, 1.5, 20},
        {"wall_yaw_deg", 24, 1, -45, 45},
        {"light_azimuth_deg", 60, 5, 0, 120},
        {"light_elevation_deg", 65, 3, 10, 89},
        {"light_distance", 5, 0.5, 3, 30},
        {"light_width", 1.5, 0.2, 0.1, 4},
        {"light_height", 0.75, 0.1, 0.1, 4},
        {"light_roll_deg", 0, 10, -90, 90},
        {"radiance", 30, 10, 0.1, 1000},
        {"sky", 0.15, 0.05, 0, 2},
        {"sky_blue", 1.1, 0.05, 0.8, 1.5},
        {"red_diffuse", 0.8, 0.1, 0.05, 0.9},
        {"red_other", 0.02, 0.01, 0, 0.2},
        {"specular", 0.1, 0.03, 0, 0.1},
        {"exponent", 200, 60, 5, 5000},
        {"white", 0.8, 0.05, 0.3, 0.95},
    };
    // The light and exposure from the direct diffuse buffer (one bounce: fast), then the
    // camera and wall, starting from a geometric estimate (sphere outline, wall line).
    const std::vector<std::string> light = {"radiance", "light_azimuth_deg", "light_elevation_deg",
                                            "light_distance", "radiance"};
    descend(p, light, {0, 1, 0, 0}, 1, rounds);
    descend(p,
            {"camera_elevation_deg", "camera_distance", "look_x", "look_y", "fov_deg",
             "wall_distance", "wall_yaw_deg"},
            {0, 1, 0, 0}, 1, rounds);
    descend(p, light, {0, 1, 0, 0}, 1, rounds);
    // The highlight's shape from the direct specular buffer.
    descend(p, {"specular", "exponent", "light_width", "light_height", "light_roll_deg"},
            {0, 0.2, 1, 0}, 1, rounds);
    // Sky and albedos from the full and indirect buffers.
    descend(p, {"sky", "sky_blue", "white", "red_other", "red_diffuse"}, {1, 0, 0, 1}, 6, rounds);
    std::printf("%s\n", scene_json(p).c_str());
    for (const Param& q : p) std::fprintf(stderr, "%s = %g\n", q.name, q.value);
    return 0;
}
