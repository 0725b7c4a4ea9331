// `exemplar flow`: DIS optical flow between two frames, optionally the backward flow and the
// occlusion mask of the forward-backward consistency test (docs/video.md).

#include <cmath>
#include <string>

#include "commands.hpp"
#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/video/occlusion.hpp"
#include "exemplar/video/optical_flow.hpp"
#include "output_files.hpp"

namespace exemplar::cli {

FlowCommand::FlowCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "flow", "Estimate optical flow between two frames (OpenCV DIS) and its occlusions");
    app_->footer(
        "Flow convention: f(x) maps pixel x of --from to x + f(x) in --to.\n"
        "Example: exemplar flow --from f0.png --to f1.png -o fwd.flo --backward bwd.flo "
        "--occlusion occ.png");
    app_->add_option("--from", from_, "Frame t")->required();
    app_->add_option("--to", to_, "Frame t+1 (same size)")->required();
    app_->add_option("--output,-o", output_, "Forward flow t -> t+1: .flo or .exr")->required();
    app_->add_option("--backward", backward_, "Also write the backward flow t+1 -> t (.flo/.exr)");
    app_->add_option("--occlusion", occlusion_,
                     "Also write the occlusion mask of frame t (1 = fails the forward-backward "
                     "test); needs no --backward");
    app_->add_option("--epsilon", epsilon_,
                     "Tolerance of the occlusion test in px^2 (squared round-trip distance); "
                     "default 2 (Benard et al. 2013), 4..10 suit estimated flow");
    app_->add_option("--preset", preset_, "DIS preset: ultrafast, fast or medium (default)");
    app_->add_flag("--quiet,-q", quiet_, "Do not print the output paths");
}

Status FlowCommand::run(const Streams& streams) const {
    // Checks that need no file.
    auto preset = video::parse_flow_preset(preset_);
    if (!preset.ok()) return invalid_argument("--preset: " + preset.status().message());
    const video::OcclusionOptions occlusion_options{epsilon_};
    if (!(std::isfinite(epsilon_) && epsilon_ > 0.0f)) {
        return invalid_argument("--epsilon: " + std::to_string(epsilon_) +
                                " is invalid (must be > 0, in px^2)");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", output_));
    if (!backward_.empty()) EXEMPLAR_RETURN_IF_ERROR(check_output_path("--backward", backward_));
    if (!occlusion_.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("--occlusion", occlusion_));
    }

    // Frames and flow.
    auto from = load_image(from_);
    if (!from.ok()) return from.status();
    auto to = load_image(to_);
    if (!to.ok()) return to.status();
    if (!from->same_size(*to)) {
        return invalid_argument("--from " + from_ + " is " + std::to_string(from->width()) + "x" +
                                std::to_string(from->height()) + " but --to " + to_ + " is " +
                                std::to_string(to->width()) + "x" + std::to_string(to->height()));
    }
    auto forward = video::estimate_flow(*from, *to, {*preset});
    if (!forward.ok()) return forward.status();
    Image backward;
    if (!backward_.empty() || !occlusion_.empty()) {
        auto flow = video::estimate_flow(*to, *from, {*preset});
        if (!flow.ok()) return flow.status();
        backward = std::move(flow).value();
    }
    Image mask;
    if (!occlusion_.empty()) {
        auto occluded = video::occlusion_mask(*forward, backward, occlusion_options);
        if (!occluded.ok()) return occluded.status();
        mask = std::move(occluded).value();
    }

    // Outputs, each atomic.
    EXEMPLAR_RETURN_IF_ERROR(save_flow(*forward, output_));
    if (!quiet_) streams.out << output_ << '\n';
    if (!backward_.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(save_flow(backward, backward_));
        if (!quiet_) streams.out << backward_ << '\n';
    }
    if (!occlusion_.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(save_image(mask, occlusion_));
        if (!quiet_) streams.out << occlusion_ << '\n';
    }
    return Status::ok();
}

}  // namespace exemplar::cli
