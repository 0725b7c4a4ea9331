// Image-space NPR over a range of render frame folders on files (npr_range.hpp): the frame loop
// of `exemplar npr` and the studio's npr job, with the bidirectional loop of §5.2.1 ("Image
// Space Texture Synthesis for 3D NPR Animation": forward, then backward along the forward flow
// with delayed disocclusions) and the paper layer.

#include "exemplar/npr/npr_range.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "exemplar/io/image_io.hpp"

namespace exemplar::npr {

namespace {

namespace fs = std::filesystem;

bool exists(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

bool all_exist(const std::vector<std::string>& files) {
    return std::all_of(files.begin(), files.end(), [](const std::string& f) { return exists(f); });
}

// The last frame of the block starting at `start`: the first frame alone, then blocks of
// `bidirectional` frames (one frame each when forward only).
int block_end(const NprRange& range, int start) {
    if (range.bidirectional == 0 || start == range.first) return start;
    return std::min(start + range.bidirectional - 1, range.last);
}

// The buffers frame n reads: those of needed_buffers, and for a backward pass the forward flow
// and occlusion in the backward flow's and disocclusion's places.
std::vector<BufferNeed> frame_needs(const NprOptions& options, bool continues, bool backward) {
    std::vector<BufferNeed> needs = needed_buffers(options, continues);
    for (BufferNeed& need : needs) {
        if (backward && need.role == BufferRole::BackwardFlow) need.name = "forward_flow";
        if (backward && need.role == BufferRole::Disocclusion) need.name = "occlusion";
    }
    return needs;
}

// The file of buffer `name` in `folder`, or the one-line error naming what is missing.
Result<std::string> buffer_file(const std::string& folder, const std::string& name) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        return io_error(folder + ": no such frame folder (from exemplar render --frames)");
    std::string path = frame_buffer_file(folder, name);
    if (path.empty()) {
        return io_error(folder + ": missing buffer '" + name + "' (" + name + ".png or " + name +
                        ".exr)");
    }
    return path;
}

// The states stored beside the output of the frame before the range, when they all exist.
std::optional<std::vector<std::string>> states_before(const NprRange& range, bool paper) {
    auto before = range.output_file(range.first - 1);
    if (!before.ok()) return std::nullopt;
    std::vector<std::string> files = state_files(*before, paper);
    if (!all_exist(files)) return std::nullopt;
    return files;
}

// A stored state (OUT.state.exr) of `pattern`.
Result<FrameState> load_state(const std::string& path, const Pattern& pattern) {
    auto packed = load_image(path);
    if (!packed.ok()) return packed.status();
    auto state = unpack_state(pattern, *packed);
    if (!state.ok()) return invalid_argument(path + ": " + state.status().message());
    return state;
}

// One run over a range: the previous frame's states and the loop's steps.
class RangeRun {
public:
    RangeRun(const Pattern& pattern, const Pattern* paper, const NprRange& range,
             const NprOptions& options, const RunContext& context)
        : pattern_(pattern), paper_(paper), range_(range), options_(options), context_(context) {}

    Status run() {
        if (auto before = states_before(range_, paper_ != nullptr))
            EXEMPLAR_RETURN_IF_ERROR(load_states(*before));
        for (int start = range_.first; start <= range_.last;) {
            if (context_.cancelled()) return cancelled();
            const int end = block_end(range_, start);
            auto done = finished(start, end);
            if (!done.ok()) return done.status();
            EXEMPLAR_RETURN_IF_ERROR(*done ? skip_block(start, end) : style_block(start, end));
            start = end + 1;
        }
        return Status::ok();
    }

private:
    // Whether every frame of the block has its output and states (and resume is on).
    Result<bool> finished(int start, int end) const {
        for (int n = start; n <= end && range_.resume; ++n) {
            auto out = range_.output_file(n);
            if (!out.ok()) return out.status();
            if (!exists(*out) || !all_exist(state_files(*out, paper_ != nullptr))) return false;
        }
        return range_.resume;
    }

