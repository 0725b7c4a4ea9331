#pragma once
/// \file
/// LazyFluids over a range of frames on files: the loop `exemplar fluid`, the studio's fluid job
/// and any other caller share (docs/fluid.md, "exemplar fluid").
///
/// Frames first..last are solved in order. Frame n reads its target alpha mask, the motion of
/// frame n − 1 to n (when there is a previous output) and, with motion blur, its own motion to
/// n + 1; the exemplar frame comes from a callback (a sequence's frame n mod its length). Each
/// output is written atomically as soon as it is done, and the next frame continues from the
/// output as read back from its file, also within one run, so a resumed or continued range gives
/// the same bytes as an uninterrupted one. Only the current and the previous frame are held:
/// memory does not grow with the range.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/fluid/lazy_fluids.hpp"

namespace exemplar::fluid {

/// Where a range's frames come from and go to, and what to do with each finished one.
struct FluidRange {
    int first = 0;  ///< First frame number.
    int last = 0;   ///< Last frame number (≥ first).
    /// Z^n: the exemplar frame of output frame n (RGBA, straight alpha). Called for every frame
    /// synthesized, and for n − 1 too when `exemplar_sequence` is set.
    std::function<Result<Image>(int n)> exemplar;
    /// The exemplar changes over the frames: frame n − 1's exemplar is the previous exemplar
    /// (FluidFrameInput::previous_exemplar). false = a still.
    bool exemplar_sequence = false;
    /// File names of frame n: its target alpha mask (channel 0), its forward motion to n + 1
    /// (.flo or EXR) and its output (RGBA PNG or EXR). Called for first − 1..last; an error for
    /// first − 1 means that there is no frame before the range.
    std::function<Result<std::string>(int n)> alpha_file, motion_file, output_file;
    /// EXR layer of the motion files (load_flow: "" = the file's two channels; "" for .flo).
    std::string motion_layer;
    /// Skip frames whose output exists; the next frame continues from the stored one.
    bool resume = true;
    /// Called after each frame with its number, its output as stored, and whether this run wrote
    /// it (false: resumed). A non-ok status stops the range.
    std::function<Status(int n, const Image& stored, bool written)> on_frame;
};

/// The exemplar of a range as `exemplar fluid --exemplar EX [--exemplar-alpha A]` and the
/// studio's fluid job open it: a still or a folder of frames (FrameSequence::from_folder), each
/// RGBA, or RGB, RGBA or grey with its alpha from `alpha_path` (an image, or a folder of as many
/// frames; channel 0). Output frame n uses frame n mod the count.
class FluidExemplar {
public:
    /// Opens `path` (and `alpha_path`, "" for none) and loads the first frame, so a bad exemplar
    /// fails here. InvalidArgument naming the file: an alpha folder of another count, an alpha of
    /// another size, an exemplar without alpha ("needs an alpha channel (RGBA), or give
    /// exemplar-alpha"); IoError for unreadable files.
    static Result<FluidExemplar> open(const std::string& path, const std::string& alpha_path = "");
    FluidExemplar(FluidExemplar&&) noexcept;
    FluidExemplar& operator=(FluidExemplar&&) noexcept;
    ~FluidExemplar();

    /// Frames: 1 for a still.
    int size() const;
    /// The files read: the exemplar's frames, then the alpha's (for sandbox checks).
    std::vector<std::string> files() const;
    /// Z^n: the frame for output frame n (RGBA, straight alpha).
    Result<Image> frame(int n);
    /// Sets `range`'s exemplar callback and exemplar_sequence to this exemplar (which must
    /// outlive the range's run).
    void use_in(FluidRange& range);

private:
    struct Impl;
    explicit FluidExemplar(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

/// Checks the range before anything runs: first ≤ last, the callbacks given, every alpha mask of
/// the range and the motion of every frame followed by another there (IoError naming the file and
/// the frame: `sim/motion/0003.flo: no such file (motion of frame 3 to 4)`).
Status check_fluid_range(const FluidRange& range);

/// Synthesizes `range` with `options`. Before anything is written, the range is checked
/// (check_fluid_range) and the options validated. The output of frame first − 1, when it and its
/// motion to `first` exist, is the first frame's previous output (a range continued). Progress
/// events are the frame's own with the fraction over the whole range; the cancel token is checked
/// before each frame and inside the synthesis (Cancelled: the frames finished so far stay, whole).
/// Errors (one line, naming the file): unreadable inputs, alpha masks, motion or a previous output
/// of other sizes than the first mask, those of synthesize_fluid_frame, write errors, on_frame's.
/// Deterministic for the inputs and options for any context.threads.
Status synthesize_fluid_range(const FluidRange& range, const FluidOptions& options,
                              const RunContext& context = {});

}  // namespace exemplar::fluid
