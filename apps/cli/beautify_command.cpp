// `exemplar beautify`: replays an SVG drawing's strokes in document order, beautifying each
// against the ones before (ShipShape, docs/sketch.md), and writes the result, a JSON report of
// the relations enforced per stroke, the ranked alternatives for the last stroke and a
// before/after picture.

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "exemplar/sketch/beautify.hpp"
#include "exemplar/sketch/fit.hpp"
#include "exemplar/sketch/svg.hpp"
#include "output_files.hpp"

namespace exemplar::cli {

namespace {

using nlohmann::json;
using sketch::Drawing;
using sketch::Path;
using sketch::SvgLayer;

// The relations of a suggestion, each with the segment it applies to (0 for one-piece strokes).
json relations_json(const sketch::Suggestion& s) {
    json relations = json::array();
    for (std::size_t k = 0; k < s.segments.size(); ++k) {
        for (const sketch::Relation& r : s.segments[k].relations) {
            relations.push_back({{"rule", r.rule},
                                 {"segment", k},
                                 {"strokes", r.strokes},
                                 {"likelihood", r.likelihood},
                                 {"detail", r.detail}});
        }
    }
    return relations;
}

json suggestion_json(const sketch::Suggestion& s, int rank) {
    const json relations = relations_json(s);
    return {{"rank", rank},
            {"likelihood", s.likelihood},
            {"original", s.original},
            {"segments", s.segments.size()},
            {"path", sketch::path_data(s.path)},
            {"relations", relations}};
}

std::string stroke_name(const Drawing& d, std::size_t i) {
    std::string name = "stroke " + std::to_string(i);
    if (i < d.ids.size() && !d.ids[i].empty()) name += " (id \"" + d.ids[i] + "\")";
    return name;
}

// The drawing's canvas: its viewBox, or its strokes' bounds.
std::array<double, 4> bounds_of(const Drawing& d) {
    return sketch::canvas_bounds(d, {SvgLayer{d.paths, {}, "black", 1.0, 1.0, ""}});
}

// The last stroke's suggestions side by side: the earlier result in grey, suggestion k in blue.
std::string suggestions_svg(const Drawing& drawing, const sketch::ReplayResult& result) {
    const auto box = bounds_of(drawing);
    const double gap = 0.05 * box[2];
    std::vector<Path> context;
    for (std::size_t i = 0; i + 1 < result.strokes.size(); ++i) {
        context.push_back(result.strokes[i].chosen.path);
    }
    std::vector<SvgLayer> layers;
    const double width = box[2] / drawing.pixels_per_unit;
    for (std::size_t k = 0; k < result.last_suggestions.size(); ++k) {
        const sketch::Affine shift =
            sketch::Affine::translation({static_cast<double>(k) * (box[2] + gap), 0.0});
        SvgLayer grey{{},        {},
                      "#999999", 0.004 * width * drawing.pixels_per_unit,
                      1.0,       "context-" + std::to_string(k + 1)};
        for (const Path& p : context) grey.paths.push_back(sketch::transformed(p, shift));
        SvgLayer blue{{sketch::transformed(result.last_suggestions[k].path, shift)},
                      {"suggestion-" + std::to_string(k + 1)},
                      result.last_suggestions[k].original ? "#cc3333" : "#1a5ae6",
                      0.006 * width * drawing.pixels_per_unit,
                      1.0,
                      "suggestion-" + std::to_string(k + 1)};
        layers.push_back(std::move(grey));
        layers.push_back(std::move(blue));
    }
    Drawing canvas = drawing;
    const double count = static_cast<double>(result.last_suggestions.size());
    canvas.view_x = box[0];
    canvas.view_y = box[1];
    canvas.view_width = count * box[2] + (count - 1) * gap;
    canvas.view_height = box[3];
    return sketch::to_svg(canvas, layers);
}

}  // namespace

BeautifyCommand::BeautifyCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "beautify",
        "Beautify a sketch stroke by stroke (ShipShape: lines, arcs, snapping, symmetry)");
    app_->footer(
        "Strokes are replayed in document order; each is beautified against the ones before and "
        "the first (most likely) suggestion is kept. Distances are in view pixels (the SVG's "
        "width against its viewBox). Rules and defaults: docs/sketch.md.\n"
        "Example: exemplar beautify sketch.svg -o clean.svg --report report.json "
        "--preview before_after.png");
    app_->add_option("drawing", input_, "Input SVG drawing (paths, lines, polylines, shapes)")
        ->required();
    app_->add_option("--output,-o", output_, "Beautified drawing (.svg)")->required();
    app_->add_option("--report", report_,
                     "JSON report: the relations enforced per stroke, how far each moved");
    app_->add_option("--suggestions", suggestions_,
                     "The ranked alternatives for the last stroke: .json (path data, "
                     "likelihoods, relations) or .svg (side by side, the input in red last)");
    app_->add_option("--preview", preview_,
                     "Before/after picture (.png): the input in grey under the result in black");
    app_->add_option("--max-suggestions", max_suggestions_,
                     "Suggestions per stroke, 1..100 (default 10, the paper's N)");
    app_->add_option("--fit", fit_px_,
                     "Refit strokes drawn as polylines (pen samples: 3 or more straight pieces) "
                     "as smooth Bezier paths within this many view px before beautifying, "
                     "0..100; 0 keeps them as drawn (default 0)");
    app_->add_flag("--quiet,-q", quiet_, "Do not print the output paths");
}

