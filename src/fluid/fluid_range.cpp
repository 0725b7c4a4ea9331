// LazyFluids over a range of frames on files (fluid_range.hpp): the per-frame loop of
// `exemplar fluid` and the studio's fluid job.

#include "exemplar/fluid/fluid_range.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"

namespace exemplar::fluid {

namespace {

bool exists(const std::string& path) {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}

// Motion file `path`, which must be W x H like the alpha masks.
Result<Image> load_motion(const std::string& path, const std::string& layer, const Image& alpha) {
    auto motion = load_flow(path, layer);
    if (!motion.ok()) return motion.status();
    if (motion->width() != alpha.width() || motion->height() != alpha.height()) {
        return invalid_argument(path + ": motion is " + size_str(*motion) +
                                " but the alpha masks are " + size_str(alpha));
    }
    return motion;
}

// The output of the frame before the range when it and its motion to `first` exist.
Result<std::optional<Image>> output_before(const FluidRange& range) {
    auto before = range.output_file(range.first - 1);
    auto before_motion = range.motion_file(range.first - 1);
    if (!before.ok() || !before_motion.ok() || !exists(*before) || !exists(*before_motion)) {
        return std::optional<Image>();
    }
    auto image = load_image(*before);
    if (!image.ok()) return image.status();
    return std::optional<Image>(std::move(image).value());
}

}  // namespace

Status check_fluid_range(const FluidRange& range) {
    if (range.last < range.first) {
        return invalid_argument("last: " + std::to_string(range.last) + " is before first " +
                                std::to_string(range.first));
    }
    if (!range.exemplar || !range.alpha_file || !range.motion_file || !range.output_file) {
        return invalid_argument("the range needs an exemplar and alpha, motion and output files");
    }
    const std::string span = std::to_string(range.first) + ".." + std::to_string(range.last);
    for (int n = range.first; n <= range.last; ++n) {
        auto alpha = range.alpha_file(n);
        if (!alpha.ok()) return alpha.status();
        if (!exists(*alpha)) {
            return io_error(*alpha + ": no such file (alpha of frame " + std::to_string(n) +
                            " of " + span + ")");
        }
        if (n == range.last) break;
        auto motion = range.motion_file(n);
        if (!motion.ok()) return motion.status();
        if (!exists(*motion)) {
            return io_error(*motion + ": no such file (motion of frame " + std::to_string(n) +
                            " to " + std::to_string(n + 1) + ")");
        }
    }
    return Status::ok();
}

Status synthesize_fluid_range(const FluidRange& range, const FluidOptions& options,
                              const RunContext& context) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    EXEMPLAR_RETURN_IF_ERROR(check_fluid_range(range));
    auto first_alpha_path = range.alpha_file(range.first);
    if (!first_alpha_path.ok()) return first_alpha_path.status();
    auto first_alpha = load_image(*first_alpha_path);
    if (!first_alpha.ok()) return first_alpha.status();
    const int W = first_alpha->width(), H = first_alpha->height();
    auto before = output_before(range);
    if (!before.ok()) return before.status();
    std::optional<Image> previous = std::move(before).value();  // frame n − 1 as stored

    const int count = range.last - range.first + 1;
    for (int n = range.first; n <= range.last; ++n) {
        if (context.cancelled()) return cancelled();
        auto out_path = range.output_file(n);
        if (!out_path.ok()) return out_path.status();
        const bool skip = range.resume && exists(*out_path);
        if (!skip) {
            // Load this frame's inputs and check them against each other.
            auto alpha_path = range.alpha_file(n);
            if (!alpha_path.ok()) return alpha_path.status();
            auto alpha = load_image(*alpha_path);
            if (!alpha.ok()) return alpha.status();
            if (alpha->width() != W || alpha->height() != H) {
                return invalid_argument(*alpha_path + ": alpha is " + size_str(*alpha) +
                                        " but frame " + std::to_string(range.first) + "'s is " +
                                        size_str(*first_alpha));
            }
            std::optional<Image> previous_motion;
            if (previous) {
                auto motion_path = range.motion_file(n - 1);
                if (!motion_path.ok()) return motion_path.status();
                auto motion = load_motion(*motion_path, range.motion_layer, *alpha);
                if (!motion.ok()) return motion.status();
                if (previous->width() != W || previous->height() != H ||
                    previous->channels() != 4) {
                    auto previous_path = range.output_file(n - 1);
                    return invalid_argument(
                        (previous_path.ok() ? *previous_path : std::string("previous output")) +
                        ": previous output is " + size_str(*previous) + " with " +
                        std::to_string(previous->channels()) + " channels but the frames are " +
                        size_str(*alpha) + " RGBA");
                }
                previous_motion = std::move(motion).value();
            }
            std::optional<Image> own_motion;
            if (options.motion_blur > 0.0f && n < range.last) {
                auto motion_path = range.motion_file(n);
                if (!motion_path.ok()) return motion_path.status();
                auto motion = load_motion(*motion_path, range.motion_layer, *alpha);
                if (!motion.ok()) return motion.status();
                own_motion = std::move(motion).value();
            }
            auto exemplar = range.exemplar(n);
            if (!exemplar.ok()) return exemplar.status();
            std::optional<Image> previous_exemplar;
            if (previous && range.exemplar_sequence) {
                auto e = range.exemplar(n - 1);
                if (!e.ok()) return e.status();
                previous_exemplar = std::move(e).value();
            }

            FluidFrameInput input;
            input.exemplar = &*exemplar;
            input.previous_exemplar = previous_exemplar ? &*previous_exemplar : nullptr;
            input.target_alpha = &*alpha;
            input.previous_output = previous ? &*previous : nullptr;
            input.previous_motion = previous_motion ? &*previous_motion : nullptr;
            input.motion = own_motion ? &*own_motion : nullptr;
            RunContext frame_context = context;
            frame_context.progress = [&](const ProgressEvent& event) {
                ProgressEvent overall = event;
                overall.fraction = (static_cast<double>(n - range.first) + event.fraction) / count;
                context.report(overall);
            };
            auto frame = synthesize_fluid_frame(input, options, frame_context);
            if (!frame.ok()) return frame.status();
            EXEMPLAR_RETURN_IF_ERROR(save_image(frame->rgba, *out_path));
        }
        // The next frame continues from this one as stored.
        auto stored = load_image(*out_path);
        if (!stored.ok()) return stored.status();
        previous = std::move(stored).value();
        if (range.on_frame) EXEMPLAR_RETURN_IF_ERROR(range.on_frame(n, *previous, !skip));
    }
    return Status::ok();
}

}  // namespace exemplar::fluid
