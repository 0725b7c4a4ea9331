// `exemplar fill`: Painting by Feature's area-feature fill (docs/feature.md). The target region
// of the canvas is filled with the texture of the source region of the palette; pixels outside
// the target region are the canvas's.

#include <string>
#include <tuple>
#include <utility>

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/feature_fill.hpp"
#include "option_help.hpp"
#include "output_files.hpp"

namespace exemplar::cli {
FillCommand::FillCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "fill",
        "Fill a region with the texture of a region picked in a palette image (Painting by "
        "Feature, docs/feature.md)");
    app_->footer(
        "Regions are images, white (mean colour > 0.5) inside: the source region on the "
        "palette's grid, the target region on the canvas's.\n"
        "Example: exemplar fill --palette painting.png --source-region sky.png --target-region "
        "area.png --canvas strokes.png -o out.png");
    app_->add_option("--palette", palette_, "The feature palette: any image (grey, RGB, RGBA)")
        ->required();
    app_->add_option("--source-region", source_region_,
                     "The area feature: white where the palette's texture is picked (palette size)")
        ->required();
    app_->add_option("--target-region", target_region_,
                     "White where the canvas is filled (canvas size)")
        ->required();
    app_->add_option("--output,-o", output_, "Result image (PNG, TIFF, EXR)")->required();
    app_->add_option("--canvas", canvas_,
                     "What is painted already (grey, RGB, RGBA): kept outside the region, "
                     "continued across its border. Without it the region is filled free-standing "
                     "on a transparent RGBA "
                     "image");
    app_->add_option("--usage", usage_,
                     "Patch usage: uniform (default: keeps sparse features), none (the "
                     "chapter's plain EM; washes sparse features out), error-budget, occurrence");
    app_->add_option("--seed", seed_, "Random seed; default 1");
    add_table_flags(
        *app_, paint::feature_fill_option_specs(), paint::FeatureFillOptions{},
        [](const paint::FeatureFillOptions& o, const paint::FeatureFillOptionSpec& spec) {
            return paint::get_option(o, spec);
        },
        numeric_values_, numeric_flags_);
    app_->add_option("--threads", threads_, "Threads (0 = all cores); the result is the same");
    app_->add_flag("--quiet,-q", quiet_, "Do not print the output path");
}

Status FillCommand::run(const Streams& streams) const {
    // Checks that need no file.
    paint::FeatureFillOptions options;
    EXEMPLAR_RETURN_IF_ERROR(set_given_table_flags(options, paint::feature_fill_option_specs(),
                                                   ModuleSetOption{}, numeric_values_,
                                                   numeric_flags_));
    auto usage = parse_usage_strategy(usage_);
    if (!usage.ok()) return invalid_argument("--" + usage.status().message());
    options.usage = *usage;
    options.seed = seed_;
    if (threads_ < 0) {
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0)");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", output_));
    EXEMPLAR_RETURN_IF_ERROR(check_output_format("--output", output_, Image(1, 1, 4), {}));

    // Inputs: the palette and its region, the canvas (if any) and the target region.
    auto palette = load_image(palette_);
    if (!palette.ok()) return palette.status();
    auto source_region = load_image(source_region_);
    if (!source_region.ok()) return source_region.status();
    auto target_region = load_image(target_region_);
    if (!target_region.ok()) return target_region.status();
    Image canvas;
    if (!canvas_.empty()) {
        auto loaded = load_image(canvas_);
        if (!loaded.ok()) return loaded.status();
        canvas = std::move(loaded).value();
    }
    if (!source_region->same_size(*palette)) {
        return invalid_argument("--source-region " + source_region_ + ": is " +
                                size_str(*source_region) + " but --palette " + palette_ + " is " +
                                size_str(*palette));
    }
    if (!canvas.empty() && !target_region->same_size(canvas)) {
        return invalid_argument("--target-region " + target_region_ + ": is " +
                                size_str(*target_region) + " but --canvas " + canvas_ + " is " +
                                size_str(canvas));
    }

    // The palette in the canvas's channels (RGBA without a canvas: transparent outside).
    const RunContext context(threads_);
    auto filled = paint::fill_with_palette(*palette, *source_region, canvas, *target_region,
                                           options, context);
    if (!filled.ok()) {
        // The library's messages start with the input's name; the file takes its place.
        std::string message = filled.status().message();
        for (const auto& [prefix, flag, file] :
             {std::tuple{"palette: ", "--palette ", palette_},
              std::tuple{"source region: ", "--source-region ", source_region_},
              std::tuple{"target region: ", "--target-region ", target_region_},
              std::tuple{"canvas: ", "--canvas ", canvas_}}) {
            const std::string p = prefix;
            if (message.rfind(p, 0) == 0) {
                return invalid_argument(flag + file + ": " + message.substr(p.size()));
            }
        }
        return filled.status();
    }
    EXEMPLAR_RETURN_IF_ERROR(save_image(*filled, output_));
    if (!quiet_) streams.out << output_ << '\n';
    return Status::ok();
}

}  // namespace exemplar::cli
