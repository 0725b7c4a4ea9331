#pragma once
/// \file
/// Image-space NPR over a range of render frame folders on files: the loop `exemplar npr`, the
/// studio's npr job and any other caller share (docs/npr.md, "exemplar npr").
///
/// Frames first..last are styled in order (npr::stylize_frame), each continuing from the one
/// before. Each output is written atomically with its synthesis state beside it (OUT.state.exr;
/// with the paper layer also OUT.paper.state.exr: state_files) as soon as it is done, the states
/// first. A frame whose output and states exist is skipped (resume) and its states read back as
/// the next frame's previous one, so a resumed range gives the same bytes as an uninterrupted
/// one; a finished frame just before the range hands its states over the same way (a range
/// continued). With `bidirectional` N the frames after the first go in blocks of N: forward, then
/// backward along the forward flow with the part visible since the block's start held (§5.2.1),
/// then written together; resume skips or redoes whole blocks. Only one block's results are held.

#include <functional>
#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/npr/npr.hpp"

namespace exemplar::npr {

/// Where a range's frames come from and go to, how they are looped, and what to do with each
/// finished one.
struct NprRange {
    int first = 0;  ///< First frame number.
    int last = 0;   ///< Last frame number (≥ first).
    /// The frame folder of frame n (`exemplar render --frames`); called for first..last. Errors
    /// name the folder as this returns it.
    std::function<Result<std::string>(int n)> frame_folder;
    /// The output file of frame n (a PNG; its states go beside it, state_files); called for
    /// first − 1..last. An error for first − 1 means that there is no frame before the range.
    std::function<Result<std::string>(int n)> output_file;
    /// The bidirectional loop with delayed disocclusions (§5.2.1): an update frame every
    /// `bidirectional` frames, the frames between done forward, then backward along the forward
    /// flow (they read `forward_flow` and `occlusion` too). 0 = forward only (the default);
    /// range 2..1000.
    int bidirectional = 0;
    /// Skip frames (blocks) whose output and states exist; the next continues from the stored
    /// states. false = every frame is styled and written again.
    bool resume = true;
    /// Called after each frame is written or skipped, in frame order (a block's frames after the
    /// whole block), with its number, its output file and its image (null when resumed: the file
    /// holds it). A non-ok status stops the range.
    std::function<Status(int n, const std::string& output, const Image* image)> on_frame;
};

/// The state files of output file `output`: `output`.state.exr and, with the paper layer,
/// `output`.paper.state.exr.
std::vector<std::string> state_files(const std::string& output, bool paper);

/// Checks the range's own settings: first ≤ last (`last: 2 is before first 5`), the callbacks
/// given, `bidirectional` 0 or 2..1000 (`bidirectional: 1 is invalid (must be 0 or 2..1000)`).
Status validate(const NprRange& range);

/// Checks, before anything runs, what a whole run of `range` reads: validate(range), every frame
/// folder, and every buffer its frames read under `options` (needed_buffers, continuing from
/// the frame before the range when its states exist; `forward_flow` and `occlusion` for the
/// backward passes). IoError naming the folder: `R/frame_0002: missing buffer 'backward_flow'
/// (backward_flow.png or backward_flow.exr)`, `R/frame_0009: no such frame folder (from
/// exemplar render --frames)`. For callers that want all or nothing; stylize_range itself stops
/// at the first missing buffer with the same message and keeps the frames finished before it.
Status check_npr_range(const NprRange& range, const NprOptions& options);

/// Styles `range` with `pattern` (prepare_pattern with `options`) and, with options.paper, the
/// paper layer `paper` (prepared likewise; null without it, required with it). The options and
/// validate(range) are checked first. Progress events are stylize_frame's with the fraction
/// over the whole range (a bidirectional block's backward passes counted); the cancel token is
/// checked before each block and inside the synthesis (Cancelled: the frames written so far
/// stay, whole, with their states). Errors (one line): a missing frame folder or buffer (as
/// check_npr_range), stylize_frame's prefixed with the frame's folder
/// (`R/frame_0001: buffer 'lines' is 64x48 but the frames are 96x64`), unreadable buffers or
/// states, write errors, on_frame's. Deterministic for the inputs and options for any
/// context.threads.
Status stylize_range(const Pattern& pattern, const Pattern* paper, const NprRange& range,
                     const NprOptions& options, const RunContext& context = {});

}  // namespace exemplar::npr
