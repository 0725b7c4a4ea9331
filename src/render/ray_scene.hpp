#pragma once
// Ray queries of the renderer and its camera model (private to src/render).

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "exemplar/core/status.hpp"
#include "exemplar/render/scene.hpp"
#include "ray_backend.hpp"
#include "vec_math.hpp"

namespace exemplar::render {

// The ray-query scene of `scene` (meshes in order: geometry ID = mesh index) from the Embree
// backend (ray_backend.hpp), loaded on first use. Unsupported if the plugin is missing;
// Internal with Embree's message if the device or the build fails.
Result<std::unique_ptr<rays::RayScene>> build_ray_scene(const Scene& scene);

struct Hit {
    bool found = false;
    float t = 0.0f;
    Vec3 position{}, geometric_normal{}, shading_normal{};
    int mesh = -1;
    unsigned primitive = 0;    // triangle index in the mesh
    float u = 0.0f, v = 0.0f;  // barycentric coordinates of vertices 1 and 2
};

// The nearest hit of a ray (tfar = infinity) beyond `tnear`, with both normals facing the ray.
inline Hit intersect(const Scene& scene, const rays::RayScene& queries, const Vec3& origin,
                     const Vec3& direction, float tnear) {
    const rays::RawHit rh = queries.intersect(origin.data(), direction.data(), tnear);
    Hit hit;
    if (!rh.found) return hit;
    hit.found = true;
    hit.t = rh.t;
    hit.mesh = static_cast<int>(rh.mesh);
    hit.primitive = rh.primitive;
    hit.u = rh.u;
    hit.v = rh.v;
    const Mesh& mesh = scene.meshes[rh.mesh];
    const auto& tri = mesh.triangles[rh.primitive];
    const float u = rh.u, v = rh.v, w = 1.0f - u - v;
    hit.position = add(origin, scale(direction, hit.t));
    hit.geometric_normal = normalize({rh.normal[0], rh.normal[1], rh.normal[2]});
    hit.shading_normal =
        normalize(add(scale(mesh.normals[tri[0]], w),
                      add(scale(mesh.normals[tri[1]], u), scale(mesh.normals[tri[2]], v))));
    // Two-sided surfaces: both normals face the incoming ray.
    if (dot(hit.geometric_normal, direction) > 0.0f)
        hit.geometric_normal = scale(hit.geometric_normal, -1.0f);
    if (dot(hit.shading_normal, hit.geometric_normal) < 0.0f)
        hit.shading_normal = scale(hit.shading_normal, -1.0f);
    return hit;
}

// True if anything lies on the ray between tnear = 0 and `tfar`.
inline bool occluded(const rays::RayScene& queries, const Vec3& origin, const Vec3& direction,
                     float tfar) {
    return queries.occluded(origin.data(), direction.data(), tfar);
}

// The pinhole camera of a render: rays through pixel positions and the inverse, projection of
// world points to pixel positions (continuous coordinates: pixel (x, y) covers [x, x+1) x
// [y, y+1), its centre is (x + 0.5, y + 0.5)).
class CameraModel {
public:
    CameraModel(const Camera& c, int width, int height)
        : position_(c.position),
          width_(static_cast<float>(width)),
          height_(static_cast<float>(height)) {
        forward_ = normalize(sub(c.look_at, c.position));
        right_ = normalize(cross(forward_, c.up));
        up_ = cross(right_, forward_);
        tan_half_ = std::tan(c.fov_deg * 3.14159265358979f / 360.0f);
        aspect_ = width_ / height_;
    }

    const Vec3& position() const { return position_; }

    // Unit direction of the ray through pixel position (px, py).
    Vec3 ray(float px, float py) const {
        const float sx = (2.0f * px / width_ - 1.0f) * tan_half_ * aspect_;
        const float sy = (1.0f - 2.0f * py / height_) * tan_half_;
        return normalize(add(forward_, add(scale(right_, sx), scale(up_, sy))));
    }

    // Pixel position of the direction `d` from the eye (a point at infinity, or p - eye);
    // false if it points behind the image plane.
    bool project_direction(const Vec3& d, float& px, float& py) const {
        const float z = dot(d, forward_);
        if (!(z > 0.0f)) return false;
        const float sx = dot(d, right_) / z, sy = dot(d, up_) / z;
        px = 0.5f * width_ * (1.0f + sx / (tan_half_ * aspect_));
        py = 0.5f * height_ * (1.0f - sy / tan_half_);
        return true;
    }

    // Pixel position of world point p; false if it is behind the eye.
    bool project(const Vec3& p, float& px, float& py) const {
        return project_direction(sub(p, position_), px, py);
    }

    // Screen-space (pixels, y down) derivative of the projection of p + h t at h = 0.
    void project_derivative(const Vec3& p, const Vec3& t, float& dx, float& dy) const {
        const Vec3 v = sub(p, position_);
        const float z = dot(v, forward_), tz = dot(t, forward_);
        const float dsx = (dot(t, right_) * z - dot(v, right_) * tz) / (z * z);
        const float dsy = (dot(t, up_) * z - dot(v, up_) * tz) / (z * z);
        dx = 0.5f * width_ * dsx / (tan_half_ * aspect_);
        dy = -0.5f * height_ * dsy / tan_half_;
    }

private:
    Vec3 position_, forward_{}, right_{}, up_{};
    float width_, height_, tan_half_ = 0.0f, aspect_ = 1.0f;
};

}  // namespace exemplar::render
