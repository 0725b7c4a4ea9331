#pragma once
/// \file
/// Animated scenes: keyframed camera and object transforms, and per-frame renders that add the
/// buffers a temporally coherent stylization needs (motion vectors, occlusion, orientation,
/// lines) to the light-path buffers of `render`.
///
/// Time is measured in frames. A property (camera position, look_at, up, fov_deg; object
/// translate, rotate_deg, scale) is animated when keyframes set it: between two keys it is
/// interpolated (linearly, or smoothly with a Catmull-Rom spline whose end tangents are zero),
/// before the first key it holds the first key's value and after the last the last one's.
/// Properties no keyframe sets keep their static value. A turntable spins an object about the
/// vertical axis through its origin (`translate`) by `turntable.degrees` every
/// `turntable.frames` frames, after its own rotation. Format of the JSON keys: docs/render.md.
///
/// Motion (see docs/render.md and docs/video.md for the convention): the forward flow f of
/// frame t maps pixel x to x + f(x) in frame t+1, the backward flow b of frame t maps x to
/// x + b(x) in frame t-1 (Middlebury/OpenCV). Both are exact: the surface point seen through the
/// centre of pixel x (triangle and barycentric coordinates) is moved with its mesh to frame t±1
/// and projected by that frame's camera; the sky is treated as infinitely far.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/render/render.hpp"
#include "exemplar/render/scene.hpp"

namespace exemplar::render {

/// How a property moves between two keyframes.
enum class Interpolation {
    Linear,  ///< Straight lines between keys (default).
    Smooth,  ///< Catmull-Rom spline through the keys, zero velocity at the first and last key.
};

/// Keys (frame, value) of one property, sorted by frame, frames distinct.
template <typename T>
struct Track {
    std::vector<std::pair<double, T>> keys;
};

/// The camera over time.
struct CameraAnimation {
    Camera camera;  ///< The static values (used where a property has no keys).
    Track<Vec3> position, look_at, up;
    Track<float> fov_deg;
    Interpolation interpolation = Interpolation::Linear;

    /// The camera at `frame`.
    Camera at(double frame) const;
    bool is_animated() const;
};

/// Scale, then rotation about x, y, z (degrees, in that order), then translation.
struct Transform {
    Vec3 translate{0.0f, 0.0f, 0.0f};
    Vec3 rotate_deg{0.0f, 0.0f, 0.0f};
    Vec3 scale{1.0f, 1.0f, 1.0f};
};

/// One object of the scene file: object-space meshes (one per material) and their transform.
struct ObjectAnimation {
    std::string name;
    std::vector<Mesh> meshes;  ///< Object space (after `normalize`); normals are not used.
    Transform transform;       ///< The static values.
    Track<Vec3> translate, rotate_deg, scale;
    Interpolation interpolation = Interpolation::Linear;
    float turntable_frames = 0.0f;  ///< Frames per turntable turn; 0 = no turntable.
    float turntable_degrees = 360.0f;

    /// World position of object-space point `p` at `frame`.
    Vec3 to_world(const Vec3& p, double frame) const;
    bool is_animated() const;
};

/// A scene file with its animation. `at(frame)` gives the scene to render.
struct Animation {
    std::string source;  ///< File name or "builtin:<name>", for messages.
    CameraAnimation camera;
    std::vector<AreaLight> lights;
    Vec3 sky{0.0f, 0.0f, 0.0f};
    std::vector<Material> materials;
    std::vector<ObjectAnimation> objects;       ///< Object ids are 1-based positions here.
    std::optional<std::pair<int, int>> frames;  ///< The file's `frames` [first, last], if given.

    /// True if the camera or any object moves.
    bool is_animated() const;
    /// The scene at `frame` (world-space meshes, in the same order at every frame).
    Scene at(double frame) const;
};

/// Parses a scene file with its animation (same format and errors as `parse_scene`).
Result<Animation> parse_animation(const std::string& json_text, const std::string& source,
                                  const std::string& base_dir);

/// Loads a scene file with its animation (relative mesh paths are relative to its folder).
Result<Animation> load_animation(const std::string& path);

/// A built-in scene with its animation (see `builtin_scene`).
Result<Animation> builtin_animation(const std::string& name, const std::string& mesh_dir = "");

/// Renders frame `frame` of `animation`: the buffers of `render(animation.at(frame))` plus
/// `forward_flow`, `backward_flow`, `occlusion` and `disocclusion` (see RenderBuffers). The
/// path tracer's random numbers do not depend on the frame (same seed, same noise pattern).
/// InvalidArgument naming the frame if the camera is degenerate at frame - 1, frame or frame + 1.
Result<RenderBuffers> render_frame(const Animation& animation, int frame,
                                   const RenderOptions& options, const RunContext& context = {});

}  // namespace exemplar::render
