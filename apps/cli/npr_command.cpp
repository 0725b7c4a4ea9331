// `exemplar npr`: image-space stippling, hatching and halftoning of a rendered animation
// (issue 20, docs/npr.md) from the frame folders of `exemplar render --frames`.
//
// Frames are synthesized in order; each output is written atomically with its synthesis state
// (the pattern coordinates of every level, OUT.state.exr; with --paper also the paper's,
// OUT.paper.state.exr) as soon as it is done; --mp4 adds
// every frame of the range (also resumed ones, read back) to one video. A frame whose
// output and state exist is skipped (resume) and its state read back as the next frame's
// previous frame, so a resumed range gives the same bytes as an uninterrupted one. A missing
// buffer stops the run with one line naming it; the frames written so far are kept. With
// --bidirectional N the frames after the first go in blocks of N (forward, then backward along
// the forward flow, then written together), and resume skips or redoes whole blocks. What a
// frame shows (tone, thresholding, orientation, paper, lines) is the library's
// npr::stylize_frame.

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "exemplar/io/folders.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/npr/npr.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "option_help.hpp"
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

// Buffer `name` of a render frame folder (npr::frame_buffer_file); `linear` tells whether it
// came from the EXR (linear light) or the PNG (sRGB-encoded values).
Status load_buffer(const std::string& folder, const std::string& name, Image& image, bool& linear) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        return io_error(folder + ": no such frame folder (from exemplar render --frames)");
    const std::string path = npr::frame_buffer_file(folder, name);
    if (path.empty()) {
        return io_error(folder + ": missing buffer '" + name + "' (" + name + ".png or " + name +
                        ".exr)");
    }
    auto loaded = load_image(path);
    if (!loaded.ok()) return loaded.status();
    image = std::move(loaded).value();
    linear = path.ends_with(".exr");
    return Status::ok();
}

