// A unidirectional path tracer with next-event estimation for the area lights, written for the
// light-path-expression buffers of StyLit (Fišer et al. 2016, §8.3.2; the paper used NVIDIA Iray).
// Each surface event is either diffuse (D) or glossy (S): a vertex picks one lobe of its
// material to continue the path, and light sampled at a vertex is split into its D and S parts,
// so every contribution has an exact event string and lands in the buffers whose expression it
// matches. Deviations from a production renderer: area lights are invisible to rays (only
// sampled directly, so there is no MIS), the sky is only reached by BSDF sampling, box pixel
// filter.

#include "exemplar/render/render.hpp"

#include <algorithm>
#include <cmath>

#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"
#include "ray_scene.hpp"
#include "render_internal.hpp"
#include "vec_math.hpp"

namespace exemplar::render {

namespace {

constexpr float kPi = 3.14159265358979f;

// Per-sample accumulators of the light buffers.
struct Sample {
    Vec3 fullgi{}, direct_diffuse{}, direct_specular{}, indirect_diffuse{}, diffuse_bounces{},
        diffuse_interreflection{};
    bool hit = false;
};

struct LightFrame {
    Vec3 corner, edge_u, edge_v, normal;
    float area;
    Vec3 radiance;
};

LightFrame light_frame(const AreaLight& light) {
    const Vec3 n = normalize(sub(light.look_at, light.center));
    Vec3 t, b;
    basis(n, t, b);
    // A deterministic in-plane frame: u horizontal where possible, then rolled.
    Vec3 u = cross({0.0f, 1.0f, 0.0f}, n);
    if (length(u) < 1e-4f) u = t;
    u = normalize(u);
    Vec3 v = cross(n, u);
    const float roll = light.roll_deg * kPi / 180.0f;
    const Vec3 ru = add(scale(u, std::cos(roll)), scale(v, std::sin(roll)));
    const Vec3 rv = cross(n, ru);
    const Vec3 eu = scale(ru, light.width), ev = scale(rv, light.height);
    return {sub(light.center, scale(add(eu, ev), 0.5f)),
            eu,
            ev,
            n,
            light.width * light.height,
            light.radiance};
}

class Tracer {
public:
    Tracer(const Scene& scene, const rays::RayScene& handle, const RenderOptions& options)
        : scene_(scene),
          handle_(handle),
          options_(options),
          camera_(scene.camera, options.width, options.height) {
        for (const AreaLight& light : scene.lights) lights_.push_back(light_frame(light));
        // Ray offsets relative to the scene's size.
        float extent = 0.0f;
        for (const Mesh& mesh : scene.meshes) {
            for (const Vec3& p : mesh.positions)
                extent = std::max(
                    extent, max_component({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])}));
        }
        epsilon_ = std::max(extent, 1.0f) * 2e-5f;
    }

    const CameraModel& camera() const { return camera_; }

    Hit intersect(const Vec3& origin, const Vec3& direction, float tnear) const {
        return render::intersect(scene_, handle_, origin, direction, tnear);
    }

    bool occluded(const Vec3& origin, const Vec3& direction, float tfar) const {
        return render::occluded(handle_, origin, direction, tfar);
    }

