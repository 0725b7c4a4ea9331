// Per-frame buffers of animations: orientation and lines (also for stills), and the exact motion
// vectors and occlusion masks of `render_frame`.

#include <algorithm>
#include <cmath>

#include "exemplar/core/parallel.hpp"
#include "exemplar/render/animation.hpp"
#include "render_internal.hpp"

namespace exemplar::render {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kCreaseCos = 0.70710678f;  // 45 degrees between neighbouring normals
constexpr float kDepthJump = 0.01f;        // smallest depth step of a discontinuity, relative
constexpr float kSlopeRatio = 4.0f;        // ... and its ratio to the neighbouring depth slopes
constexpr float kOcclusionSlack = 1e-3f;   // relative depth tolerance of the visibility test

// Position of a centre hit on `mesh` (the mesh at any frame: same topology, moved vertices).
Vec3 surface_point(const Mesh& mesh, const CentreHit& hit) {
    const auto& tri = mesh.triangles[hit.primitive];
    const float w = 1.0f - hit.u - hit.v;
    return add(scale(mesh.positions[tri[0]], w),
               add(scale(mesh.positions[tri[1]], hit.u), scale(mesh.positions[tri[2]], hit.v)));
}

// The motion of one pixel towards another frame.
struct Motion {
    float u = 0.0f, v = 0.0f;
    bool occluded = true;
};

// Where the point seen through pixel centre (cx, cy) lands in `other` (scene, BVH and camera of
// frame t±1), and whether it is visible there.
Motion motion_to(const Scene& other, const rays::RayScene& handle, const CameraModel& camera,
                 int width, int height, float cx, float cy, const CentreHit& hit,
                 const Vec3& sky_direction) {
    Motion m;
    float px = 0.0f, py = 0.0f;
    if (hit.mesh < 0) {
        // Sky: a point at infinity, visible if no geometry is in the way.
        if (!camera.project_direction(sky_direction, px, py)) return m;
        m.u = px - cx;
        m.v = py - cy;
        m.occluded = intersect(other, handle, camera.position(), sky_direction, 0.0f).found;
    } else {
        const Vec3 p = surface_point(other.meshes[static_cast<std::size_t>(hit.mesh)], hit);
        if (!camera.project(p, px, py)) return m;
        m.u = px - cx;
        m.v = py - cy;
        const Vec3 to_point = sub(p, camera.position());
        const float distance = length(to_point);
        const Hit first =
            intersect(other, handle, camera.position(), scale(to_point, 1.0f / distance), 0.0f);
        m.occluded = first.found && first.t < distance * (1.0f - kOcclusionSlack);
    }
    const auto w = static_cast<float>(width), h = static_cast<float>(height);
    if (!(px >= 0.0f && px <= w && py >= 0.0f && py <= h)) m.occluded = true;
    return m;
}

Image flow_image(int w, int h) {
    Image flow(w, h, 2);
    flow.set_channel_names({"u", "v"});
    return flow;
}

Image mask_image(int w, int h) {
    Image mask(w, h, 1);
    mask.set_channel_names({"occluded"});
    return mask;
}

}  // namespace

float screen_orientation(const CameraModel& camera, const Vec3& position, const Vec3& normal,
                         const Vec3& ray) {
    const Vec3 tangent = cross(normal, ray);
    if (!(length(tangent) >= 1e-6f)) return 0.0f;
    float dx = 0.0f, dy = 0.0f;
    camera.project_derivative(position, tangent, dx, dy);
    float angle = std::atan2(-dy, dx);  // counter-clockwise with y up on screen
    if (angle < 0.0f) angle += kPi;
    if (angle >= kPi) angle -= kPi;
    return angle;
}