    Status load_states(const std::vector<std::string>& files) {
        auto state = load_state(files[0], pattern_);
        if (!state.ok()) return state.status();
        previous_ = std::move(state).value();
        if (paper_) {
            auto paper_state = load_state(files[1], *paper_);
            if (!paper_state.ok()) return paper_state.status();
            previous_paper_ = std::move(paper_state).value();
        }
        return Status::ok();
    }

    // A finished block: its last frame's states continue the range.
    Status skip_block(int start, int end) {
        auto last_out = range_.output_file(end);
        if (!last_out.ok()) return last_out.status();
        EXEMPLAR_RETURN_IF_ERROR(load_states(state_files(*last_out, paper_ != nullptr)));
        for (int n = start; n <= end && range_.on_frame; ++n) {
            auto out = range_.output_file(n);
            if (!out.ok()) return out.status();
            EXEMPLAR_RETURN_IF_ERROR(range_.on_frame(n, *out, nullptr));
        }
        return Status::ok();
    }

    // Frame n's buffers of `needs` from its folder.
    Status load_frame(int n, const std::vector<BufferNeed>& needs, NprFrame& frame) const {
        auto folder = range_.frame_folder(n);
        if (!folder.ok()) return folder.status();
        for (const BufferNeed& need : needs) {
            auto file = buffer_file(*folder, need.name);
            if (!file.ok()) return file.status();
            auto buffer = load_image(*file);
            if (!buffer.ok()) return buffer.status();
            frame[need.role] = std::move(buffer).value();
            if (need.role == BufferRole::Tone) frame.tone_linear = file->ends_with(".exr");
        }
        return Status::ok();
    }

    // A styling error of frame n, prefixed with its folder.
    Status in_folder(int n, const Status& status) const {
        auto folder = range_.frame_folder(n);
        return Status(status.code(), (folder.ok() ? *folder : "frame " + std::to_string(n)) + ": " +
                                         status.message());
    }

    // Synthesis pass `pass` of `passes` of the block [start, start + size): its progress over the
    // whole range.
    RunContext pass_context(int start, int size, int pass, int passes) const {
        // In units of 1/passes of a frame.
        const double count = range_.last - range_.first + 1;
        return context_.part(static_cast<double>(start - range_.first) * passes + pass * size, size,
                             count * passes);
    }

    Status style_block(int start, int end) {
        const int size = end - start + 1;
        // Forward: each frame from the one before; within a bidirectional block only where the
        // point was visible in every frame since the block's start (the delayed visibility)
        std::vector<NprFrameResult> results;
        std::vector<Image> visible;
        const bool loop = range_.bidirectional > 0 && previous_.has_value();
        const int passes = loop ? 2 * size - 1 : size;
        for (int n = start; n <= end; ++n) {
            NprFrame frame;
            EXEMPLAR_RETURN_IF_ERROR(
                load_frame(n, frame_needs(options_, previous_.has_value(), false), frame));
            if (loop) {
                auto seen = delayed_visibility(visible.empty() ? Image() : visible.back(),
                                               frame.disocclusion, frame.backward_flow);
                if (!seen.ok()) return in_folder(n, seen.status());
                frame.disocclusion = *seen;
                for (float& v : frame.disocclusion.data()) v = 1.0f - v;
                visible.push_back(std::move(seen).value());
            }
            NprPaper paper_layer;
            if (paper_) {
                paper_layer.pattern = paper_;
                paper_layer.previous = previous_paper_ ? &*previous_paper_ : nullptr;
            }
            auto styled =
                stylize_frame(pattern_, frame, previous_ ? &*previous_ : nullptr, n, options_,
                              pass_context(start, size, n - start, passes), paper_layer);
            if (!styled.ok()) return in_folder(n, styled.status());
            previous_ = styled->state;
            if (paper_) previous_paper_ = styled->paper_state;
            results.push_back(std::move(styled).value());
        }
        // The forward states are held only for their coordinates now (a block of 20 frames at
        // 960x540 keeps ~7 MB per frame instead of ~25)
        for (std::size_t i = 0; loop && i + 1 < results.size(); ++i) {
            for (FrameState* state : {&results[i].state, &results[i].paper_state}) {
                state->appearance.clear();
                state->screen = Image();
            }
        }
        // Backward: the rest of each frame coherent with the next (its forward flow and
        // occlusion), the visible part held
        for (int n = end - 1; loop && n >= start; --n) {
            const auto i = static_cast<std::size_t>(n - start);
            NprFrame frame;
            EXEMPLAR_RETURN_IF_ERROR(load_frame(n, frame_needs(options_, true, true), frame));
            frame.hold = visible[i];
            frame.held = &results[i].state;
            NprPaper paper_layer;
            if (paper_) {
                paper_layer.pattern = paper_;
                paper_layer.previous = &results[i + 1].paper_state;
                paper_layer.held = &results[i].paper_state;
            }
            auto styled =
                stylize_frame(pattern_, frame, &results[i + 1].state, n, options_,
                              pass_context(start, size, size + (end - 1 - n), passes), paper_layer);
            if (!styled.ok()) return in_folder(n, styled.status());
            results[i] = std::move(styled).value();
        }
        // Write the block's frames, each with its states first
        for (int n = start; n <= end; ++n) {
            const NprFrameResult& styled = results[static_cast<std::size_t>(n - start)];
            auto out = range_.output_file(n);
            if (!out.ok()) return out.status();
            const std::vector<std::string> states = state_files(*out, paper_ != nullptr);
            SaveOptions state_options;
            state_options.format = PixelFormat::Float;
            EXEMPLAR_RETURN_IF_ERROR(
                save_image(pack_state(styled.state), states[0], state_options));
            if (paper_) {
                EXEMPLAR_RETURN_IF_ERROR(
                    save_image(pack_state(styled.paper_state), states[1], state_options));
            }
            EXEMPLAR_RETURN_IF_ERROR(save_image(styled.image, *out));
            if (range_.on_frame) EXEMPLAR_RETURN_IF_ERROR(range_.on_frame(n, *out, &styled.image));
        }
        return Status::ok();
    }

