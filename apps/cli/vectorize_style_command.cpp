// `exemplar vectorize-style`: Painting by Feature's vector image stylization (docs/feature.md).
// The drawing's stroked paths are painted with line features and its filled shapes with area
// features of a style palette file; the library's paint::vectorize_style does the work.

#include <string>

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/vectorize_style.hpp"
#include "option_help.hpp"
#include "output_files.hpp"

namespace exemplar::cli {

VectorizeStyleCommand::VectorizeStyleCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "vectorize-style",
        "Stylize an SVG drawing with line and area features of a palette image (Painting by "
        "Feature, docs/feature.md)");
    app_->footer(
        "The style palette (JSON, docs/feature.md) names the palette image, its line features "
        "(rough paths) and area features (regions), and assigns them to stroke and fill colours.\n"
        "Example: exemplar vectorize-style drawing.svg --palette style.json -o out.png");
    app_->add_option("drawing", drawing_, "The SVG drawing")->required();
    app_->add_option("--palette", palette_, "The style palette (.json)")->required();
    app_->add_option("--output,-o", output_, "Result: RGBA image (PNG, TIFF, EXR)")->required();
    app_->add_option("--width", width_,
                     "Canvas width in px; the height follows the drawing's aspect (default: the "
                     "drawing's size)");
    app_->add_option("--walk", walk_,
                     "Walk through the line features: randomized (default), looping or dp");
    app_->add_option("--usage", usage_,
                     "Patch usage of the fills: uniform (default), none, error-budget, occurrence");
    app_->add_option("--seed", seed_, "Random seed of the walks and fills; default 1");
    const auto get_brush = [](const paint::FeatureBrushOptions& o,
                              const paint::FeatureBrushOptionSpec& spec) {
        return paint::get_option(o, spec);
    };
    const auto get_fill = [](const paint::FeatureFillOptions& o,
                             const paint::FeatureFillOptionSpec& spec) {
        return paint::get_option(o, spec);
    };
    add_table_flags(*app_, paint::feature_brush_option_specs(), paint::FeatureBrushOptions{},
                    get_brush, numeric_values_, numeric_flags_);
    add_table_flags(*app_, paint::feature_fill_option_specs(), paint::FeatureFillOptions{},
                    get_fill, numeric_values_, numeric_flags_);
    app_->add_option("--threads", threads_, "Threads (0 = all cores); the result is the same");
    app_->add_flag("--quiet,-q", quiet_, "Do not print the output path");
}

Status VectorizeStyleCommand::run(const Streams& streams) const {
    // Checks that need no file.
    paint::VectorizeStyleOptions options;
    EXEMPLAR_RETURN_IF_ERROR(
        set_given_table_flags(options.brush, paint::feature_brush_option_specs(), ModuleSetOption{},
                              numeric_values_, numeric_flags_));
    EXEMPLAR_RETURN_IF_ERROR(set_given_table_flags(options.fill, paint::feature_fill_option_specs(),
                                                   ModuleSetOption{}, numeric_values_,
                                                   numeric_flags_));
    auto walk = paint::parse_walk_mode(walk_);
    if (!walk.ok()) return invalid_argument("--" + walk.status().message());
    auto usage = parse_usage_strategy(usage_);
    if (!usage.ok()) return invalid_argument("--" + usage.status().message());
    options.brush.walk = *walk;
    options.fill.usage = *usage;
    options.brush.seed = options.fill.seed = seed_;
    if (threads_ < 0) {
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0)");
    }
    if (width_ < 0 || width_ > 32768) {
        return invalid_argument("--width: " + std::to_string(width_) +
                                " is invalid (must be 1..32768, or 0 for the drawing's size)");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", output_));
    EXEMPLAR_RETURN_IF_ERROR(check_output_format("--output", output_, Image(1, 1, 4), {}));

    // Inputs: the drawing and the style palette.
    auto drawing = sketch::load_svg(drawing_);
    if (!drawing.ok()) return drawing.status();
    auto palette = paint::load_style_palette(palette_);
    if (!palette.ok()) return palette.status();

    const auto [width, height] = paint::drawing_canvas_size(*drawing, width_);
    auto out =
        paint::vectorize_style(*drawing, *palette, width, height, options, RunContext(threads_));
    if (!out.ok()) {
        // The library's messages about the drawing start with "drawing: "; the file takes its
        // place. The others name a feature of the palette file.
        std::string message = out.status().message();
        if (message.rfind("drawing: ", 0) == 0)
            return invalid_argument(drawing_ + message.substr(7));
        return invalid_argument(palette_ + ": " + message);
    }
    EXEMPLAR_RETURN_IF_ERROR(save_image(*out, output_));
    if (!quiet_) streams.out << output_ << '\n';
    return Status::ok();
}

}  // namespace exemplar::cli
