// Scene files: strict JSON parsing (every key known, every value checked) into a Scene of
// world-space triangle meshes. Built-in scenes are the JSON files of examples/render/, compiled in.

#include "exemplar/render/scene.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "builtin_scenes.hpp"
#include "exemplar/render/animation.hpp"
#include "vec_math.hpp"

namespace exemplar::render {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Walks the JSON tree, naming each value by its path (`lights[0].size`) in messages.
class Reader {
public:
    explicit Reader(std::string source) : source_(std::move(source)) {}

    Status error(const std::string& key, const std::string& problem) const {
        return invalid_argument(source_ + ": " + key + ": " + problem);
    }

    // Rejects keys of `object` not in `allowed`.
    Status check_keys(const json& object, const std::string& key,
                      const std::vector<std::string>& allowed) const {
        if (!object.is_object()) return error(key.empty() ? "scene" : key, "must be an object");
        for (const auto& item : object.items()) {
            if (std::find(allowed.begin(), allowed.end(), item.key()) == allowed.end()) {
                std::string list;
                for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
                return error(join(key, item.key()), "unknown key (expected one of: " + list + ")");
            }
        }
        return Status::ok();
    }

    static std::string join(const std::string& parent, const std::string& key) {
        return parent.empty() ? key : parent + "." + key;
    }

    Status number(const json& object, const std::string& parent, const std::string& name, float lo,
                  float hi, bool open_lo, float& out) const {
        if (!object.contains(name)) return Status::ok();
        const json& v = object.at(name);
        const std::string key = join(parent, name);
        if (!v.is_number()) return error(key, v.dump() + " is not a number");
        const double value = v.get<double>();
        if (!std::isfinite(value) || (open_lo ? value <= lo : value < lo) || value > hi) {
            std::ostringstream range;
            range << (open_lo ? "> " : ">= ") << lo << " and <= " << hi;
            return error(key, v.dump() + " is invalid (must be " + range.str() + ")");
        }
        out = static_cast<float>(value);
        return Status::ok();
    }

    Status vec3(const json& object, const std::string& parent, const std::string& name, float lo,
                float hi, Vec3& out) const {
        if (!object.contains(name)) return Status::ok();
        const json& v = object.at(name);
        const std::string key = join(parent, name);
        if (!v.is_array() || v.size() != 3) {
            return error(key, v.dump() + " is invalid (must be an array of 3 numbers)");
        }
        for (int i = 0; i < 3; ++i) {
            if (!v[i].is_number() || !std::isfinite(v[i].get<double>()) ||
                v[i].get<double>() < lo || v[i].get<double>() > hi) {
                std::ostringstream range;
                range << "must be 3 numbers in " << lo << ".." << hi;
                return error(key, v.dump() + " is invalid (" + range.str() + ")");
            }
            out[i] = v[i].get<float>();
        }
        return Status::ok();
    }

    Status string(const json& object, const std::string& parent, const std::string& name,
                  std::string& out) const {
        if (!object.contains(name)) return Status::ok();
        const json& v = object.at(name);
        if (!v.is_string()) return error(join(parent, name), v.dump() + " is not a string");
        out = v.get<std::string>();
        return Status::ok();
    }

