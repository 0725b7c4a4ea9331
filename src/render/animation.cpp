// Keyframe interpolation and the scene at a frame.

#include "exemplar/render/animation.hpp"

#include "vec_math.hpp"

namespace exemplar::render {

namespace {

// acc + w * a, for the two value types of tracks.
float madd(float acc, float a, float w) {
    return acc + w * a;
}
Vec3 madd(const Vec3& acc, const Vec3& a, float w) {
    return {acc[0] + w * a[0], acc[1] + w * a[1], acc[2] + w * a[2]};
}

// The value of `track` at `frame`; `constant` if it has no keys. Smooth: cubic Hermite with
// Catmull-Rom tangents (p[i+1] - p[i-1]) / (t[i+1] - t[i-1]), zero at the first and last key.
template <typename T>
T evaluate(const Track<T>& track, const T& constant, double frame, Interpolation mode) {
    const auto& keys = track.keys;
    if (keys.empty()) return constant;
    if (frame <= keys.front().first) return keys.front().second;
    if (frame >= keys.back().first) return keys.back().second;
    std::size_t i = 0;
    while (keys[i + 1].first <= frame) ++i;
    const double t0 = keys[i].first, t1 = keys[i + 1].first;
    const T &p0 = keys[i].second, &p1 = keys[i + 1].second;
    const auto s = static_cast<float>((frame - t0) / (t1 - t0));
    T zero{};
    if (mode == Interpolation::Linear) return madd(madd(zero, p0, 1.0f - s), p1, s);
    // Tangents scaled to the interval [t0, t1].
    T m0{}, m1{};
    if (i > 0) {
        const auto c = static_cast<float>((t1 - t0) / (t1 - keys[i - 1].first));
        m0 = madd(madd(zero, p1, c), keys[i - 1].second, -c);
    }
    if (i + 2 < keys.size()) {
        const auto c = static_cast<float>((t1 - t0) / (keys[i + 2].first - t0));
        m1 = madd(madd(zero, keys[i + 2].second, c), p0, -c);
    }
    const float s2 = s * s, s3 = s2 * s;
    T out = madd(zero, p0, 2.0f * s3 - 3.0f * s2 + 1.0f);
    out = madd(out, m0, s3 - 2.0f * s2 + s);
    out = madd(out, p1, -2.0f * s3 + 3.0f * s2);
    return madd(out, m1, s3 - s2);
}

}  // namespace

Camera CameraAnimation::at(double frame) const {
    Camera c = camera;
    c.position = evaluate(position, camera.position, frame, interpolation);
    c.look_at = evaluate(look_at, camera.look_at, frame, interpolation);
    c.up = evaluate(up, camera.up, frame, interpolation);
    c.fov_deg = evaluate(fov_deg, camera.fov_deg, frame, interpolation);
    return c;
}

bool CameraAnimation::is_animated() const {
    return !position.keys.empty() || !look_at.keys.empty() || !up.keys.empty() ||
           !fov_deg.keys.empty();
}

Vec3 ObjectAnimation::to_world(const Vec3& p, double frame) const {
    const Vec3 s = evaluate(scale, transform.scale, frame, interpolation);
    const Vec3 r = evaluate(rotate_deg, transform.rotate_deg, frame, interpolation);
    const Vec3 t = evaluate(translate, transform.translate, frame, interpolation);
    Vec3 q = rotate_xyz({p[0] * s[0], p[1] * s[1], p[2] * s[2]}, r);
    if (turntable_frames > 0.0f) {
        const auto turn = static_cast<float>(static_cast<double>(turntable_degrees) * frame /
                                             static_cast<double>(turntable_frames));
        q = rotate_xyz(q, {0.0f, turn, 0.0f});
    }
    return add(q, t);
}

bool ObjectAnimation::is_animated() const {
    return !translate.keys.empty() || !rotate_deg.keys.empty() || !scale.keys.empty() ||
           turntable_frames > 0.0f;
}

bool Animation::is_animated() const {
    if (camera.is_animated()) return true;
    for (const ObjectAnimation& object : objects) {
        if (object.is_animated()) return true;
    }
    return false;
}

Scene Animation::at(double frame) const {
    Scene scene;
    scene.source = source;
    scene.camera = camera.at(frame);
    scene.lights = lights;
    scene.sky = sky;
    scene.materials = materials;
    for (const ObjectAnimation& object : objects) {
        for (const Mesh& local : object.meshes) {
            Mesh mesh = local;
            for (Vec3& p : mesh.positions) p = object.to_world(p, frame);
            compute_normals(mesh);
            scene.meshes.push_back(std::move(mesh));
        }
    }
    return scene;
}

}  // namespace exemplar::render
