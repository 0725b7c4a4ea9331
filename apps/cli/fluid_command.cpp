// `exemplar fluid`: LazyFluids (Jamriška et al. 2015) over a range of frames, and
// `exemplar fluid simulate`: targets from the built-in stable-fluids solver (docs/fluid.md).
//
// The frames are the library's range driver's (fluid::synthesize_fluid_range: in order, each
// written atomically and read back as the next one's previous frame, resume); this file parses
// the flags, opens the exemplar (a still or a sequence) and the MP4, and prints.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "exemplar/fluid/fluid_range.hpp"
#include "exemplar/fluid/lazy_fluids.hpp"
#include "exemplar/fluid/simulate.hpp"
#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/folders.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "json_file.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"

namespace exemplar::cli {

namespace {

namespace fs = std::filesystem;

// A job-file path relative to the job file's folder.
std::string relative_to(const std::string& job, const std::string& path) {
    if (path.empty() || fs::path(path).is_absolute()) return path;
    return (fs::path(job).parent_path() / path).string();
}

Result<std::string> frame_file(const std::string& flag, const std::string& pattern, int n) {
    auto path = video::format_frame_path(pattern, n);
    if (!path.ok()) return invalid_argument(flag + ": " + path.status().message());
    return path;
}

// A scene JSON file: {"width":..,"height":..,"emitters":[{"position":[x,y],"radius":r,
// "rate":q,"velocity":[u,v]}],"obstacles":[{"position":[x,y],"radius":r}],"gravity":[gx,gy],
// "buoyancy":b,"vorticity":e,"viscosity":n,"diffusion":k,"density-decay":d,
// "warmup-frames":w,"turbulence":t,"seed":s}; width/height default to the flags'.
Result<fluid::FluidScene> read_scene(const std::string& path, int width, int height) {
    auto doc = read_json_object(path);
    if (!doc.ok()) return doc.status();
    fluid::FluidScene scene;
    scene.width = width;
    scene.height = height;
    auto number = [&](const nlohmann::json& v, const std::string& key, float& out) {
        if (!v.is_number()) return type_error(path, key, "a number");
        out = v.get<float>();
        return Status::ok();
    };
    auto pair = [&](const nlohmann::json& v, const std::string& key, float& a, float& b) {
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
            return type_error(path, key, "an array of two numbers");
        }
        a = v[0].get<float>();
        b = v[1].get<float>();
        return Status::ok();
    };
    for (const auto& [raw, value] : doc->items()) {
        const std::string key = canonical_key(raw);
        Status s;
        if (key == "width" || key == "height" || key == "warmup-frames") {
            if (!value.is_number_integer()) {
                s = type_error(path, raw, "an integer");
            } else if (key == "width") {
                scene.width = value.get<int>();
            } else if (key == "height") {
                scene.height = value.get<int>();
            } else {
                scene.warmup_frames = value.get<int>();
            }
        } else if (key == "seed") {
            if (!value.is_number_unsigned()) {
                s = type_error(path, raw, "a non-negative integer");
            } else {
                scene.seed = value.get<std::uint64_t>();
            }
        } else if (key == "gravity") {
            s = pair(value, raw, scene.gravity_x, scene.gravity_y);
        } else if (key == "buoyancy") {
            s = number(value, raw, scene.buoyancy);
        } else if (key == "vorticity") {
            s = number(value, raw, scene.vorticity);
        } else if (key == "viscosity") {
            s = number(value, raw, scene.viscosity);
        } else if (key == "diffusion") {
            s = number(value, raw, scene.diffusion);
        } else if (key == "density-decay") {
            s = number(value, raw, scene.density_decay);
        } else if (key == "turbulence") {
            s = number(value, raw, scene.turbulence);
        } else if (key == "emitters" || key == "obstacles") {
            if (!value.is_array()) {
                s = type_error(path, raw, "an array of objects");
            } else {
                for (std::size_t i = 0; i < value.size() && s.is_ok(); ++i) {
                    const nlohmann::json& item = value[i];
                    const std::string at = raw + "[" + std::to_string(i) + "]";
                    if (!item.is_object()) {
                        s = type_error(path, at, "an object");
                        break;
                    }
                    fluid::Emitter e;
                    fluid::Obstacle o;
                    for (const auto& [mraw, mv] : item.items()) {
                        const std::string m = canonical_key(mraw);
                        const std::string name = at + "." + mraw;
                        if (m == "position") {
                            s = key == "emitters" ? pair(mv, name, e.x_px, e.y_px)
                                                  : pair(mv, name, o.x_px, o.y_px);
                        } else if (m == "radius") {
                            s = number(mv, name, key == "emitters" ? e.radius_px : o.radius_px);
                        } else if (m == "rate" && key == "emitters") {
                            s = number(mv, name, e.rate);
                        } else if (m == "velocity" && key == "emitters") {
                            s = pair(mv, name, e.velocity_x, e.velocity_y);
                        } else {
                            s = invalid_argument(path + ": unknown key '" + name + "'");
                        }
                        if (!s.is_ok()) break;
                    }
                    if (key == "emitters") {
                        scene.emitters.push_back(e);
                    } else {
                        scene.obstacles.push_back(o);
                    }
                }
            }
        } else {
            s = invalid_argument(path + ": unknown key '" + raw + "'");
        }
        if (!s.is_ok()) return s;
    }
    if (Status s = fluid::validate(scene); !s.is_ok())
        return invalid_argument(path + ": " + s.message());
    return scene;
}

}  // namespace