    Status require(const json& object, const std::string& parent, const std::string& name) const {
        if (!object.contains(name)) return error(join(parent, name), "missing (required)");
        return Status::ok();
    }

private:
    std::string source_;
};

constexpr float kBig = 1e6f;
constexpr float kAngle = 100000.0f;  // degrees; keyframes may turn many times
constexpr long long kMaxFrame = 1000000;

Status parse_light(const Reader& r, const json& j, const std::string& k, AreaLight& light) {
    EXEMPLAR_RETURN_IF_ERROR(
        r.check_keys(j, k, {"center", "look_at", "width", "height", "roll_deg", "radiance"}));
    EXEMPLAR_RETURN_IF_ERROR(r.require(j, k, "center"));
    EXEMPLAR_RETURN_IF_ERROR(r.require(j, k, "look_at"));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "center", -kBig, kBig, light.center));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "look_at", -kBig, kBig, light.look_at));
    EXEMPLAR_RETURN_IF_ERROR(r.number(j, k, "width", 0.0f, kBig, true, light.width));
    EXEMPLAR_RETURN_IF_ERROR(r.number(j, k, "height", 0.0f, kBig, true, light.height));
    EXEMPLAR_RETURN_IF_ERROR(r.number(j, k, "roll_deg", -360.0f, 360.0f, false, light.roll_deg));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "radiance", 0.0f, kBig, light.radiance));
    if (length(sub(light.look_at, light.center)) <= 0.0f) {
        return r.error(k + ".look_at", "equals " + k + ".center");
    }
    return Status::ok();
}

Status parse_material(const Reader& r, const json& j, const std::string& k, Material& m) {
    EXEMPLAR_RETURN_IF_ERROR(r.check_keys(j, k, {"name", "diffuse", "specular", "exponent"}));
    EXEMPLAR_RETURN_IF_ERROR(r.require(j, k, "name"));
    EXEMPLAR_RETURN_IF_ERROR(r.string(j, k, "name", m.name));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "diffuse", 0.0f, 1.0f, m.diffuse));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "specular", 0.0f, 1.0f, m.specular));
    EXEMPLAR_RETURN_IF_ERROR(r.number(j, k, "exponent", 1.0f, 100000.0f, false, m.exponent));
    for (int c = 0; c < 3; ++c) {
        if (m.diffuse[c] + m.specular[c] > 1.0f) {
            return r.error(k, "diffuse + specular must be <= 1 per channel (energy conservation)");
        }
    }
    return Status::ok();
}

// Unit sphere at the origin: `rings` latitude bands, 2 * rings longitude segments, one vertex
// per pole and no duplicated seam, so that smooth normals are continuous everywhere.
void make_sphere(int rings, Mesh& mesh) {
    const int segments = 2 * rings;
    const float pi = 3.14159265358979f;
    mesh.positions.push_back({0.0f, 1.0f, 0.0f});
    for (int i = 1; i < rings; ++i) {
        const float theta = pi * static_cast<float>(i) / static_cast<float>(rings);
        for (int s = 0; s < segments; ++s) {
            const float phi = 2.0f * pi * static_cast<float>(s) / static_cast<float>(segments);
            mesh.positions.push_back({std::sin(theta) * std::cos(phi), std::cos(theta),
                                      -std::sin(theta) * std::sin(phi)});
        }
    }
    mesh.positions.push_back({0.0f, -1.0f, 0.0f});
    const auto ring_vertex = [&](int ring, int s) {
        return static_cast<std::uint32_t>(1 + (ring - 1) * segments + (s % segments));
    };
    const auto south = static_cast<std::uint32_t>(mesh.positions.size() - 1);
    for (int s = 0; s < segments; ++s) {
        mesh.triangles.push_back({0u, ring_vertex(1, s), ring_vertex(1, s + 1)});
        mesh.triangles.push_back({south, ring_vertex(rings - 1, s + 1), ring_vertex(rings - 1, s)});
    }
    for (int i = 1; i + 1 < rings; ++i) {
        for (int s = 0; s < segments; ++s) {
            mesh.triangles.push_back(
                {ring_vertex(i, s), ring_vertex(i + 1, s), ring_vertex(i + 1, s + 1)});
            mesh.triangles.push_back(
                {ring_vertex(i, s), ring_vertex(i + 1, s + 1), ring_vertex(i, s + 1)});
        }
    }
}

// Square [-1, 1]^2 in the xz plane, facing +y.
void make_quad(Mesh& mesh) {
    mesh.positions = {
        {-1.0f, 0.0f, -1.0f}, {-1.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 1.0f}, {1.0f, 0.0f, -1.0f}};
    mesh.triangles = {{0u, 1u, 2u}, {0u, 2u, 3u}};
}

