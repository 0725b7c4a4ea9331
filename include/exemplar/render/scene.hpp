#pragma once
/// \file
/// Scenes of the renderer: a pinhole camera, rectangular area lights, a uniform sky, diffuse +
/// glossy materials and triangle meshes (spheres, quads and OBJ files) with transforms.
///
/// Conventions: right-handed world space, y up, lengths in scene units, angles in degrees in
/// scene files. Scenes come from small JSON files (format: docs/render.md, examples in
/// examples/render/) or from the built-in set (`builtin_scene`). Parsing is strict: an unknown
/// key, a missing required key, a value of the wrong type or range, or a missing mesh file is an
/// error whose one-line message names the file and the key, e.g.
/// `scene.json: lights[0].size: -1 is invalid (must be > 0)`.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "exemplar/core/status.hpp"

namespace exemplar::render {

/// A 3-vector of floats (points, directions, RGB).
using Vec3 = std::array<float, 3>;

/// Pinhole camera.
struct Camera {
    Vec3 position{0.0f, 1.0f, 5.0f};  ///< Eye point.
    Vec3 look_at{0.0f, 1.0f, 0.0f};   ///< Point at the image centre.
    Vec3 up{0.0f, 1.0f, 0.0f};        ///< Up direction (need not be orthogonal to the view).
    float fov_deg = 40.0f;            ///< Vertical field of view in degrees, (0, 180).
};

/// One-sided rectangular area light, emitting towards `look_at`. Lights are not visible to
/// camera rays and do not block rays; they are sampled directly (next-event estimation).
struct AreaLight {
    Vec3 center{0.0f, 5.0f, 0.0f};
    Vec3 look_at{0.0f, 0.0f, 0.0f};  ///< The light's normal points from center to look_at.
    float width = 1.0f;              ///< Edge lengths, > 0.
    float height = 1.0f;
    float roll_deg = 0.0f;               ///< Rotation of the rectangle about its normal.
    Vec3 radiance{10.0f, 10.0f, 10.0f};  ///< Emitted radiance (linear RGB), >= 0.
};

/// Diffuse + glossy ("plastic") material: Lambertian `diffuse` plus a normalized Blinn-Phong lobe
/// scaled by `specular`. Each lobe is a separate event for the light-path buffers (D or S).
struct Material {
    std::string name;
    Vec3 diffuse{0.8f, 0.8f, 0.8f};  ///< Albedo, each in [0, 1].
    Vec3 specular{0.0f, 0.0f,
                  0.0f};      ///< Glossy reflectance, each in [0, 1]; diffuse+specular <= 1.
    float exponent = 100.0f;  ///< Blinn-Phong exponent, 1..100000 (larger = sharper highlight).
};

/// A triangle mesh in world space with per-vertex normals.
struct Mesh {
    std::string name;
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  ///< One per position (smooth shading).
    std::vector<std::array<std::uint32_t, 3>> triangles;
    int material = 0;   ///< Index into Scene::materials.
    int object_id = 0;  ///< 1-based object index written to the object-id buffer.
};

/// A scene ready to render.
struct Scene {
    std::string source;  ///< File name or "builtin:<name>", for messages.
    Camera camera;
    std::vector<AreaLight> lights;
    Vec3 sky{0.0f, 0.0f, 0.0f};  ///< Uniform radiance of rays that leave the scene.
    std::vector<Material> materials;
    std::vector<Mesh> meshes;
};

/// Parses a scene from JSON text. `source` names it in messages; relative mesh paths are resolved
/// against `base_dir`. Fails with InvalidArgument (bad JSON, key or value) or IoError (mesh file).
/// A file with keyframes or turntables gives the scene at its first frame (`frames`[0], else
/// frame 0); `parse_animation` (exemplar/render/animation.hpp) keeps the animation.
Result<Scene> parse_scene(const std::string& json_text, const std::string& source,
                          const std::string& base_dir);

/// Loads a scene file (relative mesh paths are relative to the file's folder).
Result<Scene> load_scene(const std::string& path);

/// Names of the built-in scenes: "sphere-on-table" (the StyLit exemplar set-up) and
/// "spot-on-table" (the bundled Spot mesh under the same camera and light).
std::vector<std::string> builtin_scene_names();

/// The JSON text of a built-in scene (the same as examples/render/<name>.json), or an
/// InvalidArgument error listing the names.
Result<std::string> builtin_scene_json(const std::string& name);

/// Loads a built-in scene. Meshes it names are looked up in `mesh_dir` (default: the examples
/// folder of the source tree this library was built from).
Result<Scene> builtin_scene(const std::string& name, const std::string& mesh_dir = "");

}  // namespace exemplar::render
