#pragma once
// Embree scenes and ray queries of the renderer (private to src/render).

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>

#include "exemplar/render/scene.hpp"
#include "vec_math.hpp"

namespace exemplar::render {

// Embree device + scene, released on destruction. Errors are collected, never printed.
class EmbreeScene {
public:
    explicit EmbreeScene(const Scene& scene) {
        // One build thread: the BVH (and so tie-breaking between equal hits) never depends on
        // scheduling.
        device_ = rtcNewDevice("threads=1");
        if (device_ == nullptr) {
            error_ =
                "Embree: cannot create a device (" + code_name(rtcGetDeviceError(nullptr)) + ")";
            return;
        }
        rtcSetDeviceErrorFunction(
            device_,
            [](void* self, RTCError, const char* message) {
                auto* me = static_cast<EmbreeScene*>(self);
                const std::lock_guard<std::mutex> lock(me->mutex_);
                if (me->error_.empty()) me->error_ = std::string("Embree: ") + message;
            },
            this);
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
        for (const Mesh& mesh : scene.meshes) {
            RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* vertices = static_cast<float*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), mesh.positions.size()));
            auto* indices = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(unsigned), mesh.triangles.size()));
            if (vertices == nullptr || indices == nullptr) {
                rtcReleaseGeometry(geometry);
                break;
            }
            for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
                std::copy(mesh.positions[i].begin(), mesh.positions[i].end(), vertices + 3 * i);
            }
            for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
                std::copy(mesh.triangles[i].begin(), mesh.triangles[i].end(), indices + 3 * i);
            }
            rtcCommitGeometry(geometry);
            rtcAttachGeometry(scene_, geometry);  // IDs 0, 1, ... = mesh index
            rtcReleaseGeometry(geometry);
        }
        rtcCommitScene(scene_);
    }
    ~EmbreeScene() {
        if (scene_ != nullptr) rtcReleaseScene(scene_);
        if (device_ != nullptr) rtcReleaseDevice(device_);
    }
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    const std::string& error() const { return error_; }
    RTCScene handle() const { return scene_; }

private:
    static std::string code_name(RTCError code) { return "error " + std::to_string(code); }

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::mutex mutex_;
    std::string error_;
};

struct Hit {
    bool found = false;
    float t = 0.0f;
    Vec3 position{}, geometric_normal{}, shading_normal{};
    int mesh = -1;
    unsigned primitive = 0;    // triangle index in the mesh
    float u = 0.0f, v = 0.0f;  // barycentric coordinates of vertices 1 and 2
};

// The nearest hit of a ray (tfar = infinity) beyond `tnear`, with both normals facing the ray.
inline Hit intersect(const Scene& scene, RTCScene handle, const Vec3& origin, const Vec3& direction,
                     float tnear) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = origin[0];
    rh.ray.org_y = origin[1];
    rh.ray.org_z = origin[2];
    rh.ray.dir_x = direction[0];
    rh.ray.dir_y = direction[1];
    rh.ray.dir_z = direction[2];
    rh.ray.tnear = tnear;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(handle, &context, &rh);
    Hit hit;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.found = true;
    hit.t = rh.ray.tfar;
    hit.mesh = static_cast<int>(rh.hit.geomID);
    hit.primitive = rh.hit.primID;
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    const Mesh& mesh = scene.meshes[rh.hit.geomID];
    const auto& tri = mesh.triangles[rh.hit.primID];
    const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
    hit.position = add(origin, scale(direction, hit.t));
    hit.geometric_normal = normalize({rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
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
inline bool occluded(RTCScene handle, const Vec3& origin, const Vec3& direction, float tfar) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = origin[0];
    ray.org_y = origin[1];
    ray.org_z = origin[2];
    ray.dir_x = direction[0];
    ray.dir_y = direction[1];
    ray.dir_z = direction[2];
    ray.tnear = 0.0f;
    ray.tfar = tfar;
    ray.mask = 0xFFFFFFFFu;
    rtcOccluded1(handle, &context, &ray);
    return ray.tfar < 0.0f;
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