struct ObjGroup {
    Mesh mesh;
    std::string material;  // OBJ material name, "" if none
    Material mtl;
};

// Loads an OBJ (and its MTL) as one mesh per material.
Status load_obj(const Reader& r, const std::string& key, const std::string& path,
                std::vector<ObjGroup>& groups) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return r.error(key, path + ": no such file");
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.mtl_search_path = fs::path(path).parent_path().string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string message = reader.Error();
        std::replace(message.begin(), message.end(), '\n', ' ');
        return r.error(key, path + ": cannot read OBJ (" + message + ")");
    }
    const auto& attrib = reader.GetAttrib();
    const auto& materials = reader.GetMaterials();
    std::map<int, std::size_t> group_of_material;
    std::vector<std::map<int, std::uint32_t>> remap;
    for (const auto& shape : reader.GetShapes()) {
        const auto& indices = shape.mesh.indices;
        for (std::size_t f = 0; f < shape.mesh.material_ids.size(); ++f) {
            const int material_id = shape.mesh.material_ids[f];
            auto [it, inserted] = group_of_material.emplace(material_id, groups.size());
            if (inserted) {
                ObjGroup group;
                if (material_id >= 0 && material_id < static_cast<int>(materials.size())) {
                    const auto& m = materials[static_cast<std::size_t>(material_id)];
                    group.material = m.name;
                    group.mtl.diffuse = {m.diffuse[0], m.diffuse[1], m.diffuse[2]};
                    group.mtl.specular = {m.specular[0], m.specular[1], m.specular[2]};
                    group.mtl.exponent = std::clamp(m.shininess, 1.0f, 100000.0f);
                }
                groups.push_back(std::move(group));
                remap.emplace_back();
            }
            ObjGroup& group = groups[it->second];
            std::array<std::uint32_t, 3> triangle{};
            for (int v = 0; v < 3; ++v) {
                const int vi = indices[3 * f + static_cast<std::size_t>(v)].vertex_index;
                auto [slot, fresh] = remap[it->second].emplace(
                    vi, static_cast<std::uint32_t>(group.mesh.positions.size()));
                if (fresh) {
                    const std::size_t base = 3 * static_cast<std::size_t>(vi);
                    group.mesh.positions.push_back({attrib.vertices[base],
                                                    attrib.vertices[base + 1],
                                                    attrib.vertices[base + 2]});
                }
                triangle[static_cast<std::size_t>(v)] = slot->second;
            }
            group.mesh.triangles.push_back(triangle);
        }
    }
    if (groups.empty()) return r.error(key, path + ": has no faces");
    return Status::ok();
}

Status parse_interpolation(const Reader& r, const json& j, const std::string& k,
                           Interpolation& out) {
    std::string name = "linear";
    EXEMPLAR_RETURN_IF_ERROR(r.string(j, k, "interpolation", name));
    if (name == "linear") {
        out = Interpolation::Linear;
    } else if (name == "smooth") {
        out = Interpolation::Smooth;
    } else {
        return r.error(Reader::join(k, "interpolation"),
                       "\"" + name + "\" is invalid (must be linear or smooth)");
    }
    return Status::ok();
}

// The `keyframes` array of `j`: each element is checked by `parse_key(element, key, frame)`;
// frames must increase strictly.
template <typename ParseKey>
Status parse_keyframes(const Reader& r, const json& j, const std::string& k, ParseKey parse_key) {
    if (!j.contains("keyframes")) return Status::ok();
    const json& keys = j.at("keyframes");
    const std::string key = Reader::join(k, "keyframes");
    if (!keys.is_array() || keys.empty()) return r.error(key, "must be a non-empty array");
    float previous = 0.0f;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const std::string ki = key + "[" + std::to_string(i) + "]";
        EXEMPLAR_RETURN_IF_ERROR(r.require(keys[i], ki, "frame"));
        float frame = 0.0f;
        EXEMPLAR_RETURN_IF_ERROR(r.number(keys[i], ki, "frame", -kBig, kBig, false, frame));
        if (i > 0 && !(frame > previous)) {
            return r.error(ki + ".frame", "must be larger than the previous keyframe's");
        }
        previous = frame;
        const Status status = parse_key(keys[i], ki, static_cast<double>(frame));
        if (!status.is_ok()) return status;
    }
    return Status::ok();
}

