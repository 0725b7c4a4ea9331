// LazyFluids over a range of frames on files (fluid_range.hpp): the per-frame loop of
// `exemplar fluid` and the studio's fluid job.

#include "exemplar/fluid/fluid_range.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/video/frame_sequence.hpp"

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

struct FluidExemplar::Impl {
    std::string path, alpha_path;
    Image still;
    std::optional<video::FrameSequence> frames, alpha_frames;

    // An exemplar image with its separate alpha, if any, as RGBA.
    static Result<Image> combine(Image image, const std::optional<Image>& alpha,
                                 const std::string& name, const std::string& alpha_name) {
        if (alpha) {
            if (alpha->width() != image.width() || alpha->height() != image.height()) {
                return invalid_argument(alpha_name + ": alpha is " + size_str(*alpha) +
                                        " but the exemplar is " + size_str(image));
            }
            if (image.channels() == 4) image = extract_channels(image, 0, 3);
            if (image.channels() == 1) {
                const Image grey = image;
                image = concat_channels({&grey, &grey, &grey});
            }
            const Image a = extract_channels(*alpha, 0, 1);
            return concat_channels({&image, &a});
        }
        if (image.channels() != 4) {
            return invalid_argument(name + ": the exemplar has " +
                                    std::to_string(image.channels()) +
                                    " channels but needs an alpha channel (RGBA), or give "
                                    "exemplar-alpha");
        }
        return image;
    }

    Result<Image> load_still() const {
        auto image = load_image(path);
        if (!image.ok()) return image.status();
        std::optional<Image> alpha;
        if (!alpha_path.empty()) {
            auto a = load_image(alpha_path);
            if (!a.ok()) return a.status();
            alpha = std::move(a).value();
        }
        return combine(std::move(image).value(), alpha, path, alpha_path);
    }
};

FluidExemplar::FluidExemplar(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FluidExemplar::FluidExemplar(FluidExemplar&&) noexcept = default;
FluidExemplar& FluidExemplar::operator=(FluidExemplar&&) noexcept = default;
FluidExemplar::~FluidExemplar() = default;

Result<FluidExemplar> FluidExemplar::open(const std::string& path, const std::string& alpha_path) {
    auto impl = std::make_unique<Impl>();
    impl->path = path;
    impl->alpha_path = alpha_path;
    std::error_code ec;
    if (!std::filesystem::is_directory(path, ec)) {
        auto still = impl->load_still();
        if (!still.ok()) return still.status();
        impl->still = std::move(still).value();
        return FluidExemplar(std::move(impl));
    }
    auto frames = video::FrameSequence::from_folder(path);
    if (!frames.ok()) return frames.status();
    impl->frames.emplace(std::move(frames).value());
    if (!alpha_path.empty()) {
        auto alpha = video::FrameSequence::from_folder(alpha_path);
        if (!alpha.ok()) return alpha.status();
        if (alpha->size() != impl->frames->size()) {
            return invalid_argument("exemplar-alpha: " + alpha_path + " has " +
                                    std::to_string(alpha->size()) + " frames but " + path +
                                    " has " + std::to_string(impl->frames->size()));
        }
        impl->alpha_frames.emplace(std::move(alpha).value());
    }
    FluidExemplar exemplar(std::move(impl));
    // The first frame now (channels, alpha), so a bad exemplar fails up front.
    auto first = exemplar.frame(0);
    if (!first.ok()) return first.status();
    return exemplar;
}

int FluidExemplar::size() const {
    return impl_->frames ? impl_->frames->size() : 1;
}

std::vector<std::string> FluidExemplar::files() const {
    if (!impl_->frames) {
        std::vector<std::string> files{impl_->path};
        if (!impl_->alpha_path.empty()) files.push_back(impl_->alpha_path);
        return files;
    }
    std::vector<std::string> files;
    for (const auto* sequence : {&impl_->frames, &impl_->alpha_frames}) {
        if (!*sequence) continue;
        for (int k = 0; k < (*sequence)->size(); ++k) files.push_back((*sequence)->frame_name(k));
    }
    return files;
}

Result<Image> FluidExemplar::frame(int n) {
    if (!impl_->frames) return impl_->still;
    const int m = impl_->frames->size();
    const int index = ((n % m) + m) % m;
    auto image = impl_->frames->read(index);
    if (!image.ok()) return image.status();
    std::optional<Image> alpha;
    if (impl_->alpha_frames) {
        auto a = impl_->alpha_frames->read(index);
        if (!a.ok()) return a.status();
        alpha = std::move(a).value();
    }
    return Impl::combine(std::move(image).value(), alpha, impl_->frames->frame_name(index),
                         impl_->alpha_frames ? impl_->alpha_frames->frame_name(index) : "");
}

void FluidExemplar::use_in(FluidRange& range) {
    range.exemplar = [this](int n) { return frame(n); };
    range.exemplar_sequence = size() > 1;
}

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
            auto frame =
                synthesize_fluid_frame(input, options, context.part(n - range.first, 1.0, count));
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
