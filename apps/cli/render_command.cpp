// `exemplar render`: a scene (built-in or JSON file) path-traced into light-path buffers, written
// as one multi-layer EXR or one file per buffer in a folder; for animations, per frame with
// motion vectors, occlusion masks, orientation and lines, to a printf-style output pattern.

#include <charconv>
#include <filesystem>
#include <map>

#include "commands.hpp"
#include "exemplar/io/folders.hpp"
#include "exemplar/render/animation.hpp"
#include "exemplar/render/render.hpp"
#include "exemplar/render/scene.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"

namespace exemplar::cli {

namespace {

namespace fs = std::filesystem;

// The library names RenderOptions fields in its messages; the user knows the flags.
Status with_flag_names(const Status& status) {
    static const std::map<std::string, std::string> flags = {{"width", "--width"},
                                                             {"height", "--height"},
                                                             {"samples_per_pixel", "--spp"},
                                                             {"max_bounces", "--max-bounces"}};
    for (const auto& [field, flag] : flags) {
        if (status.message().rfind(field + ":", 0) == 0) {
            return Status(status.code(), flag + status.message().substr(field.size()));
        }
    }
    return status;
}

constexpr int kMaxFrame = 1000000;

// "N" or "A-B" (non-negative integers, A <= B).
Status parse_frame_range(const std::string& flag, const std::string& text, int& first, int& last) {
    const auto bad = [&] {
        return invalid_argument(flag + ": \"" + text +
                                "\" is invalid (expected A-B or N, integers 0.." +
                                std::to_string(kMaxFrame) + ", A <= B)");
    };
    const std::size_t dash = text.find('-');
    const auto number = [](std::string_view part, int& out) {
        const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), out);
        return !part.empty() && ec == std::errc() && end == part.data() + part.size() && out >= 0 &&
               out <= kMaxFrame;
    };
    const std::string_view all(text);
    if (dash == std::string::npos) {
        if (!number(all, first)) return bad();
        last = first;
    } else if (!number(all.substr(0, dash), first) || !number(all.substr(dash + 1), last) ||
               first > last) {
        return bad();
    }
    return Status::ok();
}

// Checks that `output` (an .exr file, or a folder to create) can be written.
Status check_output(const std::string& output, bool one_exr) {
    std::error_code ec;
    if (one_exr) return check_output_path("--output", output);
    if (fs::exists(output, ec) && !fs::is_directory(output, ec)) {
        return invalid_argument("--output " + output +
                                ": is a file (give a folder, or a name ending in .exr)");
    }
    if (const Status can = check_folders(output); !can.is_ok()) {
        return Status(can.code(), "--output " + can.message());
    }
    return Status::ok();
}

// Writes the buffers of one render or frame (each file atomically).
Status write_buffers(const render::RenderBuffers& buffers, const std::string& output, bool one_exr,
                     const std::string& format) {
    if (one_exr) return render::save_buffers_to_exr(buffers, output);
    if (const Status made = create_folders(output); !made.is_ok()) {
        return Status(made.code(), "--output " + made.message());
    }
    return render::save_buffers_to_folder(
        buffers, output,
        format == "png" ? render::BufferFileFormat::Png : render::BufferFileFormat::Exr);
}

}  // namespace

RenderCommand::RenderCommand(CLI::App& parent) {
    std::string names;
    for (const auto& name : render::builtin_scene_names())
        names += (names.empty() ? "" : ", ") + name;
    app_ = parent.add_subcommand("render",
                                 "Path-trace a scene into light-path buffers (StyLit guides)");
    app_->footer(
        "Example: exemplar render --scene sphere-on-table --width 600 --height 456 --spp 64 "
        "--output out/sphere.exr\n"
        "Animation: exemplar render --scene examples/render/spot-turntable.json --frames 0-47 "
        "--output out/spot_%04d.exr\nBuffers: fullgi, direct_diffuse (LDE), direct_specular (LSE), "
        "indirect_diffuse, diffuse_bounces (LD{1,2}E), diffuse_interreflection (L.*DDE), normal, "
        "depth, object_id, material_id, alpha, orientation, lines; animations add forward_flow, "
        "backward_flow, occlusion, disocclusion (docs/render.md).");
    app_->add_option("--scene", scene_, "A scene JSON file, or a built-in scene: " + names)
        ->required();
    app_->add_option("--width", options_.width, "Image width in pixels, 1..16384 (default 600)");
    app_->add_option("--height", options_.height, "Image height in pixels, 1..16384 (default 456)");
    app_->add_option("--spp", options_.samples_per_pixel,
                     "Samples (paths) per pixel, 1..65536 (default 64)");
    app_->add_option("--max-bounces", options_.max_bounces,
                     "Surface reflections per path, 1..64 (default 6)");
    app_->add_option("--seed", options_.seed, "Seed of the random numbers (default 1)");
    app_->add_option("--frames", frames_,
                     "Animation frames A-B (inclusive): per frame, the buffers plus motion "
                     "vectors, occlusion, orientation and lines (default: the scene's \"frames\")");
    app_->add_option("--frame", frame_, "One animation frame N (same as --frames N-N)");
    app_->add_option("--output,-o", output_,
                     "OUT.exr: one multi-layer EXR; otherwise a folder (created if missing) with "
                     "one file per buffer. Animations: a printf pattern such as "
                     "out/frame_%04d.exr or out/frame_%04d (one folder per frame)")
        ->required();
    app_->add_option("--format", format_,
                     "Files in an output folder: png (8-bit, sRGB-encoded light buffers; default) "
                     "or exr (float, linear)");
    app_->add_option("--threads,-j", threads_, "Threads; 0 = all cores (default)");
    app_->add_flag("--quiet,-q", quiet_, "No progress bar and no output path");
}

