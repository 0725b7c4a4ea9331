#pragma once
/// \file
/// Fitting smooth cubic Bézier paths to raw pen samples: Schneider's least-squares algorithm
/// ("An algorithm for automatically fitting digitized curves", Graphics Gems, 1990). ShipShape
/// (§7.2, §7.4.1) relies on the host application for this step; we do it ourselves.

#include <vector>

#include "exemplar/sketch/path.hpp"

namespace exemplar::sketch {

/// Options of `fit_path`.
struct FitOptions {
    /// Largest allowed distance between a sample and the fitted curve, in drawing units.
    /// Default 1.0; must be > 0. Larger values give fewer, smoother segments.
    double tolerance = 1.0;
    /// Samples where the polyline turns by more than this angle (radians, measured between the
    /// chords to the neighbours ~`corner_window` units away) start a new piece with its own
    /// tangents, so sharp corners stay sharp. Default 1.2 rad (~69°); π disables.
    double corner_angle_rad = 1.2;
    /// Distance along the polyline over which the turn at a sample is measured. Default 4.
    double corner_window = 4.0;
};

/// A smooth path through the samples. Consecutive duplicate samples are dropped. Fewer than two
/// distinct samples: an empty path. A polyline whose first and last samples coincide (within
/// the tolerance) gives a closed path.
Path fit_path(const std::vector<Vec2>& samples, const FitOptions& options = {});

/// A stroke drawn as pen samples (a path of 3 or more straight pieces, as SVG polylines store
/// them) refitted by `fit_path` within `tolerance` drawing units (> 0); it stays closed if it
/// was. Any other path (one with curves, or fewer pieces) is returned unchanged, and so is a
/// stroke the fit cannot represent (fewer than two distinct samples).
Path refit_polyline(const Path& path, double tolerance);

}  // namespace exemplar::sketch