    // One path through pixel position (px, py).
    Sample trace(float px, float py, KeyedRng& rng) const {
        Sample s;
        Vec3 origin = scene_.camera.position;
        Vec3 direction = camera_.ray(px, py);
        Vec3 throughput{1.0f, 1.0f, 1.0f};
        bool first_diffuse = false, second_diffuse = false, all_diffuse = true;
        for (int vertex = 1; vertex <= options_.max_bounces; ++vertex) {
            const Hit hit = intersect(origin, direction, vertex == 1 ? 0.0f : epsilon_);
            if (!hit.found) {
                // The sky is a light reached from vertex - 1 surface events.
                if (vertex > 1)
                    add_light(s, mul(throughput, scene_.sky), vertex - 1, false, first_diffuse,
                              second_diffuse, all_diffuse);
                else
                    s.fullgi = add(s.fullgi, scene_.sky);  // LE
                break;
            }
            if (vertex == 1) s.hit = true;
            const Material& m = scene_.materials[static_cast<std::size_t>(
                scene_.meshes[static_cast<std::size_t>(hit.mesh)].material)];
            const Vec3 n = hit.shading_normal;
            const Vec3 wo = scale(direction, -1.0f);
            const float n_wo = dot(n, wo);
            if (n_wo <= 0.0f) break;  // shading normal facing away: no reflection
            const Vec3 offset_origin = add(hit.position, scale(hit.geometric_normal, epsilon_));

            // Next-event estimation: one point on every area light, split by lobe.
            for (const LightFrame& light : lights_) {
                const float u1 = rng.uniform(), u2 = rng.uniform();
                const Vec3 point =
                    add(light.corner, add(scale(light.edge_u, u1), scale(light.edge_v, u2)));
                const Vec3 to_light = sub(point, offset_origin);
                const float dist2 = dot(to_light, to_light);
                const float dist = std::sqrt(dist2);
                const Vec3 wi = scale(to_light, 1.0f / dist);
                const float cos_light = -dot(light.normal, wi);
                const float n_wi = dot(n, wi);
                if (cos_light <= 0.0f || n_wi <= 0.0f || dot(hit.geometric_normal, wi) <= 0.0f)
                    continue;
                if (occluded(offset_origin, wi, dist * (1.0f - 1e-4f))) continue;
                const float geometry = n_wi * cos_light * light.area / dist2;
                const Vec3 incoming = scale(mul(throughput, light.radiance), geometry);
                const Vec3 diffuse = scale(mul(incoming, m.diffuse), 1.0f / kPi);
                add_light(s, diffuse, vertex, true, vertex == 1 ? true : first_diffuse,
                          vertex == 2 ? true : second_diffuse, all_diffuse);
                if (max_component(m.specular) > 0.0f) {
                    const float spec = blinn_phong(n, wo, wi, m.exponent);
                    const Vec3 glossy = scale(mul(incoming, m.specular), spec);
                    add_light(s, glossy, vertex, true, vertex == 1 ? false : first_diffuse,
                              vertex == 2 ? false : second_diffuse, false);
                }
            }
            if (vertex == options_.max_bounces) break;

            // Continue the path through one lobe, chosen by reflectance.
            const float kd = luminance(m.diffuse), ks = luminance(m.specular);
            if (kd + ks <= 0.0f) break;
            const float p_specular = ks / (kd + ks);
            const bool specular = rng.uniform() < p_specular;
            Vec3 t, b;
            basis(n, t, b);
            const float u1 = rng.uniform(), u2 = rng.uniform();
            Vec3 wi;
            if (!specular) {
                const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
                wi = add(add(scale(t, r * std::cos(phi)), scale(b, r * std::sin(phi))),
                         scale(n, std::sqrt(std::max(0.0f, 1.0f - u1))));
                throughput = scale(mul(throughput, m.diffuse), 1.0f / (1.0f - p_specular));
            } else {
                const float cos_h = std::pow(u1, 1.0f / (m.exponent + 1.0f));
                const float sin_h = std::sqrt(std::max(0.0f, 1.0f - cos_h * cos_h));
                const float phi = 2.0f * kPi * u2;
                const Vec3 h =
                    add(add(scale(t, sin_h * std::cos(phi)), scale(b, sin_h * std::sin(phi))),
                        scale(n, cos_h));
                const float wo_h = dot(wo, h);
                if (wo_h <= 0.0f) break;
                wi = sub(scale(h, 2.0f * wo_h), wo);
                const float n_wi = dot(n, wi);
                if (n_wi <= 0.0f) break;
                // f cos / pdf with pdf = (e + 1) / (2 pi) cos_h^e / (4 wo.h).
                const float weight = blinn_phong(n, wo, wi, m.exponent) * n_wi * 4.0f * wo_h *
                                     2.0f * kPi /
                                     ((m.exponent + 1.0f) * std::pow(cos_h, m.exponent));
                throughput = scale(mul(throughput, m.specular), weight / p_specular);
            }
            if (dot(wi, hit.geometric_normal) <= 0.0f) break;
            if (vertex == 1) first_diffuse = !specular;
            if (vertex == 2) second_diffuse = !specular;
            all_diffuse = all_diffuse && !specular;

            // Russian roulette after three events.
            if (vertex >= 3) {
                const float keep = std::min(0.95f, max_component(throughput));
                if (rng.uniform() >= keep) break;
                throughput = scale(throughput, 1.0f / keep);
            }
            origin = offset_origin;
            direction = normalize(wi);
        }
        return s;
    }

private:
    // Normalized Blinn-Phong BRDF value (without the specular colour).
    static float blinn_phong(const Vec3& n, const Vec3& wo, const Vec3& wi, float exponent) {
        const Vec3 h = normalize(add(wo, wi));
        const float n_h = std::max(0.0f, dot(n, h));
        return (exponent + 8.0f) / (8.0f * kPi) * std::pow(n_h, exponent);
    }

