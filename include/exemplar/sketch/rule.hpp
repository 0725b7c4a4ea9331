#pragma once
/// \file
/// The beautification rules of ShipShape (Fišer et al. 2016, §7.3, Fig. 7.3) as self-contained
/// black boxes. A rule takes a candidate (the path being beautified, with the properties earlier
/// rules fixed) and the resolved drawing, and returns zero or more modified candidates, each with
/// a likelihood in [0, 1] at or above the rule's threshold, the relation it enforces and the
/// properties it fixes. Rules never depend on each other; the search (beautify.hpp) chains them.
///
/// Distances compared with thresholds are in view-space pixels (§7.3.2): drawing units times
/// `RuleContext::pixels_per_unit`.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "exemplar/sketch/path.hpp"

namespace exemplar::sketch {

/// What a path is known to be.
enum class ShapeKind { Curve, Line, Arc, Circle };
const char* to_string(ShapeKind kind);

/// Circle or arc parameters (y-down radians; `sweep_rad` signed, ±2π for a circle).
struct ArcGeometry {
    Vec2 center;
    double radius = 0.0;
    double start_angle_rad = 0.0;
    double sweep_rad = 0.0;
};

/// Properties of a candidate that rules have fixed and later rules must keep.
struct FixedProperties {
    bool start = false;      ///< Start point position.
    bool end = false;        ///< End point position.
    bool direction = false;  ///< Orientation (chord direction of a line, rotation of a path).
    bool length = false;     ///< Length of a line.
    bool center = false;     ///< Centre of an arc or circle.
    bool shape = false;      ///< Shape class decided (line, arc, a copy of a path, an offset).
    bool transform = false;  ///< The copy's transformation has been adjusted.
};

/// One enforced geometric relation.
struct Relation {
    std::string rule;          ///< Rule name, e.g. "parallel".
    std::string key;           ///< Unique per application, e.g. "parallel:3" (used for pruning).
    std::vector<int> strokes;  ///< Strokes of the drawing involved (indices in drawing order).
    double likelihood = 0.0;
    std::string detail;  ///< Human-readable, e.g. "parallel to stroke 3 (was 2.1° off)".
};

/// A snapped endpoint: what it was snapped to.
struct Attachment {
    int path = -1;         ///< Index in `RuleContext::paths`.
    Vec2 point;            ///< The snap point.
    Vec2 tangent;          ///< Unit tangent of the target path at the snap point.
    bool endpoint = true;  ///< Snapped to the target's endpoint (else to an inner point).
};

/// A candidate that is a transformed copy of a resolved path (path identity, §7.3.4).
struct Instance {
    int template_path = -1;  ///< Index in `RuleContext::paths` of the template (original).
    Affine from_template;    ///< Template → this candidate.
    int relative_to = -1;    ///< The copy (index in `paths`) it was last compared with.
    Affine relative;         ///< That copy → this candidate (becomes the step transform).
    bool reversed = false;   ///< Traversed in the opposite direction to the template.
};

/// A reflection axis: a point on it and its unit direction.
struct Axis {
    Vec2 point;
    Vec2 direction;
    int uses = 1;  ///< How many accepted paths used it.
};

/// The state of a path during the search: its geometry and what is known and fixed about it.
struct Candidate {
    Path path;
    ShapeKind kind = ShapeKind::Curve;
    ArcGeometry arc;  ///< When kind is Arc or Circle.
    FixedProperties fixed;
    std::vector<Relation> relations;    ///< Applied, in order.
    std::vector<std::string> declined;  ///< Rules whose suggestion was declined on this branch.
    std::optional<Attachment> start_attachment, end_attachment;
    std::optional<Instance> instance;
    std::optional<Axis> axis;             ///< Reflection axis used, if any.
    std::optional<Vec2> rotation_center;  ///< Snapped centre of rotation, if any.
};

/// A path of the resolved drawing with its precomputed samples (§7.3.3).
struct ResolvedPath {
    Path path;
    ShapeKind kind = ShapeKind::Curve;
    ArcGeometry arc;
    int stroke = -1;  ///< Stroke (drawing order) this path belongs to.
    int segment = 0;  ///< Segment within a multi-segment stroke.
    /// Used by the rules on geometry (snapping, lines, arcs, offsets): every segment.
    bool geometric = true;
    /// Used by the rules on copies (identity, transformation, reflection, step): single-segment
    /// strokes and whole multi-segment strokes.
    bool shape = true;
    std::vector<Vec2> dense;       ///< Flattened every ~2 view px (snapping, offsets).
    std::vector<Vec2> simplified;  ///< `dense` after Ramer–Douglas–Peucker (ε = 4 view px).
    std::vector<Vec2> match;       ///< `match_samples` points equally spaced (path matching).
    double length = 0.0;
    Box box;                     ///< Bounding box of `dense` (quick rejection in the rules).
    int template_path = -1;      ///< Its template (itself if it is an original).
    Affine from_template;        ///< Template → this.
    std::optional<Affine> step;  ///< Step transform (relative to the copy it snapped to).
    int instances = 1;           ///< On a template: number of copies including itself.
};

/// Parameters of one rule: the tolerance at which its likelihood falls to 0 (units per rule), and
/// the threshold below which it proposes nothing.
struct RuleParams {
    double tolerance = 0.0;
    double threshold = 0.0;
};

/// Options of the beautifier. Paper values are marked (§); the rest are ours (docs/sketch.md).
struct BeautifyOptions {
    int max_suggestions = 10;      ///< § 7.3: N unique suggestions (1..100).
    int segment_suggestions = 3;   ///< § 7.4.2: suggestions per segment of a multi-segment stroke.
    int intermediate_states = 10;  ///< § 7.4.2: N_IS states kept between segments.
    int max_expansions = 200;      ///< Search nodes expanded per path at most (determinism, speed).
    double rdp_epsilon_px = 4.0;   ///< § 7.3.3: Ramer–Douglas–Peucker tolerance.
    int match_samples = 32;        ///< Samples per path for matching (§ 7.3.4 "N"; not given).
    double corner_step_px = 2.0;   ///< § 7.4.1: sampling step of corner detection.
    double corner_angle_rad = 1.05;  ///< Smallest turn (over ±2 samples) that is a corner (60°).
    double hook_fraction = 0.15;     ///< § 7.4.1: shorter segments than this × neighbour dropped.
    /// End segments are dropped as hooks only up to this length (view px); longer short ones are
    /// merged into their neighbour instead, so no drawn part is lost (ours).
    double hook_max_px = 8.0;
    double center_search_px = 30.0;   ///< § 7.3.1: D, arc-centre search radius.
    double offset_percentile = 25.0;  ///< § 7.3.6: n, percentiles 50 ± n compared.
    double duplicate_px = 0.5;        ///< Suggestions closer than this are the same.
    /// How far (Fréchet distance, view px) a path may move to become a line, an arc or a copy
    /// of another path: the likelihood is also at most 1 − distance / this. Ours; the paper
    /// only uses relative measures, which let long strokes move far.
    double shape_tolerance_px = 12.0;

