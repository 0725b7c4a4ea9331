// `exemplar render`: a scene (built-in or JSON file) path-traced into light-path buffers, written
// as one multi-layer EXR or one file per buffer in a folder.

#include <filesystem>
#include <map>

#include "commands.hpp"
#include "exemplar/render/render.hpp"
#include "exemplar/render/scene.hpp"
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

}  // namespace

RenderCommand::RenderCommand(CLI::App& parent) {
    std::string names;
    for (const auto& name : render::builtin_scene_names())
        names += (names.empty() ? "" : ", ") + name;
    app_ = parent.add_subcommand("render",
                                 "Path-trace a scene into light-path buffers (StyLit guides)");
    app_->footer(
        "Example: exemplar render --scene sphere-on-table --width 600 --height 456 --spp 64 "
        "--output out/sphere.exr\nBuffers: fullgi, direct_diffuse (LDE), direct_specular (LSE), "
        "indirect_diffuse, diffuse_bounces (LD{1,2}E), diffuse_interreflection (L.*DDE), normal, "
        "depth, object_id, material_id, alpha (docs/render.md).");
    app_->add_option("--scene", scene_, "A scene JSON file, or a built-in scene: " + names)
        ->required();
    app_->add_option("--width", options_.width, "Image width in pixels, 1..16384 (default 600)");
    app_->add_option("--height", options_.height, "Image height in pixels, 1..16384 (default 456)");
    app_->add_option("--spp", options_.samples_per_pixel,
                     "Samples (paths) per pixel, 1..65536 (default 64)");
    app_->add_option("--max-bounces", options_.max_bounces,
                     "Surface reflections per path, 1..64 (default 6)");
    app_->add_option("--seed", options_.seed, "Seed of the random numbers (default 1)");
    app_->add_option("--output,-o", output_,
                     "OUT.exr: one multi-layer EXR; otherwise a folder (created if missing) with "
                     "one file per buffer")
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
    const bool one_exr = lowercase_extension(output_) == ".exr";
    std::error_code ec;
    if (one_exr) {
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", output_));
    } else {
        if (fs::exists(output_, ec) && !fs::is_directory(output_, ec)) {
            return invalid_argument("--output " + output_ +
                                    ": is a file (give a folder, or a name ending in .exr)");
        }
        fs::path parent = fs::path(output_).parent_path();
        if (parent.empty()) parent = ".";
        if (!fs::is_directory(parent, ec)) {
            return io_error("--output " + output_ + ": folder " + parent.string() +
                            " does not exist");
        }
    }

    // The scene: a file if one exists by that name (or it looks like one), else a built-in.
    const bool is_file = fs::exists(scene_, ec) || lowercase_extension(scene_) == ".json";
    auto scene = is_file ? render::load_scene(scene_) : render::builtin_scene(scene_);
    if (!scene.ok()) {
        if (is_file) return scene.status();
        return Status(scene.status().code(), "--scene: " + scene.status().message());
    }

    // Run.
    ProgressBar bar(streams.err, "render", !quiet_ && streams.err_is_terminal);
    RunContext context(threads_);
    context.progress = [&bar](const ProgressEvent& event) { bar.update(event); };
    auto buffers = render::render(*scene, options_, context);
    bar.finish();
    if (!buffers.ok()) return with_flag_names(buffers.status());

    // Write (each file atomically).
    if (one_exr) {
        EXEMPLAR_RETURN_IF_ERROR(render::save_buffers_to_exr(*buffers, output_));
    } else {
        fs::create_directory(output_, ec);
        if (ec)
            return io_error("--output " + output_ + ": cannot create folder (" + ec.message() +
                            ")");
        EXEMPLAR_RETURN_IF_ERROR(render::save_buffers_to_folder(
            *buffers, output_,
            format_ == "png" ? render::BufferFileFormat::Png : render::BufferFileFormat::Exr));
    }
    if (!quiet_) streams.out << output_ << '\n';
    return Status::ok();
}

}  // namespace exemplar::cli