Status BeautifyCommand::run(const Streams& streams) const {
    // Checks that need no file.
    sketch::BeautifyOptions options;
    options.max_suggestions = max_suggestions_;
    if (Status s = sketch::validate(options); !s.is_ok())
        return invalid_argument("--" + s.message());
    if (!(std::isfinite(fit_px_) && fit_px_ >= 0.0 && fit_px_ <= 100.0)) {
        return invalid_argument("--fit: " + std::to_string(fit_px_) +
                                " is invalid (must be 0..100 view px)");
    }
    if (lowercase_extension(output_) != ".svg") {
        return invalid_argument("--output " + output_ + ": must be an .svg file");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", output_));
    if (!report_.empty()) EXEMPLAR_RETURN_IF_ERROR(check_output_path("--report", report_));
    const std::string suggestions_ext = lowercase_extension(suggestions_);
    if (!suggestions_.empty()) {
        if (suggestions_ext != ".svg" && suggestions_ext != ".json") {
            return invalid_argument("--suggestions " + suggestions_ +
                                    ": must be a .json or .svg file");
        }
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("--suggestions", suggestions_));
    }
    if (!preview_.empty()) {
        if (lowercase_extension(preview_) != ".png") {
            return invalid_argument("--preview " + preview_ + ": must be a .png file");
        }
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("--preview", preview_));
    }

    // The drawing and its strokes.
    auto drawing = sketch::load_svg(input_);
    if (!drawing.ok()) return drawing.status();
    if (drawing->paths.empty()) {
        return invalid_argument(input_ +
                                ": the drawing has no strokes (no path, line, polyline, "
                                "polygon, circle, ellipse or rect)");
    }
    for (std::size_t i = 0; i < drawing->paths.size(); ++i) {
        if (drawing->paths[i].empty() || sketch::arc_length(drawing->paths[i]) <= 0.0) {
            return invalid_argument(input_ + ": " + stroke_name(*drawing, i) +
                                    " is degenerate (a single point)");
        }
    }
    if (fit_px_ > 0.0) {
        for (Path& p : drawing->paths) {
            p = sketch::refit_polyline(p, fit_px_ / drawing->pixels_per_unit);
        }
    }
    auto result = sketch::replay(drawing->paths, drawing->pixels_per_unit, options);
    if (!result.ok())
        return Status(result.status().code(), input_ + ": " + result.status().message());

    // Outputs, each atomic.
    std::vector<Path> clean;
    for (const sketch::StrokeResult& s : result->strokes) clean.push_back(s.chosen.path);
    const double width = (drawing->view_width > 0 ? drawing->view_width : 800.0) * 0.003;
    const SvgLayer result_layer{clean, drawing->ids, "black", width, 1.0, "beautified"};
    EXEMPLAR_RETURN_IF_ERROR(sketch::save_svg(*drawing, {result_layer}, output_));
    if (!quiet_) streams.out << output_ << '\n';

    if (!report_.empty()) {
        json strokes = json::array();
        std::map<std::string, int> totals;
        const double ppu = drawing->pixels_per_unit;
        for (std::size_t i = 0; i < result->strokes.size(); ++i) {
            const sketch::StrokeResult& s = result->strokes[i];
            const json relations = relations_json(s.chosen);
            for (const sketch::Relation& r : s.chosen.relations()) ++totals[r.rule];
            std::string kind = s.chosen.segments.size() == 1
                                   ? sketch::to_string(s.chosen.segments[0].kind)
                                   : "multi-segment";
            strokes.push_back({{"index", i},
                               {"id", i < drawing->ids.size() ? drawing->ids[i] : ""},
                               {"kind", kind},
                               {"segments", s.chosen.segments.size()},
                               {"likelihood", s.chosen.likelihood},
                               {"moved_px", s.moved * ppu},
                               {"size_px", s.size * ppu},
                               {"suggestions", s.suggestion_count},
                               {"relations", relations}});
        }
        const json report = {{"input", input_},
                             {"output", output_},
                             {"strokes", result->strokes.size()},
                             {"max_suggestions", options.max_suggestions},
                             {"relation_counts", totals},
                             {"per_stroke", strokes}};
        EXEMPLAR_RETURN_IF_ERROR(sketch::save_text(report.dump(2) + "\n", report_));
        if (!quiet_) streams.out << report_ << '\n';
    }
    if (!suggestions_.empty()) {
        std::string text;
        if (suggestions_ext == ".json") {
            json list = json::array();
            for (std::size_t k = 0; k < result->last_suggestions.size(); ++k) {
                list.push_back(
                    suggestion_json(result->last_suggestions[k], static_cast<int>(k) + 1));
            }
            text =
                json{{"stroke", result->strokes.size() - 1}, {"suggestions", list}}.dump(2) + "\n";
        } else {
            text = suggestions_svg(*drawing, *result);
        }
        EXEMPLAR_RETURN_IF_ERROR(sketch::save_text(text, suggestions_));
        if (!quiet_) streams.out << suggestions_ << '\n';
    }
    if (!preview_.empty()) {
        // Left the input, right the result over the input in light grey.
        const auto box = bounds_of(*drawing);
        const sketch::Affine shift = sketch::Affine::translation({box[2] * 1.02, 0.0});
        std::vector<Path> input_right, clean_right;
        for (const Path& p : drawing->paths) input_right.push_back(sketch::transformed(p, shift));
        for (const Path& p : clean) clean_right.push_back(sketch::transformed(p, shift));
        Drawing canvas = *drawing;
        canvas.view_x = box[0];
        canvas.view_y = box[1];
        canvas.view_width = box[2] * 2.02;
        canvas.view_height = box[3];
        const std::vector<SvgLayer> layers{{drawing->paths, {}, "black", width, 1.0, "input"},
                                           {input_right, {}, "#bbbbbb", width, 1.0, "under"},
                                           {clean_right, {}, "black", width, 1.0, "result"}};
        EXEMPLAR_RETURN_IF_ERROR(sketch::save_png(canvas, layers, preview_, 1024));
        if (!quiet_) streams.out << preview_ << '\n';
    }
    return Status::ok();
}

}  // namespace exemplar::cli