    RuleParams line{0.08, 0.5};           ///< 1 − chord/length at which L = 0.
    RuleParams arc{0.08, 0.5};            ///< Fréchet distance / length at which L = 0.
    RuleParams endpoint{10.0, 0.2};       ///< Snap distance in view px.
    RuleParams tangent{0.22, 0.3};        ///< Angle in rad (12.6°).
    RuleParams parallel{0.14, 0.3};       ///< Angle in rad (8°).
    RuleParams perpendicular{0.14, 0.3};  ///< Angle in rad (8°).
    RuleParams equal_length{0.1, 0.3};    ///< |1 − length ratio|.
    RuleParams arc_center{30.0, 0.2};     ///< Unused tolerance (D and its adaptive growth rule).
    RuleParams identity{0.1, 0.4};        ///< Fréchet distance / length after alignment.
    RuleParams reflection{0.1, 0.4};      ///< Fréchet distance / length to the exact mirror.
    RuleParams transform{1.0, 0.3};       ///< Scales the snap tolerances below.
    RuleParams step{0.2, 0.4};            ///< Distance to the stepped copy / max(step, length).
    RuleParams offset{0.35, 0.4};         ///< Interquartile spread / median offset.
    double rotation_snap_rad = 0.09;      ///< Rotation snapping tolerance (5°).
    double scale_snap = 0.06;             ///< Scale snapping tolerance (relative).
    double translation_snap_px = 8.0;     ///< Translation component snapping tolerance.
    double axis_snap_px = 10.0;           ///< Reflection-axis offset snapping tolerance.
    double axis_snap_rad = 0.07;          ///< Reflection-axis angle snapping tolerance (4°).
};

/// What the rules see: the resolved paths and the drawing-wide annotations.
struct RuleContext {
    std::vector<const ResolvedPath*> paths;
    std::vector<Axis> axes;              ///< Reflection axes used so far.
    std::vector<Vec2> rotation_centers;  ///< Centres of rotation used so far.
    double pixels_per_unit = 1.0;
    int current_stroke =
        -1;  ///< The stroke being beautified (its earlier segments are in `paths`).
    const BeautifyOptions* options = nullptr;

    double px(double units) const { return units * pixels_per_unit; }
    double units(double px_value) const { return px_value / pixels_per_unit; }
};

/// A rule's proposal.
struct RuleOutput {
    Candidate candidate;  ///< With the new relation appended and its properties fixed.
    double likelihood = 0.0;
};

/// A geometric rule (one per file in src/sketch/rules/).
class Rule {
public:
    virtual ~Rule() = default;
    /// Short name used in reports and relation keys ("parallel").
    virtual const char* name() const = 0;
    /// True if the rule may apply again on a branch after it applied (endpoint snapping: once per
    /// endpoint; each application fixes what it changed, so the chain ends).
    virtual bool repeatable() const { return false; }
    /// The rule's threshold: proposals below it are not returned.
    virtual double threshold(const BeautifyOptions& options) const = 0;
    /// Modified candidates, most likely first (deterministic order), each ≥ threshold.
    virtual std::vector<RuleOutput> apply(const Candidate& input,
                                          const RuleContext& context) const = 0;
};

/// All rules of Fig. 7.3 in a fixed order: line, arc, endpoint, tangent, parallel,
/// perpendicular, equal-length, arc-center, identity, transform, reflection, step, offset.
std::vector<std::unique_ptr<Rule>> make_rules();
/// One rule by name, or nullptr.
std::unique_ptr<Rule> make_rule(const std::string& name);

/// A resolved path with its samples, from an accepted candidate (`stroke`, `segment` as given).
ResolvedPath resolve_path(const Candidate& candidate, int stroke, int segment,
                          double pixels_per_unit, const BeautifyOptions& options);
/// A candidate for a new, unprocessed path.
Candidate make_candidate(const Path& path);

}  // namespace exemplar::sketch