    // Adds light that reached the eye after `events` surface events. `first_diffuse` and
    // `second_diffuse` describe the events nearest the eye, `all_diffuse` all of them;
    // `area_light` says whether the source is an area light (else the sky).
    static void add_light(Sample& s, const Vec3& c, int events, bool area_light, bool first_diffuse,
                          bool second_diffuse, bool all_diffuse) {
        s.fullgi = add(s.fullgi, c);
        if (events == 1 && area_light) {
            if (first_diffuse)
                s.direct_diffuse = add(s.direct_diffuse, c);
            else
                s.direct_specular = add(s.direct_specular, c);
        } else if (first_diffuse) {
            s.indirect_diffuse = add(s.indirect_diffuse, c);
        }
        if (all_diffuse && events <= 2) s.diffuse_bounces = add(s.diffuse_bounces, c);
        if (events >= 2 && first_diffuse && second_diffuse) {
            s.diffuse_interreflection = add(s.diffuse_interreflection, c);
        }
    }

    const Scene& scene_;
    const rays::RayScene& handle_;
    const RenderOptions& options_;
    std::vector<LightFrame> lights_;
    CameraModel camera_;
    float epsilon_ = 1e-4f;
};

Status check_range(const char* name, long long value, long long lo, long long hi) {
    if (value < lo || value > hi) {
        return invalid_argument(std::string(name) + ": " + std::to_string(value) +
                                " is invalid (must be " + std::to_string(lo) + ".." +
                                std::to_string(hi) + ")");
    }
    return Status::ok();
}

void put(Image& image, int x, int y, const Vec3& value) {
    float* p = image.pixel(x, y);
    p[0] = value[0];
    p[1] = value[1];
    p[2] = value[2];
}

}  // namespace

Status validate(const RenderOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(check_range("width", options.width, 1, 16384));
    EXEMPLAR_RETURN_IF_ERROR(check_range("height", options.height, 1, 16384));
    EXEMPLAR_RETURN_IF_ERROR(check_range("samples_per_pixel", options.samples_per_pixel, 1, 65536));
    EXEMPLAR_RETURN_IF_ERROR(check_range("max_bounces", options.max_bounces, 1, 64));
    return Status::ok();
}

std::vector<std::pair<std::string, const Image*>> RenderBuffers::layers() const {
    const std::vector<std::pair<std::string, const Image*>> all = {
        {"fullgi", &fullgi},
        {"direct_diffuse", &direct_diffuse},
        {"direct_specular", &direct_specular},
        {"indirect_diffuse", &indirect_diffuse},
        {"diffuse_bounces", &diffuse_bounces},
        {"diffuse_interreflection", &diffuse_interreflection},
        {"normal", &normal},
        {"depth", &depth},
        {"object_id", &object_id},
        {"material_id", &material_id},
        {"alpha", &alpha},
        {"orientation", &orientation},
        {"lines", &lines},
        {"forward_flow", &forward_flow},
        {"backward_flow", &backward_flow},
        {"occlusion", &occlusion},
        {"disocclusion", &disocclusion}};
    std::vector<std::pair<std::string, const Image*>> out;
    for (const auto& layer : all) {
        if (!layer.second->empty()) out.push_back(layer);
    }
    return out;
}

Status check_scene(const Scene& scene) {
    if (scene.meshes.empty()) return invalid_argument(scene.source + ": scene has no meshes");
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.material < 0 || mesh.material >= static_cast<int>(scene.materials.size()) ||
            mesh.normals.size() != mesh.positions.size()) {
            return invalid_argument(scene.source + ": mesh " + mesh.name +
                                    " has no valid material or normals");
        }
    }
    const Camera& c = scene.camera;
    const Vec3 forward = sub(c.look_at, c.position);
    if (!(length(forward) > 0.0f) ||
        !(length(cross(forward, c.up)) > 1e-6f * length(forward) * length(c.up))) {
        return invalid_argument(scene.source +
                                ": camera: look_at equals position or up is parallel to the view");
    }
    return Status::ok();
}