FluidCommand::FluidCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "fluid",
        "Transfer a fluid exemplar onto fluid animations (LazyFluids, Jamriska et al. 2015)");
    app_->footer(
        "Targets: per-frame alpha masks and forward motion (.flo or EXR, frame t -> t+1, pixels);\n"
        "`exemplar fluid simulate` makes them. See docs/fluid.md. Example:\n"
        "  exemplar fluid simulate --scene plume --width 256 --height 256 --frames 60 -o sim\n"
        "  exemplar fluid --exemplar fire.png --alpha sim/alpha/%04d.png --motion "
        "sim/motion/%04d.flo --first 0 --last 59 -o out/%04d.png");
    app_->add_option("--config", config_,
                     "Job file (JSON) with the same keys as the flags; flags override it");
    app_->add_option("--exemplar", exemplar_,
                     "Exemplar: an RGBA image, or a folder of RGBA frames (output frame t uses "
                     "frame t mod their count)");
    app_->add_option("--exemplar-alpha", exemplar_alpha_,
                     "Alpha of an RGB exemplar: an image (or a folder of frames), channel 0");
    app_->add_option("--alpha", alpha_, "Target alpha masks, a pattern, e.g. sim/alpha/%04d.png");
    app_->add_option("--motion", motion_,
                     "Target motion, a pattern of .flo or EXR files (frame t -> t+1, pixels)");
    app_->add_option("--motion-layer", motion_layer_,
                     "EXR layer of the motion files (e.g. motion)");
    app_->add_option("--first", first_, "First frame number");
    app_->add_option("--last", last_, "Last frame number");
    app_->add_option("--output,-o", output_, "Output pattern, RGBA PNG or EXR, e.g. out/%04d.png");
    app_->add_option("--mp4", mp4_, "Also write the range as an MP4 (over black)");
    app_->add_option("--fps", fps_, "Frames per second of the MP4 (default 24)");
    for (const fluid::FluidOptionSpec& spec : fluid::fluid_option_specs()) {
        const std::string name(spec.name);
        numeric_flags_[name] =
            app_->add_option("--" + name, numeric_values_[name], std::string(spec.doc));
    }
    app_->add_option("--usage", usage_,
                     "Patch usage: uniform (LazyFluids, default) or none (plain nearest "
                     "neighbours, which wash out; for comparisons)");
    app_->add_flag("--rotations,!--no-rotations", rotations_,
                   "Add the exemplar rotated by 90, 180 and 270 degrees (default off)");
    app_->add_option("--threads,-j", threads_, "Threads (0 = all cores)");
    seed_flag_ = app_->add_option("--seed", seed_, "Random seed (same seed, same output)");
    app_->add_flag("--resume,!--no-resume", resume_,
                   "Skip frames whose output exists (default on)");
    app_->add_flag("--quiet,-q", quiet_, "No progress bar, no output paths");

    simulate_ = app_->add_subcommand(
        "simulate", "Simulate a 2D fluid (stable fluids) into target alpha masks and motion");
    simulate_->add_option("--scene", scene_, "plume (built in) or a scene JSON file")->required();
    simulate_->add_option("--width", width_, "Frame width, pixels (8..8192)");
    simulate_->add_option("--height", height_, "Frame height, pixels (8..8192)");
    simulate_->add_option("--frames", frames_, "Number of frames (written 0..N-1)")->required();
    simulate_
        ->add_option("--output,-o", sim_output_,
                     "Folder: writes DIR/alpha/%04d.png and DIR/motion/%04d.flo")
        ->required();
    simulate_->add_option("--threads,-j", threads_, "Threads (0 = all cores)");
    simulate_->add_flag("--quiet,-q", quiet_, "No progress bar, no output paths");
}

