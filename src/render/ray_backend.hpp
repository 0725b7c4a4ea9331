#pragma once
// The interface between the renderer and its ray-query plugin, libexemplar_render_embree.so
// (embree_plugin.cpp): the only code that uses Embree. Linking libembree3 costs every process
// about 3 MB resident before main() runs, so `exemplar` loads the plugin on the first render
// instead (plugin_loader.hpp); libexemplar.so and the Python module link it in. Both sides are
// compiled from this header by one build; kPlugin.abi_version rejects a plugin from another
// build.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "plugin_loader.hpp"

namespace exemplar::render::rays {

/// Raise abi_version whenever the types below change.
inline constexpr plugin::PluginSpec kPlugin{"libexemplar_render_embree.so",
                                            "exemplar_render_embree_entry", 1, "rendering"};

/// One triangle mesh: `vertex_count` xyz positions and `triangle_count` vertex index triples.
struct MeshArrays {
    const float* positions;
    std::size_t vertex_count;
    const std::uint32_t* triangles;
    std::size_t triangle_count;
};

/// The nearest hit of a ray as Embree reports it: distance, mesh (geometry ID = mesh index),
/// triangle, barycentric coordinates of vertices 1 and 2 and the unnormalized geometric normal.
struct RawHit {
    bool found = false;
    float t = 0.0f;
    unsigned mesh = 0, primitive = 0;
    float u = 0.0f, v = 0.0f;
    float normal[3] = {0.0f, 0.0f, 0.0f};
};

/// A built scene; queries are thread-safe.
class RayScene {
public:
    virtual ~RayScene() = default;
    /// Empty, or the first error of the device or the build (one line).
    virtual const std::string& error() const = 0;
    /// The nearest hit beyond `tnear` (tfar = infinity).
    virtual RawHit intersect(const float origin[3], const float direction[3],
                             float tnear) const = 0;
    /// True if anything lies on the ray between 0 and `tfar`.
    virtual bool occluded(const float origin[3], const float direction[3], float tfar) const = 0;
};

/// What the plugin's entry point returns; `abi_version` first (plugin_loader.hpp).
struct Entry {
    int abi_version;
    /// Builds the scene of `count` meshes (geometry IDs 0, 1, ... in order), never null.
    std::unique_ptr<RayScene> (*new_scene)(const MeshArrays* meshes, std::size_t count);
};

}  // namespace exemplar::render::rays
