// `exemplar noisy`: Color Me Noisy (Fišer et al. 2014) over a frame range. The frames are the
// library's range driver's (noisy::synthesize_range: batches of parallel frames, resume, atomic
// writes); this command parses the flags and the job file, reads the media and the reference
// sequence (a pattern or a video) and collects the range into --mp4 once every frame exists.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/noisy/noisy.hpp"
#include "exemplar/noisy/noisy_range.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "json_file.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"

namespace exemplar::cli {

namespace fs = std::filesystem;
using noisy::NoisyOptions;

NoisyCommand::NoisyCommand(CLI::App& app) {
    app_ = app.add_subcommand(
        "noisy",
        "Color Me Noisy: re-synthesize a coherent reference animation from a drawing medium "
        "with controlled temporal noise (docs/noisy.md)");
    app_->add_option("--exemplar", exemplars_,
                     "Scan of the drawing medium (S); repeat for several media chosen per pixel "
                     "by --source-map");
    app_->add_option("--frames", frames_,
                     "Reference animation: frame pattern (\"R/%04d.png\") or video file");
    app_->add_option("--first", first_, "First frame number (pattern: required)");
    app_->add_option("--last", last_, "Last frame number (pattern: required)");
    app_->add_option("--output,-o", output_, "Output frame pattern (\"T/%04d.png\")");
    app_->add_option("--noise-map", noise_map_,
                     "Per-pixel noise strength in [0, 1] scaling --noise: one image, or a "
                     "frame pattern with the reference's numbers");
    app_->add_option("--source-map", source_map_,
                     "Local choice of source: grey level k (of 255) takes the k-th --exemplar "
                     "(0 = the first); one image, or a frame pattern with the reference's "
                     "numbers. Required with several --exemplar");
    app_->add_option("--exemplar-orientation", exemplar_orientations_,
                     "Orientation field of the medium: angles in radians, EXR or float TIFF "
                     "(needs --frame-orientation); one per --exemplar, in their order");
    app_->add_option("--frame-orientation", frame_orientation_,
                     "Orientation fields of the frames: one file, or a frame pattern with the "
                     "reference's numbers (needs --exemplar-orientation)");
    app_->add_option("--mp4", mp4_, "Also write the range as an MP4 file");
    app_->add_option("--fps", fps_, "Frame rate of --mp4 (default 24)");
    app_->add_option("--filter", filter_, "Low-pass filter: box (default) or lanczos3");
    app_->add_option("--seed", seed_, "Random seed: frame i depends only on (seed, i)");
    app_->add_option("--threads,-j", threads_, "Threads (0 = all cores)");
    app_->add_option("--config", config_,
                     "JSON job file with the same keys as the flags (flags win)");
    app_->add_flag("--resume,!--no-resume", resume_,
                   "Skip frames whose output exists (default on)");
    app_->add_flag("--quiet,-q", quiet_, "No progress bar and no output paths");
    for (const noisy::NoisyOptionSpec& spec : noisy::noisy_option_specs()) {
        const NoisyOptions defaults;
        std::string doc(spec.doc);
        std::string value = std::to_string(noisy::get_option(defaults, spec));
        while (value.back() == '0') value.pop_back();
        if (value.back() == '.') value.pop_back();
        // --noise has no default on the command line: the noise level is the user's choice.
        doc += " [" + (spec.unit.empty() ? std::string() : std::string(spec.unit) + ", ") +
               (spec.name == "noise" ? std::string("required") : "default " + value) + "]";
        numeric_flags_[std::string(spec.name)] = app_->add_option(
            "--" + std::string(spec.name), numeric_values_[std::string(spec.name)], doc);
    }
}

Status NoisyCommand::apply_config() {
    if (config_.empty()) return Status::ok();
    auto json = read_json_object(config_);
    if (!json.ok()) return json.status();
    for (const auto& [raw_key, value] : json->items()) {
        const std::string key = canonical_key(raw_key);
        CLI::Option* flag = app_->get_option_no_throw("--" + key);
        if (flag == nullptr || key == "config") {
            return invalid_argument(config_ + ": unknown key '" + raw_key + "'");
        }
        if (flag->count() > 0) continue;  // the command line wins
        const bool numeric = numeric_flags_.count(key) > 0;
        if (numeric || key == "first" || key == "last" || key == "seed" || key == "threads" ||
            key == "fps") {
            if (!value.is_number()) return type_error(config_, raw_key, "a number");
        } else if (key == "resume" || key == "quiet") {
            if (!value.is_boolean()) return type_error(config_, raw_key, "true or false");
        } else if (key == "exemplar" || key == "exemplar-orientation") {
            // One file, or an array of files (several media with a source map).
            const bool strings =
                value.is_string() || (value.is_array() && !value.empty() &&
                                      std::all_of(value.begin(), value.end(),
                                                  [](const auto& v) { return v.is_string(); }));
            if (!strings) return type_error(config_, raw_key, "a string or an array of strings");
            auto& files = key == "exemplar" ? exemplars_ : exemplar_orientations_;
            files.clear();
            if (value.is_string()) {
                files.push_back(value.get<std::string>());
            } else {
                for (const auto& file : value) files.push_back(file.get<std::string>());
            }
            continue;
        } else if (!value.is_string()) {
            return type_error(config_, raw_key, "a string");
        }
        if (numeric) {
            numeric_values_[key] = value.get<double>();
            numeric_from_config_.insert(key);
        } else if (key == "first") {
            first_ = value.get<int>();
            first_given_ = true;
        } else if (key == "last") {
            last_ = value.get<int>();
            last_given_ = true;
        } else if (key == "seed") {
            seed_ = value.get<std::uint64_t>();
        } else if (key == "threads") {
            threads_ = value.get<int>();
        } else if (key == "fps") {
            fps_ = value.get<double>();
        } else if (key == "resume") {
            resume_ = value.get<bool>();
        } else if (key == "quiet") {
            quiet_ = value.get<bool>();
        } else if (key == "frames") {
            frames_ = value.get<std::string>();
        } else if (key == "output") {
            output_ = value.get<std::string>();
        } else if (key == "noise-map") {
            noise_map_ = value.get<std::string>();
        } else if (key == "source-map") {
            source_map_ = value.get<std::string>();
        } else if (key == "frame-orientation") {
            frame_orientation_ = value.get<std::string>();
        } else if (key == "mp4") {
            mp4_ = value.get<std::string>();
        } else if (key == "filter") {
            filter_ = value.get<std::string>();
        }
    }
    return Status::ok();
}

Status NoisyCommand::run(const Streams& streams) {
    first_given_ = app_->get_option("--first")->count() > 0;
    last_given_ = app_->get_option("--last")->count() > 0;
    EXEMPLAR_RETURN_IF_ERROR(apply_config());
    if (exemplars_.empty()) return invalid_argument("--exemplar: is required");
    for (const auto& [flag, value] : std::vector<std::pair<const char*, const std::string*>>{
             {"--frames", &frames_}, {"--output", &output_}}) {
        if (value->empty()) return invalid_argument(std::string(flag) + ": is required");
    }
    if (exemplars_.size() > 1 && source_map_.empty()) {
        return invalid_argument("--source-map: is required with " +
                                std::to_string(exemplars_.size()) +
                                " --exemplar (it chooses the medium of every pixel)");
    }
    if (numeric_flags_.at("noise")->count() == 0 && numeric_from_config_.count("noise") == 0) {
        return invalid_argument("--noise: is required (the low-pass strength f in pixels)");
    }

    // Options, each checked against its range.
    noisy::NoisyOptions options;
    for (const noisy::NoisyOptionSpec& spec : noisy::noisy_option_specs()) {
        const std::string name(spec.name);
        if (numeric_flags_.at(name)->count() == 0 && numeric_from_config_.count(name) == 0) {
            continue;
        }
        EXEMPLAR_RETURN_IF_ERROR(noisy::set_option(options, spec, numeric_values_.at(name)));
    }
    options.seed = seed_;
    auto filter = noisy::parse_low_pass_filter(filter_);
    if (!filter.ok()) return filter.status();
    options.filter = *filter;
    EXEMPLAR_RETURN_IF_ERROR(noisy::validate(options));
    if (threads_ < 0)
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0)");

