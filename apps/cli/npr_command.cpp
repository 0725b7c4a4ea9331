// `exemplar npr`: image-space stippling, hatching and halftoning of a rendered animation
// (issue 20, docs/npr.md) from the frame folders of `exemplar render --frames`.
//
// Frames are synthesized in order; each output is written atomically with its synthesis state
// (the pattern coordinates of every level, OUT.state.exr) as soon as it is done; --mp4 adds
// every frame of the range (also resumed ones, read back) to one video. A frame whose
// output and state exist is skipped (resume) and its state read back as the next frame's
// previous frame, so a resumed range gives the same bytes as an uninterrupted one. A missing
// buffer stops the run with one line naming it; the frames written so far are kept.

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "commands.hpp"
#include "exemplar/io/folders.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/npr/pattern.hpp"
#include "exemplar/npr/synthesis.hpp"
#include "exemplar/render/render.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"

namespace exemplar::cli {

namespace {

namespace fs = std::filesystem;

bool exists(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

Result<std::string> frame_path(const std::string& flag, const std::string& pattern, int n) {
    auto path = video::format_frame_path(pattern, n);
    if (!path.ok()) return invalid_argument(flag + ": " + path.status().message());
    return path;
}

// Buffer `name` of a render frame folder: NAME.png or NAME.exr.
Result<Image> load_buffer(const std::string& folder, const std::string& name, int channels) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        return io_error(folder + ": no such frame folder (from exemplar render --frames)");
    for (const char* extension : {".exr", ".png"}) {
        const std::string path = (fs::path(folder) / (name + extension)).string();
        if (!exists(path)) continue;
        auto image = load_image(path);
        if (!image.ok()) return image.status();
        if (image->channels() < channels)
            return invalid_argument(path + ": has " + std::to_string(image->channels()) +
                                    " channels, buffer '" + name + "' needs " +
                                    std::to_string(channels));
        // Light buffers in EXR are linear; the tone is taken sRGB-encoded like the PNGs
        if (std::string(extension) == ".exr" && channels == 0) return render::encode_srgb(*image);
        return image;
    }
    return io_error(folder + ": missing buffer '" + name + "' (" + name + ".png or " + name +
                    ".exr)");
}

Status same_size(const Image& image, int width, int height, const std::string& folder,
                 const std::string& name) {
    if (image.width() == width && image.height() == height) return Status::ok();
    return invalid_argument(folder + ": buffer '" + name + "' is " + std::to_string(image.width()) +
                            "x" + std::to_string(image.height()) + " but the frames are " +
                            std::to_string(width) + "x" + std::to_string(height));
}

}  // namespace

NprCommand::NprCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "npr", "Stipple, hatch or halftone a rendered animation in image space (docs/npr.md)");
    app_->footer(
        "Frame folders come from `exemplar render --frames A-B -o R/frame_%04d`. Example:\n"
        "  exemplar npr --pattern hatch.png --style hatch --frames \"R/frame_%04d\" --first 0 "
        "--last 47 -o \"O/%04d.png\"");
    app_->add_option("--pattern", pattern_, "Example pattern (grey or RGB image)")->required();
    app_->add_option("--frames", frames_,
                     "Frame folders of `exemplar render --frames`, a pattern, e.g. R/frame_%04d")
        ->required();
    app_->add_option("--first", first_, "First frame number")->required();
    app_->add_option("--last", last_, "Last frame number")->required();
    app_->add_option("--output,-o", output_, "Output pattern, PNG, e.g. O/%04d.png")->required();
    app_->add_option("--style", style_,
                     "stipple, halftone (isotropic, thresholded), hatch (oriented, thresholded) "
                     "or pattern (the synthesized pattern itself, no tone); default stipple");
    app_->add_option("--tone", tone_,
                     "Buffer giving the tone (luma, sRGB-encoded); default direct_diffuse");
    app_->add_option("--orientation", orientation_,
                     "Buffer giving the pattern's orientation (angle, rad), or none; default "
                     "orientation for hatch, none otherwise");
    app_->add_flag("--lines,!--no-lines", lines_,
                   "Draw the renderer's `lines` buffer (silhouettes, creases) in ink (default on)");
    app_->add_flag("--tone-correction,!--no-tone-correction", tone_correction_,
                   "Blur, subtract and re-threshold so the local tone matches (default on)");
    app_->add_option("--levels", levels_, "Pyramid levels (1..6, default 3)");
    app_->add_option("--patch-size", patch_size_,
                     "Initialization patch size in coarsest-level pixels (3..32, default 12)");
    app_->add_option("--coherence-weight", coherence_weight_,
                     "Weight of the temporal coherence term (0..100, default 1)");
    app_->add_option("--mp4", mp4_, "Also write the range as an MP4 (even frame sizes)");
    app_->add_option("--fps", fps_, "Frames per second of the MP4 (default 24)");
    app_->add_option("--threads,-j", threads_, "Threads (0 = all cores)");
    app_->add_option("--seed", seed_, "Random seed (same seed, same output)");
    app_->add_flag("--resume,!--no-resume", resume_,
                   "Skip frames whose output and state exist (default on)");
    app_->add_flag("--quiet,-q", quiet_, "No progress bar, no output paths");
}