// An optional Vec3 of a keyframe, appended to `track` if present.
Status key_vec3(const Reader& r, const json& j, const std::string& k, const std::string& name,
                float lo, float hi, double frame, Track<Vec3>& track) {
    if (!j.contains(name)) return Status::ok();
    Vec3 value{};
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, name, lo, hi, value));
    track.keys.emplace_back(frame, value);
    return Status::ok();
}

// `scale`: a positive number or three.
Status parse_scale(const Reader& r, const json& j, const std::string& k, Vec3& out) {
    if (j.contains("scale") && j.at("scale").is_number()) {
        float s = 1.0f;
        EXEMPLAR_RETURN_IF_ERROR(r.number(j, k, "scale", 0.0f, kBig, true, s));
        out = {s, s, s};
        return Status::ok();
    }
    return r.vec3(j, k, "scale", 1e-6f, kBig, out);
}

Status check_camera(const Reader& r, const std::string& k, const Camera& camera) {
    const Vec3 forward = sub(camera.look_at, camera.position);
    if (length(forward) <= 0.0f) return r.error(k + ".look_at", "equals the camera position");
    if (length(cross(forward, camera.up)) <= 1e-6f * length(forward) * length(camera.up)) {
        return r.error(k + ".up", "is parallel to the view direction (or zero)");
    }
    return Status::ok();
}

Status parse_camera(const Reader& r, const json& j, CameraAnimation& animation) {
    const std::string k = "camera";
    Camera& camera = animation.camera;
    EXEMPLAR_RETURN_IF_ERROR(
        r.check_keys(j, k, {"position", "look_at", "up", "fov_deg", "keyframes", "interpolation"}));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "position", -kBig, kBig, camera.position));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "look_at", -kBig, kBig, camera.look_at));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "up", -kBig, kBig, camera.up));
    EXEMPLAR_RETURN_IF_ERROR(r.number(j, k, "fov_deg", 0.0f, 179.0f, true, camera.fov_deg));
    EXEMPLAR_RETURN_IF_ERROR(parse_interpolation(r, j, k, animation.interpolation));
    EXEMPLAR_RETURN_IF_ERROR(check_camera(r, k, camera));
    const auto camera_key = [&](const json& key, const std::string& ki, double frame) {
        EXEMPLAR_RETURN_IF_ERROR(
            r.check_keys(key, ki, {"frame", "position", "look_at", "up", "fov_deg"}));
        EXEMPLAR_RETURN_IF_ERROR(
            key_vec3(r, key, ki, "position", -kBig, kBig, frame, animation.position));
        EXEMPLAR_RETURN_IF_ERROR(
            key_vec3(r, key, ki, "look_at", -kBig, kBig, frame, animation.look_at));
        EXEMPLAR_RETURN_IF_ERROR(key_vec3(r, key, ki, "up", -kBig, kBig, frame, animation.up));
        if (key.contains("fov_deg")) {
            float fov = 0.0f;
            EXEMPLAR_RETURN_IF_ERROR(r.number(key, ki, "fov_deg", 0.0f, 179.0f, true, fov));
            animation.fov_deg.keys.emplace_back(frame, fov);
        }
        return Status::ok();
    };
    EXEMPLAR_RETURN_IF_ERROR(parse_keyframes(r, j, k, camera_key));
    // The camera at every key must be valid (in between, render_frame checks).
    if (j.contains("keyframes")) {
        const json& keys = j.at("keyframes");
        for (std::size_t i = 0; i < keys.size(); ++i) {
            EXEMPLAR_RETURN_IF_ERROR(check_camera(r, "camera.keyframes[" + std::to_string(i) + "]",
                                                  animation.at(keys[i].at("frame").get<double>())));
        }
    }
    return Status::ok();
}

