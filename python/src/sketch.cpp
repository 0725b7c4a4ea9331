// exemplar.beautify: ShipShape on an SVG drawing (text or file) or on polylines, stroke by
// stroke. The keywords are `exemplar beautify`'s flags (apps/cli/beautify_command.cpp); where
// the CLI writes files this returns the beautified SVG text, the report's entries and the last
// stroke's suggestions as Python objects.

#include <pybind11/stl.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "exemplar/sketch/beautify.hpp"
#include "exemplar/sketch/fit.hpp"
#include "exemplar/sketch/svg.hpp"
#include "keywords.hpp"

namespace exemplar::python {

namespace {

using sketch::Drawing;
using sketch::Path;

/// What beautify returns.
struct BeautifyResult {
    std::string svg;
    std::vector<std::string> paths;
    py::list strokes;
    py::dict relation_counts;
    py::list suggestions;
};

// The relations of a suggestion, each with the segment it applies to (the CLI's report).
py::list relations_of(const sketch::Suggestion& s) {
    py::list relations;
    for (std::size_t k = 0; k < s.segments.size(); ++k) {
        for (const sketch::Relation& r : s.segments[k].relations) {
            py::dict entry;
            entry["rule"] = r.rule;
            entry["segment"] = k;
            entry["strokes"] = r.strokes;
            entry["likelihood"] = r.likelihood;
            entry["detail"] = r.detail;
            relations.append(entry);
        }
    }
    return relations;
}

std::string stroke_name(const Drawing& d, std::size_t i) {
    std::string name = "stroke " + std::to_string(i);
    if (i < d.ids.size() && !d.ids[i].empty()) name += " (id \"" + d.ids[i] + "\")";
    return name;
}

// The drawing: SVG text, an .svg file, or polylines (Nx2 arrays in view pixels).
std::pair<Drawing, std::string> drawing_from(const py::object& object) {
    if (py::isinstance<py::str>(object)) {
        const std::string given = object.cast<std::string>();
        if (given.find('<') != std::string::npos) {
            return {take(sketch::parse_svg(given, "drawing")), "drawing"};
        }
        return {take(sketch::load_svg(given)), given};
    }
    if (!py::isinstance<py::sequence>(object) || py::isinstance<py::array>(object)) {
        throw py::type_error(
            "drawing: must be SVG text, an .svg path or a sequence of Nx2 "
            "point arrays");
    }
    Drawing drawing;
    const auto strokes = py::reinterpret_borrow<py::sequence>(object);
    for (std::size_t i = 0; i < strokes.size(); ++i) {
        const std::string what = "drawing[" + std::to_string(i) + "]";
        const py::object stroke = strokes[i];
        if (!py::isinstance<py::array>(stroke)) {
            throw InputError(what + ": must be a numpy array of points (Nx2)");
        }
        const auto points =
            py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(stroke);
        if (!points || points.ndim() != 2 || points.shape(1) != 2) {
            throw InputError(what + ": must be an Nx2 array of points (x, y)");
        }
        std::vector<sketch::Vec2> polyline;
        for (py::ssize_t k = 0; k < points.shape(0); ++k) {
            const double x = points.at(k, 0), y = points.at(k, 1);
            if (!std::isfinite(x) || !std::isfinite(y)) {
                throw InputError(what + ": contains NaN or infinity");
            }
            polyline.push_back({x, y});
        }
        drawing.paths.push_back(sketch::polyline_path(polyline));
        drawing.ids.emplace_back();
    }
    return {std::move(drawing), "drawing"};
}

BeautifyResult beautify_py(const py::object& drawing_arg, py::kwargs kwargs) {
    py::dict args(kwargs);
    // Checks that need no drawing, as the CLI makes them.
    sketch::BeautifyOptions options;
    if (const py::object max = pop(args, "max_suggestions"); !max.is_none()) {
        const double value = number(max, "max_suggestions");
        if (value != std::floor(value)) {
            throw InputError("max_suggestions: " + std::string(py::str(max)) +
                             " is invalid (must be an integer)");
        }
        options.max_suggestions = static_cast<int>(std::clamp(value, -1.0, 1e6));
    }
    if (const Status s = sketch::validate(options); !s.is_ok()) {
        // The library names the field (max-suggestions); this is its keyword.
        std::string message = s.message();
        if (message.rfind("max-suggestions", 0) == 0) message.replace(0, 15, "max_suggestions");
        throw StatusError(Status(s.code(), message));
    }
    double fit_px = 0.0;
    if (const py::object fit = pop(args, "fit"); !fit.is_none()) fit_px = number(fit, "fit");
    if (!(std::isfinite(fit_px) && fit_px >= 0.0 && fit_px <= 100.0)) {
        throw InputError("fit: " + std::to_string(fit_px) + " is invalid (must be 0..100 view px)");
    }
    reject_unknown(args, "beautify");

    auto [drawing, name] = drawing_from(drawing_arg);
    if (drawing.paths.empty()) {
        throw InputError(name +
                         ": the drawing has no strokes (no path, line, polyline, polygon, circle, "
                         "ellipse or rect)");
    }
    for (std::size_t i = 0; i < drawing.paths.size(); ++i) {
        if (drawing.paths[i].empty() || sketch::arc_length(drawing.paths[i]) <= 0.0) {
            throw InputError(name + ": " + stroke_name(drawing, i) +
                             " is degenerate (a single point)");
        }
    }
    if (fit_px > 0.0) {
        for (Path& p : drawing.paths) {
            p = sketch::refit_polyline(p, fit_px / drawing.pixels_per_unit);
        }
    }
    Result<sketch::ReplayResult> replayed = [&] {
        py::gil_scoped_release release;
        return sketch::replay(drawing.paths, drawing.pixels_per_unit, options);
    }();
    if (!replayed.ok()) {
        throw StatusError(
            Status(replayed.status().code(), name + ": " + replayed.status().message()));
    }
    const sketch::ReplayResult& result = *replayed;

    // The CLI's output file, report and suggestions.
    BeautifyResult out;
    std::vector<Path> clean;
    for (const sketch::StrokeResult& s : result.strokes) {
        clean.push_back(s.chosen.path);
        out.paths.push_back(sketch::path_data(s.chosen.path));
    }
    const double width = (drawing.view_width > 0 ? drawing.view_width : 800.0) * 0.003;
    out.svg = sketch::to_svg(
        drawing, {sketch::SvgLayer{clean, drawing.ids, "black", width, 1.0, "beautified"}});
    std::map<std::string, int> totals;
    const double ppu = drawing.pixels_per_unit;
    for (std::size_t i = 0; i < result.strokes.size(); ++i) {
        const sketch::StrokeResult& s = result.strokes[i];
        for (const sketch::Relation& r : s.chosen.relations()) ++totals[r.rule];
        py::dict entry;
        entry["index"] = i;
        entry["id"] = i < drawing.ids.size() ? drawing.ids[i] : "";
        entry["kind"] = s.chosen.segments.size() == 1
                            ? std::string(sketch::to_string(s.chosen.segments[0].kind))
                            : std::string("multi-segment");
        entry["segments"] = s.chosen.segments.size();
        entry["likelihood"] = s.chosen.likelihood;
        entry["moved_px"] = s.moved * ppu;
        entry["size_px"] = s.size * ppu;
        entry["suggestions"] = s.suggestion_count;
        entry["relations"] = relations_of(s.chosen);
        out.strokes.append(entry);
    }
    for (const auto& [rule, count] : totals) out.relation_counts[py::str(rule)] = count;
    for (std::size_t k = 0; k < result.last_suggestions.size(); ++k) {
        const sketch::Suggestion& s = result.last_suggestions[k];
        py::dict entry;
        entry["rank"] = k + 1;
        entry["likelihood"] = s.likelihood;
        entry["original"] = s.original;
        entry["segments"] = s.segments.size();
        entry["path"] = sketch::path_data(s.path);
        entry["relations"] = relations_of(s);
        out.suggestions.append(entry);
    }
    return out;
}

}  // namespace

void register_sketch(py::module_& module) {
    py::class_<BeautifyResult>(module, "BeautifyResult",
                               "What beautify returns: the beautified drawing and what changed.")
        .def_readonly("svg", &BeautifyResult::svg,
                      "The beautified drawing as SVG text (the CLI's --output file).")
        .def_readonly("paths", &BeautifyResult::paths,
                      "SVG path data of every beautified stroke, in drawing order.")
        .def_readonly("strokes", &BeautifyResult::strokes,
                      "Per stroke, the CLI's --report entry: index, id, kind, segments, "
                      "likelihood, moved_px, size_px, suggestions, relations.")
        .def_readonly("relation_counts", &BeautifyResult::relation_counts,
                      "How often each rule was applied (the report's relation_counts).")
        .def_readonly("suggestions", &BeautifyResult::suggestions,
                      "The ranked alternatives for the last stroke (the CLI's --suggestions "
                      ".json): rank, likelihood, original, segments, path, relations.")
        .def("__repr__", [](const BeautifyResult& r) {
            return "<exemplar.BeautifyResult " + std::to_string(r.paths.size()) + " strokes>";
        });
    module.def("_beautify", &beautify_py, py::arg("drawing"));
}

}  // namespace exemplar::python