Result<RenderBuffers> render_with_hits(const Scene& scene, const RenderOptions& options,
                                       const RunContext& context, std::vector<CentreHit>* hits) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    EXEMPLAR_RETURN_IF_ERROR(check_scene(scene));
    auto ray_scene = build_ray_scene(scene);
    if (!ray_scene.ok()) return ray_scene.status();
    const Tracer tracer(scene, **ray_scene, options);
    const CameraModel& camera = tracer.camera();

    const int w = options.width, h = options.height;
    RenderBuffers out;
    for (Image* rgb : {&out.fullgi, &out.direct_diffuse, &out.direct_specular,
                       &out.indirect_diffuse, &out.diffuse_bounces, &out.diffuse_interreflection}) {
        *rgb = Image(w, h, 3);
    }
    out.normal = Image(w, h, 3);
    Image facet_normal(w, h, 3);  // geometric normal facing the eye: creases of the lines buffer
    out.normal.set_channel_names({"X", "Y", "Z"});
    out.depth = Image(w, h, 1);
    out.depth.set_channel_names({"Z"});
    out.object_id = Image(w, h, 1);
    out.object_id.set_channel_names({"id"});
    out.material_id = Image(w, h, 1);
    out.material_id.set_channel_names({"id"});
    out.alpha = Image(w, h, 1);
    out.alpha.set_channel_names({"A"});
    out.orientation = Image(w, h, 1);
    out.orientation.set_channel_names({"angle"});
    if (hits != nullptr) {
        hits->assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), CentreHit{});
    }

    const auto render_row = [&](int y) {
        if (context.cancelled()) return;
        for (int x = 0; x < w; ++x) {
            // Geometry buffers from the ray through the pixel centre.
            const Vec3 centre =
                camera.ray(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
            const Hit hit = tracer.intersect(camera.position(), centre, 0.0f);
            if (hit.found) {
                const Mesh& mesh = scene.meshes[static_cast<std::size_t>(hit.mesh)];
                put(out.normal, x, y, hit.shading_normal);
                put(facet_normal, x, y, hit.geometric_normal);
                out.depth.at(x, y, 0) = hit.t;
                out.object_id.at(x, y, 0) = static_cast<float>(mesh.object_id);
                out.material_id.at(x, y, 0) = static_cast<float>(mesh.material + 1);
                out.orientation.at(x, y, 0) =
                    screen_orientation(camera, hit.position, hit.shading_normal, centre);
                if (hits != nullptr) {
                    (*hits)[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                            static_cast<std::size_t>(x)] = {hit.mesh, hit.primitive, hit.u, hit.v};
                }
            }
            // Light buffers: the mean of samples_per_pixel paths, keyed by (seed, pixel, sample).
            Sample sum;
            int hit_count = 0;
            const auto pixel = static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(w) +
                               static_cast<std::uint64_t>(x);
            for (int i = 0; i < options.samples_per_pixel; ++i) {
                KeyedRng rng(options.seed, pixel, static_cast<std::uint64_t>(i));
                const float jx = rng.uniform(), jy = rng.uniform();
                const Sample s =
                    tracer.trace(static_cast<float>(x) + jx, static_cast<float>(y) + jy, rng);
                sum.fullgi = add(sum.fullgi, s.fullgi);
                sum.direct_diffuse = add(sum.direct_diffuse, s.direct_diffuse);
                sum.direct_specular = add(sum.direct_specular, s.direct_specular);
                sum.indirect_diffuse = add(sum.indirect_diffuse, s.indirect_diffuse);
                sum.diffuse_bounces = add(sum.diffuse_bounces, s.diffuse_bounces);
                sum.diffuse_interreflection =
                    add(sum.diffuse_interreflection, s.diffuse_interreflection);
                hit_count += s.hit ? 1 : 0;
            }
            const float inv = 1.0f / static_cast<float>(options.samples_per_pixel);
            put(out.fullgi, x, y, scale(sum.fullgi, inv));
            put(out.direct_diffuse, x, y, scale(sum.direct_diffuse, inv));
            put(out.direct_specular, x, y, scale(sum.direct_specular, inv));
            put(out.indirect_diffuse, x, y, scale(sum.indirect_diffuse, inv));
            put(out.diffuse_bounces, x, y, scale(sum.diffuse_bounces, inv));
            put(out.diffuse_interreflection, x, y, scale(sum.diffuse_interreflection, inv));
            out.alpha.at(x, y, 0) = static_cast<float>(hit_count) * inv;
        }
    };

    // Rows in batches, so that progress and cancellation are handled on the caller's thread.
    const int batch = std::max(8, 4 * resolve_threads(context.threads));
    for (int y0 = 0; y0 < h; y0 += batch) {
        if (context.cancelled()) return cancelled();
        const int y1 = std::min(h, y0 + batch);
        parallel_for(y0, y1, context.threads, render_row);
        ProgressEvent event;
        event.stage = "render";
        event.fraction = static_cast<double>(y1) / static_cast<double>(h);
        context.report(event);
    }
    if (context.cancelled()) return cancelled();
    out.lines = geometry_lines(out.depth, out.object_id, facet_normal);
    return out;
}

Result<RenderBuffers> render(const Scene& scene, const RenderOptions& options,
                             const RunContext& context) {
    return render_with_hits(scene, options, context, nullptr);
}

}  // namespace exemplar::render
