// The renderer's ray queries with Embree 3, built as the plugin libexemplar_render_embree.so
// (ray_backend.hpp says why). It links no exemplar library.

#include <embree3/rtcore.h>

#include <algorithm>
#include <limits>
#include <mutex>

#include "ray_backend.hpp"

namespace exemplar::render::rays {

namespace {

// Embree device + scene, released on destruction. Errors are collected, never printed.
class EmbreeScene final : public RayScene {
public:
    EmbreeScene(const MeshArrays* meshes, std::size_t count) {
        // One build thread: the BVH (and so tie-breaking between equal hits) never depends on
        // scheduling.
        device_ = rtcNewDevice("threads=1");
        if (device_ == nullptr) {
            error_ = "Embree: cannot create a device (error " +
                     std::to_string(rtcGetDeviceError(nullptr)) + ")";
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
        for (std::size_t m = 0; m < count; ++m) {
            const MeshArrays& mesh = meshes[m];
            RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* vertices = static_cast<float*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), mesh.vertex_count));
            auto* indices = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(unsigned), mesh.triangle_count));
            if (vertices == nullptr || indices == nullptr) {
                rtcReleaseGeometry(geometry);
                break;
            }
            std::copy_n(mesh.positions, 3 * mesh.vertex_count, vertices);
            std::copy_n(mesh.triangles, 3 * mesh.triangle_count, indices);
            rtcCommitGeometry(geometry);
            rtcAttachGeometry(scene_, geometry);  // IDs 0, 1, ... = mesh index
            rtcReleaseGeometry(geometry);
        }
        rtcCommitScene(scene_);
    }
    ~EmbreeScene() override {
        if (scene_ != nullptr) rtcReleaseScene(scene_);
        if (device_ != nullptr) rtcReleaseDevice(device_);
    }
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    const std::string& error() const override { return error_; }

    RawHit intersect(const float origin[3], const float direction[3], float tnear) const override {
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
        rtcIntersect1(scene_, &context, &rh);
        RawHit hit;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
        hit.found = true;
        hit.t = rh.ray.tfar;
        hit.mesh = rh.hit.geomID;
        hit.primitive = rh.hit.primID;
        hit.u = rh.hit.u;
        hit.v = rh.hit.v;
        hit.normal[0] = rh.hit.Ng_x;
        hit.normal[1] = rh.hit.Ng_y;
        hit.normal[2] = rh.hit.Ng_z;
        return hit;
    }

    bool occluded(const float origin[3], const float direction[3], float tfar) const override {
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
        rtcOccluded1(scene_, &context, &ray);
        return ray.tfar < 0.0f;
    }

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::mutex mutex_;
    std::string error_;
};

std::unique_ptr<RayScene> new_scene(const MeshArrays* meshes, std::size_t count) {
    return std::make_unique<EmbreeScene>(meshes, count);
}

constexpr Entry kEntry{kPlugin.abi_version, &new_scene};

}  // namespace

}  // namespace exemplar::render::rays

// The plugin's one exported symbol (rays::kPlugin); also linked into libexemplar.so and
// the Python module, where the renderer calls it directly.
extern "C" __attribute__((visibility("default"))) const exemplar::render::rays::Entry*
exemplar_render_embree_entry() {
    return &exemplar::render::rays::kEntry;
}