Status FluidCommand::run(const Streams& streams) {
    if (simulate_->parsed()) return run_simulate(streams);
    return run_transfer(streams);
}

Status FluidCommand::run_simulate(const Streams& streams) const {
    fluid::FluidScene scene;
    if (scene_ == "plume") {
        scene = fluid::plume_scene(width_, height_);
        EXEMPLAR_RETURN_IF_ERROR(fluid::validate(scene));
    } else {
        auto read = read_scene(scene_, width_, height_);
        if (!read.ok()) return read.status();
        scene = std::move(read).value();
    }
    const std::string alpha_dir = (fs::path(sim_output_) / "alpha").string();
    const std::string motion_dir = (fs::path(sim_output_) / "motion").string();
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", (fs::path(alpha_dir) / "x").string()));
    EXEMPLAR_RETURN_IF_ERROR(create_folders(alpha_dir));
    EXEMPLAR_RETURN_IF_ERROR(create_folders(motion_dir));
    ProgressBar bar(streams.err, "simulate", !quiet_ && streams.err_is_terminal);
    RunContext context(threads_);
    const Status status = fluid::simulate(
        scene, frames_,
        [&](int frame, const Image& alpha, const Image& motion) {
            EXEMPLAR_RETURN_IF_ERROR(
                video::write_frame(alpha, (fs::path(alpha_dir) / "%04d.png").string(), frame));
            auto motion_path =
                video::format_frame_path((fs::path(motion_dir) / "%04d.flo").string(), frame);
            if (!motion_path.ok()) return motion_path.status();
            EXEMPLAR_RETURN_IF_ERROR(save_flo(motion, *motion_path));
            bar.update(static_cast<double>(frame + 1) / frames_,
                       "frame " + std::to_string(frame + 1) + "/" + std::to_string(frames_));
            return Status::ok();
        },
        context);
    bar.finish();
    if (!status.is_ok()) return status;
    if (!quiet_) {
        streams.out << (fs::path(alpha_dir) / "%04d.png").string() << '\n'
                    << (fs::path(motion_dir) / "%04d.flo").string() << '\n';
    }
    return Status::ok();
}