Status parse_object(const Reader& r, const json& j, const std::string& k,
                    const std::string& base_dir, Animation& animation, int object_id) {
    EXEMPLAR_RETURN_IF_ERROR(
        r.check_keys(j, k,
                     {"name", "shape", "file", "material", "subdivisions", "normalize", "scale",
                      "rotate_deg", "translate", "keyframes", "interpolation", "turntable"}));
    EXEMPLAR_RETURN_IF_ERROR(r.require(j, k, "shape"));
    std::string name = "object" + std::to_string(object_id), shape, file, material;
    EXEMPLAR_RETURN_IF_ERROR(r.string(j, k, "name", name));
    EXEMPLAR_RETURN_IF_ERROR(r.string(j, k, "shape", shape));
    EXEMPLAR_RETURN_IF_ERROR(r.string(j, k, "file", file));
    EXEMPLAR_RETURN_IF_ERROR(r.string(j, k, "material", material));
    float subdivisions = 64.0f;
    EXEMPLAR_RETURN_IF_ERROR(r.number(j, k, "subdivisions", 2.0f, 1024.0f, false, subdivisions));
    bool normalize = false;
    if (j.contains("normalize")) {
        if (!j.at("normalize").is_boolean()) {
            return r.error(k + ".normalize", j.at("normalize").dump() + " is not true or false");
        }
        normalize = j.at("normalize").get<bool>();
    }
    ObjectAnimation object;
    object.name = name;
    Transform& transform = object.transform;
    EXEMPLAR_RETURN_IF_ERROR(parse_scale(r, j, k, transform.scale));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "rotate_deg", -kAngle, kAngle, transform.rotate_deg));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(j, k, "translate", -kBig, kBig, transform.translate));
    EXEMPLAR_RETURN_IF_ERROR(parse_interpolation(r, j, k, object.interpolation));
    const auto object_key = [&](const json& key, const std::string& ki, double frame) {
        EXEMPLAR_RETURN_IF_ERROR(
            r.check_keys(key, ki, {"frame", "translate", "rotate_deg", "scale"}));
        EXEMPLAR_RETURN_IF_ERROR(
            key_vec3(r, key, ki, "translate", -kBig, kBig, frame, object.translate));
        EXEMPLAR_RETURN_IF_ERROR(
            key_vec3(r, key, ki, "rotate_deg", -kAngle, kAngle, frame, object.rotate_deg));
        if (key.contains("scale")) {
            Vec3 value{};
            EXEMPLAR_RETURN_IF_ERROR(parse_scale(r, key, ki, value));
            object.scale.keys.emplace_back(frame, value);
        }
        return Status::ok();
    };
    EXEMPLAR_RETURN_IF_ERROR(parse_keyframes(r, j, k, object_key));
    if (j.contains("turntable")) {
        const std::string kt = k + ".turntable";
        const json& t = j.at("turntable");
        EXEMPLAR_RETURN_IF_ERROR(r.check_keys(t, kt, {"frames", "degrees"}));
        EXEMPLAR_RETURN_IF_ERROR(r.require(t, kt, "frames"));
        EXEMPLAR_RETURN_IF_ERROR(
            r.number(t, kt, "frames", 0.0f, kBig, true, object.turntable_frames));
        EXEMPLAR_RETURN_IF_ERROR(
            r.number(t, kt, "degrees", -kAngle, kAngle, false, object.turntable_degrees));
    }

    // Geometry in object space, one group per material.
    std::vector<ObjGroup> groups;
    if (shape == "sphere" || shape == "quad") {
        if (j.contains("file")) return r.error(k + ".file", "only for shape \"mesh\"");
        groups.emplace_back();
        if (shape == "sphere") {
            make_sphere(static_cast<int>(subdivisions), groups[0].mesh);
        } else {
            make_quad(groups[0].mesh);
        }
    } else if (shape == "mesh") {
        EXEMPLAR_RETURN_IF_ERROR(r.require(j, k, "file"));
        const fs::path path =
            fs::path(file).is_absolute() ? fs::path(file) : fs::path(base_dir) / file;
        EXEMPLAR_RETURN_IF_ERROR(load_obj(r, k + ".file", path.string(), groups));
    } else {
        return r.error(k + ".shape", "\"" + shape + "\" is invalid (must be sphere, quad or mesh)");
    }

    // normalize: bounding box to height 1, centred on the origin in x and z, bottom at y = 0.
    Vec3 lo{kBig, kBig, kBig}, hi{-kBig, -kBig, -kBig};
    for (const auto& g : groups) {
        for (const Vec3& p : g.mesh.positions) {
            for (int c = 0; c < 3; ++c) {
                lo[c] = std::min(lo[c], p[c]);
                hi[c] = std::max(hi[c], p[c]);
            }
        }
    }
    const float size = std::max(hi[1] - lo[1], 1e-12f);
    const Vec3 offset{-(lo[0] + hi[0]) / 2.0f, -lo[1], -(lo[2] + hi[2]) / 2.0f};

    for (auto& g : groups) {
        Mesh& mesh = g.mesh;
        if (normalize) {
            for (Vec3& p : mesh.positions) p = scale(add(p, offset), 1.0f / size);
        }
        mesh.name = g.material.empty() ? name : name + "/" + g.material;
        mesh.object_id = object_id;
        // The object's material, or the OBJ's own (added to the scene under "<name>/<mtl>").
        if (!material.empty()) {
            auto it = std::find_if(animation.materials.begin(), animation.materials.end(),
                                   [&](const Material& m) { return m.name == material; });
            if (it == animation.materials.end()) {
                return r.error(k + ".material", "\"" + material + "\" is not defined in materials");
            }
            mesh.material = static_cast<int>(it - animation.materials.begin());
        } else if (!g.material.empty()) {
            g.mtl.name = mesh.name;
            animation.materials.push_back(g.mtl);
            mesh.material = static_cast<int>(animation.materials.size() - 1);
        } else {
            return r.error(k + ".material", "missing (required unless the OBJ has materials)");
        }
        object.meshes.push_back(std::move(mesh));
    }
    animation.objects.push_back(std::move(object));
    return Status::ok();
}

}  // namespace