Status NprCommand::run(const Streams& streams) {
    // Options, validated once
    if (style_ != "stipple" && style_ != "halftone" && style_ != "hatch" && style_ != "pattern")
        return invalid_argument("--style: '" + style_ +
                                "' is invalid (must be one of stipple, hatch, halftone, pattern)");
    if (style_ == "pattern" && app_->count("--tone") > 0)
        return invalid_argument("--tone: not used by --style pattern (it shows no tone)");
    const bool thresholded = style_ != "pattern";
    std::string orientation = orientation_.value_or(style_ == "hatch" ? "orientation" : "none");
    if (last_ < first_)
        return invalid_argument("--last: " + std::to_string(last_) + " is before --first " +
                                std::to_string(first_));
    if (!(fps_ > 0 && fps_ <= 1000))
        return invalid_argument("--fps: " + std::to_string(fps_) + " is invalid (must be 0..1000)");
    npr::PatternOptions pattern_options;
    pattern_options.levels = levels_;
    npr::SynthesisOptions options;
    options.init_patch_size = patch_size_;
    options.coherence_weight = coherence_weight_;
    options.seed = seed_;
    options.threads = threads_;
    EXEMPLAR_RETURN_IF_ERROR(npr::validate(pattern_options));
    EXEMPLAR_RETURN_IF_ERROR(npr::validate(options));
    npr::HalftoneOptions halftone_options;
    halftone_options.tone_correction = tone_correction_;

    auto probe = frame_path("--output", output_, first_);
    if (!probe.ok()) return probe.status();
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", *probe));
    EXEMPLAR_RETURN_IF_ERROR(frame_path("--frames", frames_, first_).status());

    // The pattern: the coarsest level's patches span patch-size x 2^(levels-1) pattern pixels
    auto pattern_image = load_image(pattern_);
    if (!pattern_image.ok()) return pattern_image.status();
    const int min_size = patch_size_ << (levels_ - 1);
    auto prepared = npr::prepare_pattern(*pattern_image, pattern_options, min_size, threads_);
    if (!prepared.ok())
        return invalid_argument("--pattern " + pattern_ + ": " + prepared.status().message());
    const npr::Pattern& pattern = *prepared;

    if (!mp4_.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("--mp4", mp4_));
        EXEMPLAR_RETURN_IF_ERROR(video::check_video_support(mp4_));
        if (!video::mp4_writing_supported())
            return unsupported("--mp4: this OpenCV build cannot encode MP4");
    }
    std::optional<video::Mp4Writer> mp4;  // opened at the first frame (its size)
    const auto add_to_mp4 = [&](const Image& frame) -> Status {
        if (mp4_.empty()) return Status::ok();
        if (!mp4) {
            if (frame.width() % 2 != 0 || frame.height() % 2 != 0)
                return invalid_argument("--mp4: the frames are " + std::to_string(frame.width()) +
                                        "x" + std::to_string(frame.height()) +
                                        " but MP4 needs even sizes");
            auto writer = video::Mp4Writer::open(mp4_, frame.width(), frame.height(), fps_);
            if (!writer.ok()) return writer.status();
            mp4.emplace(std::move(writer).value());
        }
        Image rgb(frame.width(), frame.height(), 3);
        for (int y = 0; y < rgb.height(); ++y)
            for (int x = 0; x < rgb.width(); ++x)
                for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = frame.at(x, y, 0);
        return mp4->write(rgb);
    };
    ProgressBar bar(streams.err, "npr", !quiet_ && streams.err_is_terminal);
    const int count = last_ - first_ + 1;
    std::optional<npr::FrameState> previous;
    // A finished frame just before the range hands over to it
    if (auto before = frame_path("--output", output_, first_ - 1);
        before.ok() && exists(*before + ".state.exr")) {
        auto packed = load_image(*before + ".state.exr");
        if (!packed.ok()) return packed.status();
        auto state = npr::unpack_state(pattern, *packed);
        if (!state.ok())
            return invalid_argument(*before + ".state.exr: " + state.status().message());
        previous = std::move(state).value();
    }
    int written = 0;
    for (int n = first_; n <= last_; ++n) {
        const std::string out_path = *frame_path("--output", output_, n);
        const std::string state_path = out_path + ".state.exr";
        if (resume_ && exists(out_path) && exists(state_path)) {
            auto packed = load_image(state_path);
            if (!packed.ok()) return packed.status();
            auto state = npr::unpack_state(pattern, *packed);
            if (!state.ok()) return invalid_argument(state_path + ": " + state.status().message());
            previous = std::move(state).value();
            if (!mp4_.empty()) {
                auto stored = load_image(out_path);
                if (!stored.ok()) return stored.status();
                EXEMPLAR_RETURN_IF_ERROR(add_to_mp4(*stored));
            }
            continue;
        }
        // This frame's buffers
        const std::string folder = *frame_path("--frames", frames_, n);
        npr::FrameInput input;
        Image tone;
        if (thresholded) {
            auto loaded = load_buffer(folder, tone_, 0);
            if (!loaded.ok()) return loaded.status();
            tone = npr::to_grey(*loaded);
            for (float& v : tone.data()) v = std::clamp(v, 0.0f, 1.0f);
            input.width = tone.width();
            input.height = tone.height();
        }
        if (orientation != "none") {
            auto angle = load_buffer(folder, orientation, 1);
            if (!angle.ok()) return angle.status();
            input.orientation = extract_channels(*angle, 0, 1);
        }
        if (previous) {
            auto flow = load_buffer(folder, "backward_flow", 2);
            if (!flow.ok()) return flow.status();
            auto disocclusion = load_buffer(folder, "disocclusion", 1);
            if (!disocclusion.ok()) return disocclusion.status();
            input.backward_flow = extract_channels(*flow, 0, 2);
            input.disocclusion = extract_channels(*disocclusion, 0, 1);
        }
        std::optional<Image> lines;
        if (lines_) {
            auto loaded = load_buffer(folder, "lines", 1);
            if (!loaded.ok()) return loaded.status();
            lines = extract_channels(*loaded, 0, 1);
        }
        // Sizes: from the tone, else from the first buffer present (the renderer always
        // writes `lines`)
        const Image* sized = !input.orientation.empty()     ? &input.orientation
                             : !input.backward_flow.empty() ? &input.backward_flow
                             : lines                        ? &*lines
                                                            : nullptr;
        if (input.width == 0 && sized != nullptr) {
            input.width = sized->width();
            input.height = sized->height();
        } else if (input.width == 0) {
            auto probe_buffer = load_buffer(folder, "lines", 1);
            if (!probe_buffer.ok()) return probe_buffer.status();
            input.width = probe_buffer->width();
            input.height = probe_buffer->height();
        }
        for (const auto& [image, name] : {std::pair{&input.orientation, orientation},
                                          {&input.backward_flow, "backward_flow"},
                                          {&input.disocclusion, "disocclusion"}}) {
            if (!image->empty())
                EXEMPLAR_RETURN_IF_ERROR(
                    same_size(*image, input.width, input.height, folder, name));
        }
        if (lines)
            EXEMPLAR_RETURN_IF_ERROR(same_size(*lines, input.width, input.height, folder, "lines"));
        if (previous && previous->coords[0].width() != input.width)
            return invalid_argument(folder + ": frame size differs from the previous frame's");

        // Synthesize, threshold, ink the lines
        auto state =
            npr::synthesize_frame(pattern, input, previous ? &*previous : nullptr, n, options);
        if (!state.ok()) return state.status();
        Image result = thresholded ? npr::halftone(state->screen, tone, halftone_options, threads_)
                                   : state->screen;
        if (lines) {
            for (int y = 0; y < result.height(); ++y)
                for (int x = 0; x < result.width(); ++x)
                    if (lines->at(x, y, 0) > 0.5f) result.at(x, y, 0) = 0.0f;
        }
        EXEMPLAR_RETURN_IF_ERROR(create_folders(fs::path(out_path).parent_path().string()));
        SaveOptions state_options;
        state_options.format = PixelFormat::Float;
        EXEMPLAR_RETURN_IF_ERROR(save_image(npr::pack_state(*state), state_path, state_options));
        EXEMPLAR_RETURN_IF_ERROR(video::write_frame(result, output_, n));
        EXEMPLAR_RETURN_IF_ERROR(add_to_mp4(result));
        ++written;
        if (!quiet_) streams.out << out_path << '\n';
        previous = std::move(state).value();
        bar.update(static_cast<double>(n - first_ + 1) / count,
                   "frame " + std::to_string(n) + " (" + std::to_string(n - first_ + 1) + "/" +
                       std::to_string(count) + ")");
    }
    bar.finish();
    return finish_frame_range(streams.out, mp4, mp4_, written, count, quiet_);
}

}  // namespace exemplar::cli