Status FluidCommand::apply_config(fluid::FluidOptions& options) {
    auto doc = read_json_object(config_);
    if (!doc.ok()) return doc.status();
    for (const auto& [raw, value] : doc->items()) {
        const std::string key = canonical_key(raw);
        auto text = [&](std::string& into) -> Status {
            if (!value.is_string()) return type_error(config_, raw, "a string");
            into = relative_to(config_, value.get<std::string>());
            return Status::ok();
        };
        auto integer = [&](int& into) -> Status {
            if (!value.is_number_integer()) return type_error(config_, raw, "an integer");
            into = value.get<int>();
            return Status::ok();
        };
        Status s;
        if (key == "exemplar") {
            s = exemplar_.empty() ? text(exemplar_) : Status::ok();
        } else if (key == "exemplar-alpha") {
            s = exemplar_alpha_.empty() ? text(exemplar_alpha_) : Status::ok();
        } else if (key == "alpha") {
            s = alpha_.empty() ? text(alpha_) : Status::ok();
        } else if (key == "motion") {
            s = motion_.empty() ? text(motion_) : Status::ok();
        } else if (key == "output") {
            s = output_.empty() ? text(output_) : Status::ok();
        } else if (key == "mp4") {
            s = mp4_.empty() ? text(mp4_) : Status::ok();
        } else if (key == "motion-layer") {
            if (!value.is_string()) return type_error(config_, raw, "a string");
            if (motion_layer_.empty()) motion_layer_ = value.get<std::string>();
        } else if (key == "usage") {
            if (!value.is_string()) return type_error(config_, raw, "a string");
            if (usage_.empty()) usage_ = value.get<std::string>();
        } else if (key == "first") {
            if (!first_) {
                int v = 0;
                s = integer(v);
                first_ = v;
            }
        } else if (key == "last") {
            if (!last_) {
                int v = 0;
                s = integer(v);
                last_ = v;
            }
        } else if (key == "threads") {
            if (app_->count("--threads") == 0) s = integer(threads_);
        } else if (key == "fps") {
            if (!value.is_number()) return type_error(config_, raw, "a number");
            if (app_->count("--fps") == 0) fps_ = value.get<double>();
        } else if (key == "seed") {
            if (!value.is_number_unsigned()) return type_error(config_, raw, "an integer >= 0");
            if (seed_flag_->count() == 0) options.synthesis.seed = value.get<std::uint64_t>();
        } else if (key == "rotations") {
            if (!value.is_boolean()) return type_error(config_, raw, "true or false");
            if (app_->count("--rotations") + app_->count("--no-rotations") == 0) {
                rotations_ = value.get<bool>();
            }
        } else {
            const fluid::FluidOptionSpec* spec = nullptr;
            for (const auto& candidate : fluid::fluid_option_specs()) {
                if (candidate.name == key) spec = &candidate;
            }
            if (spec == nullptr) return invalid_argument(config_ + ": unknown key '" + raw + "'");
            if (!value.is_number()) return type_error(config_, raw, "a number");
            if (numeric_flags_.at(key)->count() == 0) {
                s = fluid::set_option(options, *spec, value.get<double>());
                if (!s.is_ok()) return invalid_argument(config_ + ": " + s.message());
            }
        }
        if (!s.is_ok()) return s;
    }
    return Status::ok();
}