// A stored state (OUT.state.exr) as the previous frame of the next one.
Result<npr::FrameState> load_state(const std::string& path, const npr::Pattern& pattern) {
    auto packed = load_image(path);
    if (!packed.ok()) return packed.status();
    auto state = npr::unpack_state(pattern, *packed);
    if (!state.ok()) return invalid_argument(path + ": " + state.status().message());
    return state;
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
    if (bidirectional_ < 0 || bidirectional_ == 1 || bidirectional_ > 1000)
        return invalid_argument("--bidirectional: " + std::to_string(bidirectional_) +
                                " is invalid (must be 0 or 2..1000)");
    if (last_ < first_)
        return invalid_argument("--last: " + std::to_string(last_) + " is before --first " +
                                std::to_string(first_));
    if (!(fps_ > 0 && fps_ <= 1000))
        return invalid_argument("--fps: " + std::to_string(fps_) + " is invalid (must be 0..1000)");
    if (threads_ < 0)
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0)");
    const RunContext context(threads_);

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
    // A frame's stored states: the pattern's (OUT.state.exr) and the paper's
    // (OUT.paper.state.exr)
    const auto state_files = [&](const std::string& out_path) {
        std::vector<std::string> files{out_path + ".state.exr"};
        if (paper) files.push_back(out_path + ".paper.state.exr");
        return files;
    };
    const auto all_exist = [&](const std::vector<std::string>& files) {
        for (const std::string& file : files)
            if (!exists(file)) return false;
        return true;
    };
    std::optional<npr::FrameState> previous, previous_paper;
    const auto load_states = [&](const std::vector<std::string>& files) -> Status {
        auto state = load_state(files[0], pattern);
        if (!state.ok()) return state.status();
        previous = std::move(state).value();
        if (paper) {
            auto paper_state = load_state(files[1], *paper);
            if (!paper_state.ok()) return paper_state.status();
            previous_paper = std::move(paper_state).value();
        }
        return Status::ok();
    };

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
    // A finished frame just before the range hands over to it
    if (auto before = frame_path("--output", output_, first_ - 1);
        before.ok() && all_exist(state_files(*before)))
        EXEMPLAR_RETURN_IF_ERROR(load_states(state_files(*before)));
    // Frame n's buffers (those of `needs`) from its folder
    const auto load_frame = [&](int n, const std::vector<npr::BufferNeed>& needs,
                                npr::NprFrame& frame) -> Status {
        const std::string folder = *frame_path("--frames", frames_, n);
        for (const npr::BufferNeed& need : needs) {
            bool linear = false;
            EXEMPLAR_RETURN_IF_ERROR(load_buffer(folder, need.name, frame[need.role], linear));
            if (need.role == npr::BufferRole::Tone) frame.tone_linear = linear;
        }
        return Status::ok();
    };
    const auto in_folder = [&](int n, const Status& status) {
        return Status(status.code(), *frame_path("--frames", frames_, n) + ": " + status.message());
    };
    // Blocks of frames done together: one frame each, or with --bidirectional N the first frame,
    // then the N frames up to each update frame (forward, then backward)
    int written = 0;
    for (int start = first_; start <= last_;) {
        const int end = bidirectional_ == 0 || start == first_
                            ? start
                            : std::min(start + bidirectional_ - 1, last_);
        bool done = resume_;
        for (int n = start; n <= end && done; ++n) {
            const std::string out_path = *frame_path("--output", output_, n);
            done = exists(out_path) && all_exist(state_files(out_path));
        }
        if (done) {
            EXEMPLAR_RETURN_IF_ERROR(
                load_states(state_files(*frame_path("--output", output_, end))));
            for (int n = start; n <= end && !mp4_.empty(); ++n) {
                auto stored = load_image(*frame_path("--output", output_, n));
                if (!stored.ok()) return stored.status();
                EXEMPLAR_RETURN_IF_ERROR(add_to_mp4(*stored));
            }
            start = end + 1;
            continue;
        }
        // Forward: each frame from the one before; within a bidirectional block only where the
        // point was visible in every frame since the block's start (the delayed visibility)
        std::vector<npr::NprFrameResult> results;
        std::vector<Image> visible;
        const bool loop = bidirectional_ > 0 && previous.has_value();
        for (int n = start; n <= end; ++n) {
            npr::NprFrame frame;
            EXEMPLAR_RETURN_IF_ERROR(
                load_frame(n, npr::needed_buffers(options, previous.has_value()), frame));
            if (loop) {
                auto seen = npr::delayed_visibility(visible.empty() ? Image() : visible.back(),
                                                    frame.disocclusion, frame.backward_flow);
                if (!seen.ok()) return in_folder(n, seen.status());
                frame.disocclusion = *seen;
                for (float& v : frame.disocclusion.data()) v = 1.0f - v;
                visible.push_back(std::move(seen).value());
            }
            npr::NprPaper paper_layer;
            if (paper) {
                paper_layer.pattern = &*paper;
                paper_layer.previous = previous_paper ? &*previous_paper : nullptr;
            }
            auto styled = npr::stylize_frame(pattern, frame, previous ? &*previous : nullptr, n,
                                             options, context, paper_layer);
            if (!styled.ok()) return in_folder(n, styled.status());
            previous = styled->state;
            if (paper) previous_paper = styled->paper_state;
            results.push_back(std::move(styled).value());
        }
        // The forward states are held only for their coordinates now (a block of 20 frames at
        // 960x540 keeps ~7 MB per frame instead of ~25)
        for (std::size_t i = 0; loop && i + 1 < results.size(); ++i) {
            for (npr::FrameState* state : {&results[i].state, &results[i].paper_state}) {
                state->appearance.clear();
                state->screen = Image();
            }
        }
        // Backward: the rest of each frame coherent with the next (its forward flow and
        // occlusion), the visible part held
        for (int n = end - 1; loop && n >= start; --n) {
            const std::size_t i = static_cast<std::size_t>(n - start);
            npr::NprFrame frame;
            std::vector<npr::BufferNeed> needs = npr::needed_buffers(options, true);
            for (npr::BufferNeed& need : needs) {
                if (need.role == npr::BufferRole::BackwardFlow) need.name = "forward_flow";
                if (need.role == npr::BufferRole::Disocclusion) need.name = "occlusion";
            }
            EXEMPLAR_RETURN_IF_ERROR(load_frame(n, needs, frame));
            frame.hold = visible[i];
            frame.held = &results[i].state;
            npr::NprPaper paper_layer;
            if (paper) {
                paper_layer.pattern = &*paper;
                paper_layer.previous = &results[i + 1].paper_state;
                paper_layer.held = &results[i].paper_state;
            }
            auto styled = npr::stylize_frame(pattern, frame, &results[i + 1].state, n, options,
                                             context, paper_layer);
            if (!styled.ok()) return in_folder(n, styled.status());
            results[i] = std::move(styled).value();
        }
        // Write the block's frames and states
        for (int n = start; n <= end; ++n) {
            const npr::NprFrameResult& styled = results[static_cast<std::size_t>(n - start)];
            const std::string out_path = *frame_path("--output", output_, n);
            const std::vector<std::string> states = state_files(out_path);
            EXEMPLAR_RETURN_IF_ERROR(create_folders(fs::path(out_path).parent_path().string()));
            SaveOptions state_options;
            state_options.format = PixelFormat::Float;
            EXEMPLAR_RETURN_IF_ERROR(
                save_image(npr::pack_state(styled.state), states[0], state_options));
            if (paper)
                EXEMPLAR_RETURN_IF_ERROR(
                    save_image(npr::pack_state(styled.paper_state), states[1], state_options));
            EXEMPLAR_RETURN_IF_ERROR(video::write_frame(styled.image, output_, n));
            EXEMPLAR_RETURN_IF_ERROR(add_to_mp4(styled.image));
            ++written;
            if (!quiet_) streams.out << out_path << '\n';
        }
        bar.update(static_cast<double>(end - first_ + 1) / count,
                   "frame " + std::to_string(end) + " (" + std::to_string(end - first_ + 1) + "/" +
                       std::to_string(count) + ")");
        start = end + 1;
    }
    bar.finish();
    return finish_frame_range(streams.out, mp4, mp4_, written, count, quiet_);
}

}  // namespace exemplar::cli
