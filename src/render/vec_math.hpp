#pragma once
// Small vector helpers on Vec3 for the renderer (private to src/render).

#include <cmath>

#include "exemplar/render/scene.hpp"

namespace exemplar::render {

inline Vec3 add(const Vec3& a, const Vec3& b) {
    return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 sub(const Vec3& a, const Vec3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 mul(const Vec3& a, const Vec3& b) {
    return {a[0] * b[0], a[1] * b[1], a[2] * b[2]};
}
inline Vec3 scale(const Vec3& a, float s) {
    return {a[0] * s, a[1] * s, a[2] * s};
}
inline float dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline float length(const Vec3& a) {
    return std::sqrt(dot(a, a));
}
inline Vec3 normalize(const Vec3& a) {
    const float len = length(a);
    return len > 0.0f ? scale(a, 1.0f / len) : a;
}
inline float max_component(const Vec3& a) {
    return std::fmax(a[0], std::fmax(a[1], a[2]));
}
inline float luminance(const Vec3& a) {
    return 0.2126f * a[0] + 0.7152f * a[1] + 0.0722f * a[2];
}

// Orthonormal basis around a unit vector n (Duff et al. 2017).
inline void basis(const Vec3& n, Vec3& t, Vec3& b) {
    const float sign = std::copysign(1.0f, n[2]);
    const float a = -1.0f / (sign + n[2]);
    const float c = n[0] * n[1] * a;
    t = {1.0f + sign * n[0] * n[0] * a, sign * c, -sign * n[0]};
    b = {c, sign + n[1] * n[1] * a, -n[1]};
}

// Area-weighted vertex normals.
inline void compute_normals(Mesh& mesh) {
    mesh.normals.assign(mesh.positions.size(), Vec3{0.0f, 0.0f, 0.0f});
    for (const auto& t : mesh.triangles) {
        const Vec3 n = cross(sub(mesh.positions[t[1]], mesh.positions[t[0]]),
                             sub(mesh.positions[t[2]], mesh.positions[t[0]]));
        for (std::uint32_t v : t) mesh.normals[v] = add(mesh.normals[v], n);
    }
    for (Vec3& n : mesh.normals) {
        const float len = length(n);
        n = len > 0.0f ? scale(n, 1.0f / len) : Vec3{0.0f, 1.0f, 0.0f};
    }
}

inline Vec3 rotate_xyz(Vec3 p, const Vec3& angles_deg) {
    const float to_rad = 3.14159265358979f / 180.0f;
    for (int axis = 0; axis < 3; ++axis) {
        const float a = angles_deg[axis] * to_rad;
        const float c = std::cos(a), s = std::sin(a);
        const int i = (axis + 1) % 3, j = (axis + 2) % 3;
        const float pi = p[i], pj = p[j];
        p[i] = c * pi - s * pj;
        p[j] = s * pi + c * pj;
    }
    return p;
}

}  // namespace exemplar::render