Status FluidCommand::run_transfer(const Streams& streams) {
    // Options: defaults, then the job file, then flags.
    fluid::FluidOptions options;
    if (seed_flag_->count() > 0) options.synthesis.seed = seed_;
    for (const fluid::FluidOptionSpec& spec : fluid::fluid_option_specs()) {
        const std::string name(spec.name);
        if (numeric_flags_.at(name)->count() > 0) {
            EXEMPLAR_RETURN_IF_ERROR(fluid::set_option(options, spec, numeric_values_.at(name)));
        }
    }
    if (!config_.empty()) EXEMPLAR_RETURN_IF_ERROR(apply_config(options));
    options.rotations = rotations_;
    if (!usage_.empty()) {
        if (usage_ != "uniform" && usage_ != "none") {
            return invalid_argument("--usage: '" + usage_ +
                                    "' is invalid (must be one of uniform, none)");
        }
        options.uniform_usage = usage_ == "uniform";
    }
    EXEMPLAR_RETURN_IF_ERROR(fluid::validate(options));
    for (const auto& [flag, value] : {std::pair{"--exemplar", &exemplar_},
                                      {"--alpha", &alpha_},
                                      {"--motion", &motion_},
                                      {"--output", &output_}}) {
        if (value->empty()) return invalid_argument(std::string(flag) + " is required");
    }
    if (!first_ || !last_) return invalid_argument("--first and --last are required");
    const int first = *first_, last = *last_;
    if (last < first) {
        return invalid_argument("--last: " + std::to_string(last) + " is before --first " +
                                std::to_string(first));
    }
    if (!(fps_ > 0 && fps_ <= 1000)) {
        return invalid_argument("--fps: " + std::to_string(fps_) + " is invalid (must be 0..1000)");
    }

    // Everything is checked before a frame or the MP4 is written: the output pattern, the
    // targets of every frame, the exemplar.
    auto probe = frame_file("--output", output_, first);
    if (!probe.ok()) return probe.status();
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", *probe));
    fluid::FluidRange range;
    range.first = first;
    range.last = last;
    range.alpha_file = [&](int n) { return frame_file("--alpha", alpha_, n); };
    range.motion_file = [&](int n) { return frame_file("--motion", motion_, n); };
    range.output_file = [&](int n) { return frame_file("--output", output_, n); };
    range.motion_layer = motion_layer_;
    range.resume = resume_;
    auto exemplar = fluid::FluidExemplar::open(exemplar_, exemplar_alpha_);
    range.exemplar = [](int) -> Result<Image> { return Image(); };  // set below, once opened
    EXEMPLAR_RETURN_IF_ERROR(fluid::check_fluid_range(range));
    if (!exemplar.ok()) return exemplar.status();
    exemplar->use_in(range);
    std::optional<video::Mp4Writer> mp4;
    if (!mp4_.empty()) {
        auto first_alpha_path = frame_file("--alpha", alpha_, first);
        if (!first_alpha_path.ok()) return first_alpha_path.status();
        auto first_alpha = load_image(*first_alpha_path);
        if (!first_alpha.ok()) return first_alpha.status();
        const int W = first_alpha->width(), H = first_alpha->height();
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("--mp4", mp4_));
        EXEMPLAR_RETURN_IF_ERROR(video::check_video_support(mp4_));
        if (!video::mp4_writing_supported()) {
            return unsupported("--mp4: this OpenCV build cannot encode MP4");
        }
        if (W % 2 != 0 || H % 2 != 0) {
            return invalid_argument("--mp4: the frames are " + std::to_string(W) + "x" +
                                    std::to_string(H) + " but MP4 needs even sizes");
        }
        auto writer = video::Mp4Writer::open(mp4_, W, H, fps_);
        if (!writer.ok()) return writer.status();
        mp4.emplace(std::move(writer).value());
    }

    // Frames in order (the library's range driver: resume, continue, atomic frames).
    ProgressBar bar(streams.err, "fluid", !quiet_ && streams.err_is_terminal);
    const int count = last - first + 1;
    int next = first;  // the frame being synthesized, for the progress bar
    int written = 0;
    range.on_frame = [&](int n, const Image& stored, bool wrote) -> Status {
        next = n + 1;
        if (wrote) {
            ++written;
            if (!quiet_) streams.out << *frame_file("--output", output_, n) << '\n';
        }
        if (!mp4) return Status::ok();
        // Over black: the premultiplied colour.
        Image rgb(stored.width(), stored.height(), 3);
        for (int y = 0; y < rgb.height(); ++y) {
            for (int x = 0; x < rgb.width(); ++x) {
                const float a = stored.channels() == 4 ? stored.at(x, y, 3) : 1.0f;
                for (int c = 0; c < 3; ++c) {
                    rgb.at(x, y, c) = stored.at(x, y, std::min(c, stored.channels() - 1)) * a;
                }
            }
        }
        return mp4->write(rgb);
    };
    RunContext context(threads_);
    context.progress = [&](const ProgressEvent& e) {
        bar.update(e.fraction, "frame " + std::to_string(next) + " (" +
                                   std::to_string(next - first + 1) + "/" + std::to_string(count) +
                                   ")");
    };
    EXEMPLAR_RETURN_IF_ERROR(fluid::synthesize_fluid_range(range, options, context));
    bar.finish();
    return finish_frame_range(streams.out, mp4, mp4_, written, count, quiet_);
}

}  // namespace exemplar::cli