    // Inputs: the media, the reference frames (a missing one is reported now), the maps.
    std::vector<noisy::NoisySource> sources;
    for (const std::string& path : exemplars_) {
        auto medium = load_image(path);
        if (!medium.ok()) return medium.status();
        sources.push_back({std::move(*medium), Image()});
    }
    const Image& source = sources.front().image;
    const bool is_pattern = frames_.find('%') != std::string::npos;
    Result<video::FrameSequence> sequence = invalid_argument("--frames: unset");
    if (is_pattern) {
        if (!first_given_ || !last_given_) {
            return invalid_argument("--frames " + frames_ +
                                    ": a frame pattern needs --first and --last");
        }
        sequence = video::FrameSequence::from_pattern(frames_, first_, last_);
    } else {
        sequence = video::FrameSequence::from_video(frames_);
    }
    if (!sequence.ok()) return sequence.status();
    const int base = sequence->first_number();
    const int lo = is_pattern ? first_ : (first_given_ ? first_ : 0);
    const int hi = is_pattern ? last_ : (last_given_ ? last_ : sequence->size() - 1);
    if (lo < 0 || hi >= base + sequence->size() || hi < lo) {
        return invalid_argument("--first/--last: " + std::to_string(lo) + ".." +
                                std::to_string(hi) + " is invalid (the video has frames 0.." +
                                std::to_string(sequence->size() - 1) + ")");
    }
    if (exemplar_orientations_.empty() != frame_orientation_.empty()) {
        return invalid_argument(
            "--exemplar-orientation and --frame-orientation: give both, or neither");
    }
    if (!exemplar_orientations_.empty() && exemplar_orientations_.size() != exemplars_.size()) {
        return invalid_argument(
            "--exemplar-orientation: " + std::to_string(exemplar_orientations_.size()) +
            " given for " + std::to_string(exemplars_.size()) +
            " --exemplar (give one per exemplar, in their order)");
    }
    // The media's orientation fields (angles in radians need a float format); a frame
    // pattern's extension is checked now, not at its first frame.
    const auto flagged = [](const std::string& flag, const Status& status) {
        return status.is_ok() ? status : Status(status.code(), flag + " " + status.message());
    };
    for (std::size_t k = 0; k < exemplar_orientations_.size(); ++k) {
        auto angles = noisy::load_orientation_field(exemplar_orientations_[k]);
        if (!angles.ok()) return flagged("--exemplar-orientation", angles.status());
        sources[k].orientation = std::move(*angles);
    }
    // A per-pixel input (--noise-map, --source-map, --frame-orientation): one file for the
    // range or a frame pattern with the reference's numbers.
    const auto range_input = [](const std::string& value) {
        noisy::RangeInput input;
        if (value.empty()) return input;
        input.per_frame = value.find('%') != std::string::npos;
        input.file = [value, per_frame = input.per_frame](int n) -> Result<std::string> {
            return per_frame ? video::format_frame_path(value, n) : Result<std::string>(value);
        };
        return input;
    };
    noisy::NoisyRange range;
    range.first = lo;
    range.last = hi;
    range.noise_map = range_input(noise_map_);
    range.source_map = range_input(source_map_);
    range.orientation = range_input(frame_orientation_);
    if (range.orientation.file) {
        auto first_file = range.orientation.file(lo);
        if (!first_file.ok()) return first_file.status();
        EXEMPLAR_RETURN_IF_ERROR(
            flagged("--frame-orientation", noisy::check_orientation_file(*first_file)));
    }
    auto output_path = [&](int number) { return video::format_frame_path(output_, number); };
    {
        auto probe = output_path(lo);
        if (!probe.ok()) return probe.status();
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", *probe));
        EXEMPLAR_RETURN_IF_ERROR(check_output_format(
            "--output", *probe, source, output_options(source, exemplars_.front(), *probe)));
    }
    if (!mp4_.empty()) EXEMPLAR_RETURN_IF_ERROR(video::check_video_support(mp4_));

