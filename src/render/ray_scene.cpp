// The renderer's ray-query scene from the Embree backend: linked in (libexemplar.so, the Python
// module) or loaded from the plugin on first use (the `exemplar` command).

#include "ray_scene.hpp"

// Defined by embree_plugin.cpp where that is linked in; null in the `exemplar` executable.
extern "C" const exemplar::render::rays::Entry* exemplar_render_embree_entry()
    __attribute__((weak));

namespace exemplar::render {

namespace {

Result<const rays::Entry*> backend() {
    return plugin::linked_or_loaded(exemplar_render_embree_entry, rays::kPlugin);
}

}  // namespace

Result<std::unique_ptr<rays::RayScene>> build_ray_scene(const Scene& scene) {
    auto entry = backend();
    if (!entry.ok()) return entry.status();
    std::vector<rays::MeshArrays> meshes;
    meshes.reserve(scene.meshes.size());
    for (const Mesh& mesh : scene.meshes) {
        meshes.push_back(
            {mesh.positions.empty() ? nullptr : mesh.positions[0].data(), mesh.positions.size(),
             mesh.triangles.empty() ? nullptr : mesh.triangles[0].data(), mesh.triangles.size()});
    }
    std::unique_ptr<rays::RayScene> built = (*entry)->new_scene(meshes.data(), meshes.size());
    if (!built->error().empty()) return Status(ErrorCode::Internal, built->error());
    return built;
}

}  // namespace exemplar::render
