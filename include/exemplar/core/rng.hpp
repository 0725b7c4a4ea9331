#pragma once
/// \file
/// Counter-based random numbers. Every random decision in exemplar is a pure function of a
/// key such as (seed, level, iteration, pixel), so results never depend on thread count or
/// scheduling, and any single pixel's decisions can be replayed.

#include <cstdint>

namespace exemplar {

/// SplitMix64 finalizer: a strong 64-bit mixing function.
constexpr std::uint64_t mix64(std::uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/// Hashes a sequence of keys into one 64-bit value.
constexpr std::uint64_t hash_keys(std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0,
                                  std::uint64_t d = 0, std::uint64_t e = 0) {
    std::uint64_t h = mix64(a);
    h = mix64(h ^ b);
    h = mix64(h ^ c);
    h = mix64(h ^ d);
    return mix64(h ^ e);
}

/// A small generator whose whole stream is determined by its key. Cheap to construct per pixel.
class KeyedRng {
public:
    constexpr explicit KeyedRng(std::uint64_t key) : state_(key) {}
    KeyedRng(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0,
             std::uint64_t d = 0)
        : state_(hash_keys(seed, a, b, c, d)) {}

    /// Next 64 random bits.
    constexpr std::uint64_t next() {
        state_ += 0x9E3779B97F4A7C15ull;
        return mix64(state_);
    }
    /// Uniform float in [0, 1).
    constexpr float uniform() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }
    /// Uniform integer in [0, n) for n > 0.
    constexpr std::uint32_t below(std::uint32_t n) {
        return static_cast<std::uint32_t>(((next() >> 32) * static_cast<std::uint64_t>(n)) >> 32);
    }
    /// Uniform integer in [lo, hi] (inclusive), lo <= hi.
    constexpr int range(int lo, int hi) {
        return lo + static_cast<int>(below(static_cast<std::uint32_t>(hi - lo + 1)));
    }

private:
    std::uint64_t state_;
};

}  // namespace exemplar