Result<Animation> parse_animation(const std::string& json_text, const std::string& source,
                                  const std::string& base_dir) {
    const Reader r(source);
    json root;
    try {
        root = json::parse(json_text);
    } catch (const json::parse_error& e) {
        std::string what = e.what();
        std::replace(what.begin(), what.end(), '\n', ' ');
        return invalid_argument(source + ": not valid JSON (" + what + ")");
    }
    EXEMPLAR_RETURN_IF_ERROR(r.check_keys(
        root, "", {"camera", "sky", "lights", "materials", "objects", "frames", "comment"}));
    Animation animation;
    animation.source = source;
    EXEMPLAR_RETURN_IF_ERROR(r.require(root, "", "camera"));
    EXEMPLAR_RETURN_IF_ERROR(parse_camera(r, root.at("camera"), animation.camera));
    EXEMPLAR_RETURN_IF_ERROR(r.vec3(root, "", "sky", 0.0f, kBig, animation.sky));
    if (root.contains("frames")) {
        const json& f = root.at("frames");
        if (!f.is_array() || f.size() != 2 || !f[0].is_number_integer() ||
            !f[1].is_number_integer() || f[0].get<long long>() > f[1].get<long long>() ||
            std::llabs(f[0].get<long long>()) > kMaxFrame ||
            std::llabs(f[1].get<long long>()) > kMaxFrame) {
            return r.error("frames", f.dump() +
                                         " is invalid (must be [FIRST, LAST], integers with "
                                         "FIRST <= LAST, |frame| <= 1000000)");
        }
        animation.frames = {f[0].get<int>(), f[1].get<int>()};
    }
    const auto array = [&](const std::string& key) -> Result<json> {
        if (!root.contains(key)) return json::array();
        if (!root.at(key).is_array()) return r.error(key, "must be an array");
        return root.at(key);
    };
    auto lights = array("lights");
    if (!lights.ok()) return lights.status();
    for (std::size_t i = 0; i < lights->size(); ++i) {
        AreaLight light;
        EXEMPLAR_RETURN_IF_ERROR(
            parse_light(r, (*lights)[i], "lights[" + std::to_string(i) + "]", light));
        animation.lights.push_back(light);
    }
    auto materials = array("materials");
    if (!materials.ok()) return materials.status();
    std::set<std::string> names;
    for (std::size_t i = 0; i < materials->size(); ++i) {
        Material m;
        const std::string key = "materials[" + std::to_string(i) + "]";
        EXEMPLAR_RETURN_IF_ERROR(parse_material(r, (*materials)[i], key, m));
        if (!names.insert(m.name).second) {
            return r.error(key + ".name", "\"" + m.name + "\" is defined twice");
        }
        animation.materials.push_back(m);
    }
    auto objects = array("objects");
    if (!objects.ok()) return objects.status();
    if (objects->empty()) return r.error("objects", "missing or empty (need at least one object)");
    for (std::size_t i = 0; i < objects->size(); ++i) {
        EXEMPLAR_RETURN_IF_ERROR(parse_object(r, (*objects)[i],
                                              "objects[" + std::to_string(i) + "]", base_dir,
                                              animation, static_cast<int>(i) + 1));
    }
    return animation;
}

