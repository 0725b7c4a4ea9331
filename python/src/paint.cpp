// exemplar.directions and exemplar.paint: Brushables (Lukac et al. 2015) as `exemplar directions`
// and `exemplar paint` do it (apps/cli/directions_command.cpp, paint_command.cpp), arrays where
// they read and write files, strokes as dicts with the keys of their JSON stroke files. Neither
// verb has an option table: the keywords are the CLI's flags with '_' for '-'.
// exemplar.brush, exemplar.fill and exemplar.vectorize_style: Painting by Feature as `exemplar
// brush`, `exemplar fill` and `exemplar vectorize-style` do it (brush_command.cpp,
// fill_command.cpp, vectorize_style_command.cpp); their numeric keywords come from the option
// tables feature_brush_option_specs() and feature_fill_option_specs().

#include "exemplar/paint/paint.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "exemplar/paint/directions.hpp"
#include "exemplar/paint/feature_brush.hpp"
#include "exemplar/paint/feature_fill.hpp"
#include "exemplar/paint/strokes.hpp"
#include "exemplar/paint/vectorize_style.hpp"
#include "keywords.hpp"
#include "run.hpp"

namespace exemplar::python {

namespace {

template <typename T>
void set_number(py::dict& kwargs, const char* name, T& field) {
    const py::object value = pop(kwargs, name);
    if (value.is_none()) return;
    if constexpr (std::is_same_v<T, float>) {
        field = static_cast<float>(number(value, name));
    } else {
        field = integer(value, name);
    }
}

py::array directions_py(const py::object& image, py::kwargs kwargs) {
    py::dict args(kwargs);
    paint::DirectionAnalysisOptions options;
    set_number(args, "radius", options.radius_px);
    set_number(args, "iterations", options.iterations);
    set_number(args, "gradient_sigma", options.gradient_sigma_px);
    options.harmonize_signs = pop_bool(args, "harmonize", true);
    const int threads = threads_keyword(pop(args, "threads"));
    reject_unknown(args, "directions");
    check(paint::validate(options));
    const Image input = image_from_array(image, "image", Shape::Colour).image;
    Result<Image> field = [&] {
        py::gil_scoped_release release;
        return paint::analyze_directions(input, options, threads);
    }();
    return grey_array_from_image(paint::direction_angles(take(std::move(field))));
}

std::string indexed(const char* name, std::size_t i) {
    return std::string(name) + "[" + std::to_string(i) + "]";
}

// A stroke: a dict {"points": Nx2, "width": 40, "comb": False}, as the CLI's JSON stroke files.
paint::Stroke stroke_from(const py::handle& dict, const std::string& what) {
    if (!py::isinstance<py::dict>(dict)) {
        throw py::type_error(what + ": must be a dict with points, width, comb");
    }
    // A copy (dict.copy(); py::dict(d) would share d): pop() must not change the caller's.
    py::dict entry = dict.attr("copy")();
    const py::object points = pop(entry, "points");
    const py::object width = pop(entry, "width");
    const py::object comb = pop(entry, "comb");
    const py::object label = pop(entry, "label");
    for (const auto& key : entry) {
        throw py::type_error(what + ": unknown key '" + std::string(py::str(key.first)) +
                             "' (keys: points, width, comb, label)");
    }
    if (points.is_none()) throw py::type_error(what + ": needs 'points'");
    const auto array =
        py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
    if (!array || array.ndim() != 2 || array.shape(1) != 2) {
        throw InputError(what + ": points must be Nx2 (x, y in canvas pixels)");
    }
    paint::Stroke stroke;
    for (py::ssize_t k = 0; k < array.shape(0); ++k) {
        stroke.points.push_back(
            {static_cast<float>(array.at(k, 0)), static_cast<float>(array.at(k, 1))});
    }
    if (!width.is_none()) stroke.width_px = static_cast<float>(number(width, what + " width"));
    if (!comb.is_none()) {
        if (!py::isinstance<py::bool_>(comb)) throw py::type_error(what + " comb: must be a bool");
        stroke.comb = comb.cast<bool>();
    }
    if (!label.is_none()) stroke.label = integer(label, what + " label");
    return stroke;
}

// Strokes: a sequence of stroke dicts, `name[i]` in messages.
std::vector<paint::Stroke> strokes_from(const py::handle& strokes, const char* name) {
    if (!py::isinstance<py::sequence>(strokes) || py::isinstance<py::str>(strokes)) {
        throw py::type_error(std::string(name) +
                             ": must be a sequence of dicts with points, width, comb");
    }
    std::vector<paint::Stroke> out;
    const auto sequence = py::reinterpret_borrow<py::sequence>(strokes);
    for (std::size_t i = 0; i < sequence.size(); ++i) {
        out.push_back(stroke_from(sequence[i], indexed(name, i)));
    }
    return out;
}

// The canvas of paint and brush: the width/height keywords, or the background's size.
struct Canvas {
    Image background;  // RGB or RGBA; empty: none
    int width = 0, height = 0;
};

Canvas canvas_from(const py::object& width_given, const py::object& height_given,
                   const py::object& canvas_given) {
    Canvas out;
    Image& background = out.background;
    if (!canvas_given.is_none()) {
        background = image_from_array(canvas_given, "canvas", Shape::Colour).image;
        if (background.channels() != 3 && background.channels() != 4) {
            throw InputError("canvas: must be RGB or RGBA");
        }
    }
    const int width = width_given.is_none() ? background.width() : integer(width_given, "width");
    const int height =
        height_given.is_none() ? background.height() : integer(height_given, "height");
    if (width <= 0 || height <= 0) {
        throw InputError("width/height: " + std::to_string(width) + "x" + std::to_string(height) +
                         " is invalid (both must be > 0, or give canvas)");
    }
    if (width > 32768 || height > 32768) throw InputError("width/height: at most 32768 px");
    if (!background.empty() && (background.width() != width || background.height() != height)) {
        throw InputError("canvas: is " + std::to_string(background.width()) + "x" +
                         std::to_string(background.height()) + " but width/height are " +
                         std::to_string(width) + "x" + std::to_string(height));
    }
    out.width = width;
    out.height = height;
    return out;
}

py::array paint_py(const py::object& source, const py::object& strokes, py::kwargs kwargs) {
    py::dict args(kwargs);
    paint::PaintOptions options;
    set_number(args, "shape_weight", options.shape_weight);
    set_number(args, "edge_extent", options.edge_extent_px);
    set_number(args, "shape_bins", options.shape_bins);
    set_number(args, "alpha_weight", options.alpha_weight);
    set_number(args, "vote_coherence", options.vote_coherence);
    set_number(args, "vote_histogram", options.vote_histogram);
    if (const py::object usage = pop(args, "usage"); !usage.is_none()) {
        options.usage = take(parse_usage_strategy(text(usage, "usage")));
    }
    set_number(args, "patch_size", options.patch_size);
    pop_seed(args, options.seed);
    check(paint::validate(options));
    const py::object width_given = pop(args, "width");
    const py::object height_given = pop(args, "height");
    const py::object canvas_given = pop(args, "canvas");
    const py::object mask_given = pop(args, "source_mask");
    const py::object directions_given = pop(args, "source_directions");
    const py::object labels_given = pop(args, "source_labels");
    const RunKeywords run_keywords = pop_run_keywords(args);
    reject_unknown(args, "paint");

    const Canvas target = canvas_from(width_given, height_given, canvas_given);
    const Image& background = target.background;
    const int width = target.width, height = target.height;

    paint::PaintSource input;
    ImageArg source_arg = image_from_array(source, "source", Shape::Colour);
    input.image = source_arg.image;
    if (input.image.channels() != 3 && input.image.channels() != 4) {
        throw InputError("source: has " + std::to_string(input.image.channels()) +
                         " channels (must be RGB or RGBA)");
    }
    if (!mask_given.is_none()) {
        input.mask = image_from_array(mask_given, "source_mask", Shape::Grey).image;
    }
    if (!directions_given.is_none()) {
        ImageArg arg = image_from_array(directions_given, "source_directions", Shape::Grey);
        if (arg.type != SampleType::Float32) {
            throw InputError(
                "source_directions: a direction field holds angles in radians and "
                "must be float32");
        }
        input.directions = std::move(arg.image);
    }
    if (!labels_given.is_none())
        input.labels =
            integer_ids(labels_given, "source_labels", "segment id", paint::max_stroke_label);
    const std::vector<paint::Stroke> stroke_list = strokes_from(strokes, "strokes");
    paint::PaintCanvas canvas(width, height);
    for (const paint::Stroke& stroke : stroke_list) take(canvas.add_stroke(stroke));

    PythonRun run(run_keywords);
    paint::PaintResult result = run(
        [&](const RunContext& context) { return paint::paint(input, canvas, options, context); });
    Image out = background.empty() ? std::move(result.image)
                                   : paint::composite_over(result.image, background);
    return array_from_image(std::move(out), source_arg.type);
}

// exemplar.brush: `exemplar brush` (apps/cli/brush_command.cpp) with the feature and the paths as
// stroke dicts; keywords: the CLI's flags and the brush's option table.
py::array brush_py(const py::object& palette, const py::object& feature, const py::object& paths,
                   py::kwargs kwargs) {
    py::dict args(kwargs);
    paint::FeatureBrushOptions options;
    pop_table_options(args, options, paint::feature_brush_option_specs());
    if (const py::object walk = pop(args, "walk"); !walk.is_none()) {
        options.walk = take(paint::parse_walk_mode(text(walk, "walk")));
    }
    pop_seed(args, options.seed);
    check(paint::validate(options));
    const bool snap = pop_bool(args, "snap", true);
    float brush_width = 0.0f;
    set_number(args, "brush_width", brush_width);
    const py::object width_given = pop(args, "width");
    const py::object height_given = pop(args, "height");
    const py::object canvas_given = pop(args, "canvas");
    const RunKeywords run_keywords = pop_run_keywords(args);
    reject_unknown(args, "brush");

    const Canvas target = canvas_from(width_given, height_given, canvas_given);
    ImageArg palette_arg = image_from_array(palette, "palette", Shape::Colour);
    const paint::Stroke selection = stroke_from(feature, "feature");
    const std::vector<paint::Stroke> path_list = strokes_from(paths, "paths");

    PythonRun run(run_keywords);
    Image layer = run([&](const RunContext& context) -> Result<Image> {
        auto picked =
            paint::pick_line_feature(palette_arg.image, selection, options, snap, context.threads);
        if (!picked.ok()) return picked.status();
        return paint::paint_feature(*picked, path_list, target.width, target.height, brush_width,
                                    context.threads);
    });
    Image out = target.background.empty() ? std::move(layer)
                                          : paint::composite_over(layer, target.background);
    return array_from_image(std::move(out), palette_arg.type);
}

// An image of fill: HxW (grey) or HxWxC.
ImageArg any_image(const py::handle& value, const char* name) {
    const bool grey =
        py::isinstance<py::array>(value) && py::reinterpret_borrow<py::array>(value).ndim() == 2;
    return image_from_array(value, name, grey ? Shape::Grey : Shape::Colour);
}

// exemplar.fill: `exemplar fill` (apps/cli/fill_command.cpp) with the images as arrays;
// keywords: the CLI's flags and the fill's option table.
py::array fill_py(const py::object& palette, const py::object& source_region,
                  const py::object& target_region, py::kwargs kwargs) {
    py::dict args(kwargs);
    paint::FeatureFillOptions options;
    pop_table_options(args, options, paint::feature_fill_option_specs());
    if (const py::object usage = pop(args, "usage"); !usage.is_none()) {
        options.usage = take(parse_usage_strategy(text(usage, "usage")));
    }
    pop_seed(args, options.seed);
    check(paint::validate(options));
    const py::object canvas_given = pop(args, "canvas");
    const RunKeywords run_keywords = pop_run_keywords(args);
    reject_unknown(args, "fill");

    ImageArg palette_arg = any_image(palette, "palette");
    const Image source = any_image(source_region, "source_region").image;
    const Image target = any_image(target_region, "target_region").image;
    const Image canvas = canvas_given.is_none() ? Image() : any_image(canvas_given, "canvas").image;
    PythonRun run(run_keywords);
    Image out = run([&](const RunContext& context) {
        return paint::fill_with_palette(palette_arg.image, source, canvas, target, options,
                                        context);
    });
    return array_from_image(std::move(out), palette_arg.type);
}

// exemplar.vectorize_style: `exemplar vectorize-style` (apps/cli/vectorize_style_command.cpp)
// with the drawing and the style palette as files; keywords: the CLI's flags and the brush's and
// fill's option tables.
py::array vectorize_style_py(const std::string& drawing_path, const std::string& palette_path,
                             py::kwargs kwargs) {
    py::dict args(kwargs);
    paint::VectorizeStyleOptions options;
    pop_table_options(args, options.brush, paint::feature_brush_option_specs());
    pop_table_options(args, options.fill, paint::feature_fill_option_specs());
    if (const py::object walk = pop(args, "walk"); !walk.is_none()) {
        options.brush.walk = take(paint::parse_walk_mode(text(walk, "walk")));
    }
    if (const py::object usage = pop(args, "usage"); !usage.is_none()) {
        options.fill.usage = take(parse_usage_strategy(text(usage, "usage")));
    }
    pop_seed(args, options.brush.seed);
    options.fill.seed = options.brush.seed;
    int width = 0;
    set_number(args, "width", width);
    const RunKeywords run_keywords = pop_run_keywords(args);
    reject_unknown(args, "vectorize_style");
    if (width < 0 || width > 32768) {
        check(invalid_argument("width: " + std::to_string(width) +
                               " is invalid (must be 1..32768, or 0 for the drawing's size)"));
    }

    const sketch::Drawing drawing = take(sketch::load_svg(drawing_path));
    const paint::StylePalette palette = take(paint::load_style_palette(palette_path));
    const auto [w, h] = paint::drawing_canvas_size(drawing, width);
    PythonRun run(run_keywords);
    Image out = run([&](const RunContext& context) {
        return paint::vectorize_style(drawing, palette, w, h, options, context);
    });
    return array_from_image(std::move(out), SampleType::UInt8);
}

}  // namespace

void register_paint(py::module_& module) {
    module.def("_directions", &directions_py, py::arg("image"));
    module.def("_paint", &paint_py, py::arg("source"), py::arg("strokes"));
    module.def("_brush", &brush_py, py::arg("palette"), py::arg("feature"), py::arg("paths"));
    module.def("_fill", &fill_py, py::arg("palette"), py::arg("source_region"),
               py::arg("target_region"));
    module.def("_vectorize_style", &vectorize_style_py, py::arg("drawing"), py::arg("palette"));
    module.def("_feature_brush_option_specs", [] {
        return table_specs_for_python<paint::FeatureBrushOptions>(
            paint::feature_brush_option_specs(),
            [](const paint::FeatureBrushOptions& o, const paint::FeatureBrushOptionSpec& spec) {
                return paint::get_option(o, spec);
            });
    });
    module.def("_feature_fill_option_specs", [] {
        return table_specs_for_python<paint::FeatureFillOptions>(
            paint::feature_fill_option_specs(),
            [](const paint::FeatureFillOptions& o, const paint::FeatureFillOptionSpec& spec) {
                return paint::get_option(o, spec);
            });
    });
}

}  // namespace exemplar::python
