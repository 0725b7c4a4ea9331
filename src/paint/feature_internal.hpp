#pragma once
// Pieces shared by the line-feature brush's files (active_contour.cpp, feature_graph.cpp,
// feature_brush.cpp): equal-interval path sampling, tangents, bilinear lookups, the walk builder.

#include <cstdint>
#include <span>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/paint/feature_brush.hpp"

namespace exemplar::paint {

/// Samples a polyline every `spacing` of arc length from its first point, point by point: the
/// samples of a path are those of any prefix of it followed by the rest, so a growing stroke
/// keeps its samples (the same floating-point operations happen in the same order).
class PathSampler {
public:
    explicit PathSampler(double spacing) : spacing_(spacing) {}
    /// Appends the samples that `point` adds to `out`.
    void add(StrokePoint point, std::vector<StrokePoint>& out);

private:
    double spacing_;
    bool started_ = false;
    StrokePoint last_;
    double until_next_ = 0.0;  // arc length from last_ to the next sample
};

/// InvalidArgument naming the first point outside [0, width] × [0, height] of `palette`.
Status check_inside(const Image& palette, std::span<const StrokePoint> points);

/// All samples of a polyline.
std::vector<StrokePoint> sample_path(std::span<const StrokePoint> points, double spacing);

/// Half-width in samples of the window a sample's tangent is measured over: a quarter of the
/// brush width, at least one sample.
int tangent_reach(float width_px, float spacing_px);

/// Sets frames[k] (position and unit tangent along the path) for k in [first, points.size()):
/// the tangent is the direction from sample k − reach to k + reach (clamped to the ends), or the
/// previous sample's where that is zero. `frames` is resized to points.size().
void update_frames(std::span<const StrokePoint> points, int reach, int first,
                   std::vector<PathSample>& frames);

/// Bilinear lookup of all channels of `image` at (x, y) in its pixel coordinates (pixel centres
/// at +0.5), clamped at the borders.
void sample_bilinear(const Image& image, float x, float y, float* out);

/// Builds a walk through a feature's graph as far as asked, remembering where it stopped, so
/// that a growing stroke extends its walk (Randomized and Looping) without changing it.
class WalkBuilder {
public:
    WalkBuilder(const LineFeature& feature, WalkMode mode, std::uint64_t key);
    /// Makes `walk` at least `length` long: appends for the prefix-stable modes, recomputes the
    /// whole walk (exactly `length`) for DynamicProgramming. Randomized walks may overshoot.
    void extend(std::vector<int>& walk, int length);

private:
    void extend_randomized(std::vector<int>& walk, int length);
    void extend_looping(std::vector<int>& walk, int length) const;
    std::vector<int> cheapest_walk(int length) const;
    // Dijkstra's cheapest route from `from` to `goal` (excluding `from`, ending at `goal`);
    // if `avoid_recent`, without the jumps whose shift repeats a recent jump's.
    std::vector<int> cheapest_route(int from, int goal, bool avoid_recent) const;
    bool recent_shift(int shift) const;

    const LineFeature* feature_;
    WalkMode mode_;
    std::uint64_t key_;
    std::uint64_t segment_ = 0;
    int loop_from_ = 0, loop_to_ = 0;  // Looping: the jump loop_from_ → loop_to_
    std::vector<int> recent_shifts_;   // Randomized: shifts i − (j − 1) of the last jumps
    int shift_tolerance_ = 1;          // in samples
};

}  // namespace exemplar::paint
