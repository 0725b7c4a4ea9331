// `exemplar npr`: image-space stippling, hatching and halftoning of a rendered animation
// (issue 20, docs/npr.md) from the frame folders of `exemplar render --frames`.
//
// The frames are the library's range driver's (npr::stylize_range: in order, each output
// written atomically with its synthesis state beside it, resume, a range continued, the
// bidirectional blocks, the paper layer); what a frame shows is npr::stylize_frame. This file
// parses the flags, prepares the pattern and the paper, adds every frame of the range (also
// resumed ones, read back) to the MP4 with --mp4, and prints.

#include <optional>
#include <string>
#include <utility>

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/npr/npr.hpp"
#include "exemplar/npr/npr_range.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "option_help.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"

namespace exemplar::cli {

namespace {

Result<std::string> frame_path(const std::string& flag, const std::string& pattern, int n) {
    auto path = video::format_frame_path(pattern, n);
    if (!path.ok()) return invalid_argument(flag + ": " + path.status().message());
    return path;
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
    add_table_flags(
        *app_, npr::npr_option_specs(), npr::NprOptions{},
        [](const npr::NprOptions& o, const npr::NprOptionSpec& spec) {
            return npr::get_option(o, spec);
        },
        numeric_values_, numeric_flags_);
    app_->add_option("--paper", paper_,
                     "Paper texture (grey image), synthesized like the pattern: grain, and the "
                     "shape's boundary (alpha buffer) eroded by its noise");
    app_->add_option("--bidirectional", bidirectional_,
                     "Bidirectional loop with delayed disocclusions every N frames (forward, "
                     "then backward along the forward flow; 0 = forward only, the default)");
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
    npr::NprOptions options;
    auto style = npr::parse_style(style_);
    if (!style.ok()) return invalid_argument("--" + style.status().message());
    options.style = *style;
    EXEMPLAR_RETURN_IF_ERROR(set_given_table_flags(
        options, npr::npr_option_specs(), ModuleSetOption{}, numeric_values_, numeric_flags_));
    options.tone = tone_;
    options.orientation = orientation_;
    options.lines = lines_;
    options.tone_correction = tone_correction_;
    options.seed = seed_;
    options.paper = !paper_.empty();
    for (const char* flag : {"paper-grain", "erosion"})
        if (!options.paper && numeric_flags_.at(flag)->count() > 0)
            return invalid_argument(std::string("--") + flag + ": needs --paper");
    if (const Status valid = npr::validate(options); !valid.is_ok())
        return invalid_argument("--" + valid.message());
    if (last_ < first_)
        return invalid_argument("--last: " + std::to_string(last_) + " is before --first " +
                                std::to_string(first_));
    npr::NprRange range;
    range.first = first_;
    range.last = last_;
    range.frame_folder = [&](int n) { return frame_path("--frames", frames_, n); };
    range.output_file = [&](int n) { return frame_path("--output", output_, n); };
    range.bidirectional = bidirectional_;
    range.resume = resume_;
    if (const Status valid = npr::validate(range); !valid.is_ok())
        return invalid_argument("--" + valid.message());
    if (!(fps_ > 0 && fps_ <= 1000))
        return invalid_argument("--fps: " + std::to_string(fps_) + " is invalid (must be 0..1000)");
    if (threads_ < 0)
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0)");
    RunContext context(threads_);

    auto probe = frame_path("--output", output_, first_);
    if (!probe.ok()) return probe.status();
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", *probe));
    EXEMPLAR_RETURN_IF_ERROR(frame_path("--frames", frames_, first_).status());

    auto pattern_image = load_image(pattern_);
    if (!pattern_image.ok()) return pattern_image.status();
    auto prepared = npr::prepare_pattern(*pattern_image, options, context);
    if (!prepared.ok())
        return invalid_argument("--pattern " + pattern_ + ": " + prepared.status().message());
    const npr::Pattern& pattern = *prepared;
    std::optional<npr::Pattern> paper;
    if (options.paper) {
        auto paper_image = load_image(paper_);
        if (!paper_image.ok()) return paper_image.status();
        auto prepared_paper = npr::prepare_pattern(*paper_image, options, context);
        if (!prepared_paper.ok())
            return invalid_argument("--paper " + paper_ + ": " + prepared_paper.status().message());
        paper = std::move(prepared_paper).value();
    }
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
    // Frames in order (the library's range driver: resume, states, bidirectional blocks)
    ProgressBar bar(streams.err, "npr", !quiet_ && streams.err_is_terminal);
    const int count = last_ - first_ + 1;
    int next = first_;  // the first frame not handed over yet, for the progress bar
    int written = 0;
    range.on_frame = [&](int n, const std::string& out_path, const Image* image) -> Status {
        next = n + 1;
        if (image) {
            EXEMPLAR_RETURN_IF_ERROR(add_to_mp4(*image));
            ++written;
            if (!quiet_) streams.out << out_path << '\n';
            return Status::ok();
        }
        if (mp4_.empty()) return Status::ok();
        auto stored = load_image(out_path);
        if (!stored.ok()) return stored.status();
        return add_to_mp4(*stored);
    };
    context.progress = [&](const ProgressEvent& e) {
        bar.update(e.fraction, "frame " + std::to_string(next) + " (" +
                                   std::to_string(next - first_ + 1) + "/" + std::to_string(count) +
                                   ")");
    };
    EXEMPLAR_RETURN_IF_ERROR(
        npr::stylize_range(pattern, paper ? &*paper : nullptr, range, options, context));
    bar.finish();
    return finish_frame_range(streams.out, mp4, mp4_, written, count, quiet_);
}

}  // namespace exemplar::cli