Status RenderCommand::run(const Streams& streams) const {
    // Checks that need no file.
    EXEMPLAR_RETURN_IF_ERROR(with_flag_names(render::validate(options_)));
    if (threads_ < 0) {
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0; 0 = all cores)");
    }
    if (format_ != "png" && format_ != "exr") {
        return invalid_argument("--format: \"" + format_ + "\" is invalid (must be png or exr)");
    }
    int first = 0, last = 0;
    const bool frame_given = app_->count("--frame") > 0;
    const bool frames_given = !frames_.empty() || frame_given;
    if (!frames_.empty() && frame_given) {
        return invalid_argument("--frame: cannot be combined with --frames");
    }
    if (!frames_.empty())
        EXEMPLAR_RETURN_IF_ERROR(parse_frame_range("--frames", frames_, first, last));
    if (frame_given) {
        EXEMPLAR_RETURN_IF_ERROR(parse_frame_range("--frame", std::to_string(frame_), first, last));
    }
    const bool one_exr = lowercase_extension(output_) == ".exr";

    // The scene: a file if one exists by that name (or it looks like one), else a built-in.
    std::error_code ec;
    const bool is_file = fs::exists(scene_, ec) || lowercase_extension(scene_) == ".json";
    auto animation = is_file ? render::load_animation(scene_) : render::builtin_animation(scene_);
    if (!animation.ok()) {
        if (is_file) return animation.status();
        return Status(animation.status().code(), "--scene: " + animation.status().message());
    }
    const bool animate = frames_given || animation->is_animated();
    if (animate && !frames_given) {
        if (!animation->frames) {
            return invalid_argument("--frames: required: " + animation->source +
                                    " is animated and names no \"frames\"");
        }
        first = animation->frames->first;
        last = animation->frames->second;
    }

    // Output names: a still, or one per frame from a printf pattern.
    const bool pattern = output_.find('%') != std::string::npos;
    const auto output_of = [&](int frame) -> Result<std::string> {
        if (!pattern) return output_;
        auto path = video::format_frame_path(output_, frame);
        if (!path.ok()) return Status(path.status().code(), "--output: " + path.status().message());
        return path;
    };
    if (animate && !pattern && last > first) {
        return invalid_argument("--output " + output_ +
                                ": needs a frame number pattern for several frames (e.g. "
                                "out/frame_%04d.exr or out/frame_%04d)");
    }
    if (!animate && pattern) {
        auto path = output_of(0);
        if (!path.ok()) return path.status();
        return invalid_argument("--output " + output_ +
                                ": is a frame pattern, but the scene is a still (give --frames)");
    }
    for (int frame : {first, last}) {
        auto path = output_of(frame);
        if (!path.ok()) return path.status();
        EXEMPLAR_RETURN_IF_ERROR(check_output(*path, one_exr));
    }

    ProgressBar bar(streams.err, "render", !quiet_ && streams.err_is_terminal);
    RunContext context(threads_);
    if (animate) {
        const int count = last - first + 1;
        for (int frame = first; frame <= last; ++frame) {
            const std::string stage = "frame " + std::to_string(frame);
            context.progress = [&bar, &stage, frame, first, count](const ProgressEvent& event) {
                ProgressEvent overall = event;
                overall.stage = stage;
                overall.fraction = (static_cast<double>(frame - first) + event.fraction) /
                                   static_cast<double>(count);
                bar.update(overall);
            };
            auto buffers = render::render_frame(*animation, frame, options_, context);
            if (!buffers.ok()) {
                bar.finish();
                return with_flag_names(buffers.status());
            }
            const std::string path = *output_of(frame);
            EXEMPLAR_RETURN_IF_ERROR(write_buffers(*buffers, path, one_exr, format_));
            if (!quiet_) streams.out << path << '\n';
        }
        bar.finish();
        return Status::ok();
    }

    context.progress = [&bar](const ProgressEvent& event) { bar.update(event); };
    auto buffers = render::render(animation->at(0), options_, context);
    bar.finish();
    if (!buffers.ok()) return with_flag_names(buffers.status());
    EXEMPLAR_RETURN_IF_ERROR(write_buffers(*buffers, output_, one_exr, format_));
    if (!quiet_) streams.out << output_ << '\n';
    return Status::ok();
}

}  // namespace exemplar::cli
