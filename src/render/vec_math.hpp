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

}  // namespace exemplar::render
