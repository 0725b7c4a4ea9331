#pragma once
// What the per-frame renderer shares with the still renderer (private to src/render).

#include <vector>

#include "exemplar/render/render.hpp"
#include "ray_scene.hpp"

namespace exemplar::render {

// The surface point seen through a pixel centre: mesh index (-1 = background), triangle and
// barycentric coordinates of its vertices 1 and 2.
struct CentreHit {
    int mesh = -1;
    unsigned primitive = 0;
    float u = 0.0f, v = 0.0f;
};

// Checks a scene before rendering (meshes, materials, camera); the message names scene.source.
Status check_scene(const Scene& scene);

// `render`, also returning the centre hit of every pixel (row-major) if `hits` is not null.
Result<RenderBuffers> render_with_hits(const Scene& scene, const RenderOptions& options,
                                       const RunContext& context, std::vector<CentreHit>* hits);

// The orientation buffer's value at a surface point (see RenderBuffers::orientation).
float screen_orientation(const CameraModel& camera, const Vec3& position, const Vec3& normal,
                         const Vec3& ray);

// The lines buffer from the centre-ray depth, object id and geometric (facet) normals.
Image geometry_lines(const Image& depth, const Image& object_id, const Image& facet_normal);

}  // namespace exemplar::render