    const Pattern& pattern_;
    const Pattern* paper_;
    const NprRange& range_;
    const NprOptions& options_;
    const RunContext& context_;
    std::optional<FrameState> previous_, previous_paper_;  ///< The previous frame's states.
};

}  // namespace

std::vector<std::string> state_files(const std::string& output, bool paper) {
    std::vector<std::string> files{output + ".state.exr"};
    if (paper) files.push_back(output + ".paper.state.exr");
    return files;
}

Status validate(const NprRange& range) {
    if (range.last < range.first) {
        return invalid_argument("last: " + std::to_string(range.last) + " is before first " +
                                std::to_string(range.first));
    }
    if (!range.frame_folder || !range.output_file)
        return invalid_argument("the range needs frame folders and output files");
    if (range.bidirectional < 0 || range.bidirectional == 1 || range.bidirectional > 1000) {
        return invalid_argument("bidirectional: " + std::to_string(range.bidirectional) +
                                " is invalid (must be 0 or 2..1000)");
    }
    return Status::ok();
}

Status check_npr_range(const NprRange& range, const NprOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(validate(range));
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    bool continues = states_before(range, options.paper).has_value();
    for (int start = range.first; start <= range.last;) {
        const int end = block_end(range, start);
        const bool loop = range.bidirectional > 0 && continues;
        for (int n = start; n <= end; ++n) {
            auto folder = range.frame_folder(n);
            if (!folder.ok()) return folder.status();
            std::vector<BufferNeed> needs = frame_needs(options, continues, false);
            if (loop && n < end) {
                for (BufferNeed& need : frame_needs(options, true, true))
                    needs.push_back(std::move(need));
            }
            for (const BufferNeed& need : needs)
                EXEMPLAR_RETURN_IF_ERROR(buffer_file(*folder, need.name).status());
            continues = true;
        }
        start = end + 1;
    }
    return Status::ok();
}

Status stylize_range(const Pattern& pattern, const Pattern* paper, const NprRange& range,
                     const NprOptions& options, const RunContext& context) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    EXEMPLAR_RETURN_IF_ERROR(validate(range));
    if (options.paper != (paper != nullptr)) {
        return invalid_argument(options.paper ? "paper: the paper layer needs a paper texture"
                                              : "paper: a paper texture without the paper layer");
    }
    return RangeRun(pattern, paper, range, options, context).run();
}

}  // namespace exemplar::npr
