// `exemplar brush`: Painting by Feature's line-feature brush (docs/feature.md). The feature is a
// rough path in the palette (snapped onto its edge unless --no-snap), the paths are painted with
// it on a transparent layer or over --canvas.

#include <string>
#include <vector>

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/feature_brush.hpp"
#include "option_help.hpp"
#include "output_files.hpp"
#include "stroke_files.hpp"

namespace exemplar::cli {

BrushCommand::BrushCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "brush",
        "Paint paths with a line feature picked in a palette image (Painting by Feature, "
        "docs/feature.md)");
    app_->footer(
        "Feature and path files: strokes JSON [{\"points\": [[x, y], ...], \"width\": 40}] or "
        "SVG;\nthe feature is one stroke in palette pixels (its width = the patch size), the "
        "paths are in canvas pixels.\n"
        "Example: exemplar brush --palette painting.png --feature edge.json --path curve.svg "
        "--width 800 --height 400 -o out.png");
    app_->add_option("--palette", palette_, "The feature palette: any image (grey, RGB, RGBA)")
        ->required();
    app_->add_option("--feature", feature_,
                     "The line feature: one rough stroke along it in the palette (.json or .svg)")
        ->required();
    app_->add_option("--path", path_, "The paths to paint (.json or .svg), in canvas pixels")
        ->required();
    app_->add_option("--output,-o", output_, "Result: RGBA image (PNG, TIFF, EXR)")->required();
    app_->add_option("--width", width_, "Canvas width in px (or from --canvas)");
    app_->add_option("--height", height_, "Canvas height in px (or from --canvas)");
    app_->add_option("--canvas", canvas_, "Background to paint over (RGB or RGBA)");
    app_->add_option("--brush-width", brush_width_,
                     "Width of every painted stroke in px (default: each path's width; the "
                     "feature is scaled by brush width / feature width)");
    app_->add_option("--walk", walk_,
                     "Walk through the feature: randomized (default), looping or dp (comparison "
                     "modes)");
    app_->add_option("--seed", seed_, "Random seed of the walk; default 1");
    app_->add_flag("--snap,!--no-snap", snap_,
                   "Snap the feature's rough path onto the palette's edge (default on)");
    add_table_flags(
        *app_, paint::feature_brush_option_specs(), paint::FeatureBrushOptions{},
        [](const paint::FeatureBrushOptions& o, const paint::FeatureBrushOptionSpec& spec) {
            return paint::get_option(o, spec);
        },
        numeric_values_, numeric_flags_);
    app_->add_option("--threads", threads_, "Threads (0 = all cores); the result is the same");
    app_->add_flag("--quiet,-q", quiet_, "Do not print the output path");
}

Status BrushCommand::run(const Streams& streams) const {
    // Checks that need no file.
    paint::FeatureBrushOptions options;
    EXEMPLAR_RETURN_IF_ERROR(set_given_table_flags(options, paint::feature_brush_option_specs(),
                                                   ModuleSetOption{}, numeric_values_,
                                                   numeric_flags_));
    auto walk = paint::parse_walk_mode(walk_);
    if (!walk.ok()) return invalid_argument("--" + walk.status().message());
    options.walk = *walk;
    options.seed = seed_;
    if (threads_ < 0) {
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0)");
    }
    if (app_->get_option("--brush-width")->count() > 0 &&
        !(brush_width_ > 0.0f && brush_width_ <= 4096.0f)) {
        return invalid_argument("--brush-width: " + std::to_string(brush_width_) +
                                " is invalid (must be > 0 and at most 4096)");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_stroke_file("--feature", feature_));
    EXEMPLAR_RETURN_IF_ERROR(check_stroke_file("--path", path_));
    EXEMPLAR_RETURN_IF_ERROR(check_canvas_size(canvas_, width_, height_));
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", output_));
    EXEMPLAR_RETURN_IF_ERROR(check_output_format("--output", output_, Image(1, 1, 4), {}));

    // Inputs: the palette, the canvas, the feature (in palette pixels) and the paths.
    auto palette = load_image(palette_);
    if (!palette.ok()) return palette.status();
    const int channels = palette->channels();
    if (channels != 1 && channels != 3 && channels != 4) {
        return invalid_argument("--palette " + palette_ + ": has " + std::to_string(channels) +
                                " channels (must be grey, RGB or RGBA)");
    }
    auto canvas_file = load_canvas(canvas_, width_, height_);
    if (!canvas_file.ok()) return canvas_file.status();
    const int width = canvas_file->width, height = canvas_file->height;
    const Image& background = canvas_file->background;
    auto features = read_strokes("--feature", feature_, palette->width(), palette->height());
    if (!features.ok()) return features.status();
    if (features->size() != 1) {
        return invalid_argument("--feature " + feature_ + ": holds " +
                                std::to_string(features->size()) +
                                " strokes (must be one: the rough path along the feature)");
    }
    auto paths = read_strokes("--path", path_, width, height);
    if (!paths.ok()) return paths.status();
    if (paths->empty()) return invalid_argument("--path " + path_ + ": holds no path");

    // The feature: snapped, sampled, its graph; then every path painted with it.
    // The library's messages start with "feature: "; the file takes its place.
    const auto about_feature = [&](const Status& status) {
        std::string message = status.message();
        if (message.rfind("feature: ", 0) == 0) message.erase(0, 9);
        return invalid_argument("--feature " + feature_ + ": " + message);
    };
    const RunContext context(threads_);
    auto feature =
        paint::pick_line_feature(*palette, features->front(), options, snap_, context.threads);
    if (!feature.ok()) return about_feature(feature.status());
    auto layer =
        paint::paint_feature(*feature, *paths, width, height, brush_width_, context.threads);
    if (!layer.ok()) return invalid_argument("--path " + path_ + ": " + layer.status().message());
    const Image out =
        background.empty() ? std::move(layer).value() : paint::composite_over(*layer, background);

    EXEMPLAR_RETURN_IF_ERROR(save_image(out, output_));
    if (!quiet_) streams.out << output_ << '\n';
    return Status::ok();
}

}  // namespace exemplar::cli
