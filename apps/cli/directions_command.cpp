// `exemplar directions`: the signed direction field of an exemplar (Brushables §3.1, docs/paint.md)
// as an angle field for `exemplar paint --source-directions`, and a direction-wheel preview.

#include <string>

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/paint/directions.hpp"
#include "output_files.hpp"

namespace exemplar::cli {

namespace {

bool ends_with_exr(const std::string& path) {
    return path.size() >= 4 && (path.ends_with(".exr") || path.ends_with(".EXR"));
}

}  // namespace

DirectionsCommand::DirectionsCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "directions", "Signed direction field of an exemplar (edge tangent flow, Brushables)");
    app_->footer(
        "The field is one channel \"angle\": radians in (-pi, pi], counter-clockwise on screen, "
        "0 = right.\nExample: exemplar directions grass.png -o grass_dirs.exr --preview "
        "grass_dirs.png");
    app_->add_option("input", input_, "Exemplar image")->required();
    app_->add_option("--output,-o", output_, "Direction field (.exr, channel \"angle\")")
        ->required();
    app_->add_option("--radius", options_.radius_px,
                     "Radius of the edge tangent flow filter in px (1..100); default 10, about 35 "
                     "for noisy textures (Brushables 3.4)");
    app_->add_option("--iterations", options_.iterations,
                     "Edge tangent flow iterations (0..10); default 3");
    app_->add_option("--gradient-sigma", options_.gradient_sigma_px,
                     "Blur before the gradients in px (0..10); default 1");
    app_->add_flag("!--no-harmonize", options_.harmonize_signs,
                   "Skip the sign harmonization (plain ETF: signs flip between stripes)");
    app_->add_option("--preview", preview_, "Also write the field in direction-wheel colours");
    app_->add_option("--threads", threads_, "Threads (0 = all cores); the result is the same");
    app_->add_flag("--quiet,-q", quiet_, "Do not print the output paths");
}

Status DirectionsCommand::run(const Streams& streams) const {
    // Checks that need no file.
    if (Status s = paint::validate(options_); !s.is_ok())
        return invalid_argument("--" + s.message());
    if (threads_ < 0) {
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0)");
    }
    if (!ends_with_exr(output_)) {
        return invalid_argument("--output " + output_ +
                                ": the direction field must be an .exr file (it holds angles)");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", output_));
    if (!preview_.empty()) EXEMPLAR_RETURN_IF_ERROR(check_output_path("--preview", preview_));

    // Analysis.
    auto image = load_image(input_);
    if (!image.ok()) return image.status();
    auto field = paint::analyze_directions(*image, options_, threads_);
    if (!field.ok()) return field.status();

    // Outputs, each atomic.
    EXEMPLAR_RETURN_IF_ERROR(save_image(paint::direction_angles(*field), output_));
    if (!quiet_) streams.out << output_ << '\n';
    if (!preview_.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(save_image(paint::direction_wheel(*field), preview_));
        if (!quiet_) streams.out << preview_ << '\n';
    }
    return Status::ok();
}

}  // namespace exemplar::cli