    // The frames: the library's range driver (resume, batches of parallel frames, atomic
    // writes); the reference frames are read from the sequence on this thread.
    range.reference = [&](int n) { return sequence->read(n - base); };
    range.reference_name = [&](int n) { return sequence->frame_name(n - base); };
    range.output_file = output_path;
    range.save = output_options(source, exemplars_.front(), *output_path(lo));
    range.resume = resume_;
    int written = 0, last_written = lo;
    range.on_frame = [&](int n, const std::string&) {
        ++written;
        last_written = n;
        return Status::ok();
    };
    ProgressBar bar(streams.err, "noisy", streams.err_is_terminal && !quiet_);
    RunContext context(threads_);
    context.progress = [&](const ProgressEvent& e) {
        bar.update(e.fraction, "frame " + std::to_string(last_written));
    };
    EXEMPLAR_RETURN_IF_ERROR(noisy::synthesize_range(sources, range, options, context));
    bar.finish();
    if (!quiet_) {
        if (written == 0) {
            streams.err << "exemplar noisy: every frame of the range exists\n";
        } else {
            streams.out << output_ << " (" << written << " frame" << (written == 1 ? "" : "s")
                        << ")\n";
        }
    }

    if (!mp4_.empty()) {
        Result<video::Mp4Writer> writer = invalid_argument("--mp4: unset");
        for (int n = lo; n <= hi; ++n) {
            auto image = load_image(*output_path(n));
            if (!image.ok()) return image.status();
            if (n == lo) {
                writer = video::Mp4Writer::open(mp4_, image->width(), image->height(), fps_);
                if (!writer.ok()) return writer.status();
            }
            EXEMPLAR_RETURN_IF_ERROR(writer->write(*image));
        }
        EXEMPLAR_RETURN_IF_ERROR(writer->finish());
        if (!quiet_) streams.out << mp4_ << '\n';
    }
    return Status::ok();
}

}  // namespace exemplar::cli