Result<Scene> parse_scene(const std::string& json_text, const std::string& source,
                          const std::string& base_dir) {
    auto animation = parse_animation(json_text, source, base_dir);
    if (!animation.ok()) return animation.status();
    return animation->at(animation->frames ? animation->frames->first : 0);
}

Result<Animation> load_animation(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return io_error(path + ": no such file");
    std::ifstream in(path, std::ios::binary);
    if (!in) return io_error(path + ": cannot open");
    std::ostringstream text;
    text << in.rdbuf();
    if (!in.good() && !in.eof()) return io_error(path + ": cannot read");
    return parse_animation(text.str(), path, fs::path(path).parent_path().string());
}

Result<Scene> load_scene(const std::string& path) {
    auto animation = load_animation(path);
    if (!animation.ok()) return animation.status();
    return animation->at(animation->frames ? animation->frames->first : 0);
}

std::vector<std::string> builtin_scene_names() {
    std::vector<std::string> names;
    for (const auto& scene : detail::kBuiltinScenes) names.emplace_back(scene.name);
    return names;
}

Result<std::string> builtin_scene_json(const std::string& name) {
    for (const auto& scene : detail::kBuiltinScenes) {
        if (scene.name == name) return std::string(scene.json);
    }
    std::string list;
    for (const auto& n : builtin_scene_names()) list += (list.empty() ? "" : ", ") + n;
    return invalid_argument("scene \"" + name + "\" is not a built-in scene (built-in: " + list +
                            ")");
}

Result<Animation> builtin_animation(const std::string& name, const std::string& mesh_dir) {
    auto text = builtin_scene_json(name);
    if (!text.ok()) return text.status();
    return parse_animation(*text, "builtin:" + name,
                           mesh_dir.empty() ? std::string(detail::kBuiltinMeshDir) : mesh_dir);
}

Result<Scene> builtin_scene(const std::string& name, const std::string& mesh_dir) {
    auto animation = builtin_animation(name, mesh_dir);
    if (!animation.ok()) return animation.status();
    return animation->at(animation->frames ? animation->frames->first : 0);
}

}  // namespace exemplar::render