Image geometry_lines(const Image& depth, const Image& object_id, const Image& facet_normal) {
    const int w = depth.width(), h = depth.height();
    Image lines(w, h, 1);
    lines.set_channel_names({"L"});
    const auto id = [&](int x, int y) { return object_id.at(x, y, 0); };
    const auto d = [&](int x, int y) { return depth.at(x, y, 0); };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (id(x, y) <= 0.0f) continue;  // background is never a line
            bool line = false;
            const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
            for (int k = 0; k < 4 && !line; ++k) {
                const int qx = x + dx[k], qy = y + dy[k];
                if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                if (id(qx, qy) != id(x, y)) {
                    // Silhouette between objects: the nearer side.
                    line = id(qx, qy) <= 0.0f || d(x, y) < d(qx, qy);
                    continue;
                }
                // Crease: facet normals apart by more than 45 degrees (smooth shading normals
                // would round a cube's edges away); the nearer side.
                const float* n = facet_normal.pixel(x, y);
                const float* m = facet_normal.pixel(qx, qy);
                if (n[0] * m[0] + n[1] * m[1] + n[2] * m[2] < kCreaseCos && d(x, y) <= d(qx, qy)) {
                    line = true;
                }
            }
            // Depth discontinuity within one object: a step to a deeper neighbour q that is
            // much larger than the depth slopes on either side of it (a slanted or curved
            // surface changes its slope gradually, even near a silhouette).
            for (int k = 0; k < 4 && !line; ++k) {
                const int qx = x + dx[k], qy = y + dy[k];
                if (qx < 0 || qy < 0 || qx >= w || qy >= h || id(qx, qy) != id(x, y)) continue;
                const float step = d(qx, qy) - d(x, y);
                if (!(step > kDepthJump * d(x, y))) continue;
                float slope = 0.0f;
                const int px = x - dx[k], py = y - dy[k], rx = qx + dx[k], ry = qy + dy[k];
                if (px >= 0 && py >= 0 && px < w && py < h && id(px, py) == id(x, y))
                    slope = std::max(slope, std::fabs(d(x, y) - d(px, py)));
                if (rx >= 0 && ry >= 0 && rx < w && ry < h && id(rx, ry) == id(x, y))
                    slope = std::max(slope, std::fabs(d(rx, ry) - d(qx, qy)));
                line = step > kSlopeRatio * slope;
            }
            lines.at(x, y, 0) = line ? 1.0f : 0.0f;
        }
    }
    return lines;
}

Result<RenderBuffers> render_frame(const Animation& animation, int frame,
                                   const RenderOptions& options, const RunContext& context) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    Scene scenes[3];  // frame - 1, frame, frame + 1
    for (int i = 0; i < 3; ++i) {
        scenes[i] = animation.at(static_cast<double>(frame + i - 1));
        scenes[i].source = animation.source + ": frame " + std::to_string(frame + i - 1);
        EXEMPLAR_RETURN_IF_ERROR(check_scene(scenes[i]));
    }
    std::vector<CentreHit> hits;
    auto rendered = render_with_hits(scenes[1], options, context, &hits);
    if (!rendered.ok()) return rendered.status();
    RenderBuffers out = std::move(rendered).value();

    auto previous = build_ray_scene(scenes[0]);
    if (!previous.ok()) return previous.status();
    auto next = build_ray_scene(scenes[2]);
    if (!next.ok()) return next.status();
    const int w = options.width, h = options.height;
    const CameraModel camera_previous(scenes[0].camera, w, h), camera(scenes[1].camera, w, h),
        camera_next(scenes[2].camera, w, h);
    out.forward_flow = flow_image(w, h);
    out.backward_flow = flow_image(w, h);
    out.occlusion = mask_image(w, h);
    out.disocclusion = mask_image(w, h);
    parallel_for(0, h, context.threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const CentreHit& hit = hits[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                                        static_cast<std::size_t>(x)];
            const float cx = static_cast<float>(x) + 0.5f, cy = static_cast<float>(y) + 0.5f;
            const Vec3 sky = camera.ray(cx, cy);
            const Motion forward =
                motion_to(scenes[2], **next, camera_next, w, h, cx, cy, hit, sky);
            const Motion backward =
                motion_to(scenes[0], **previous, camera_previous, w, h, cx, cy, hit, sky);
            out.forward_flow.at(x, y, 0) = forward.u;
            out.forward_flow.at(x, y, 1) = forward.v;
            out.backward_flow.at(x, y, 0) = backward.u;
            out.backward_flow.at(x, y, 1) = backward.v;
            out.occlusion.at(x, y, 0) = forward.occluded ? 1.0f : 0.0f;
            out.disocclusion.at(x, y, 0) = backward.occluded ? 1.0f : 0.0f;
        }
    });
    if (context.cancelled()) return cancelled();
    return out;
}

}  // namespace exemplar::render
