#pragma once
/// \file
/// Color Me Noisy over a range of frames on files: the loop `exemplar noisy`, the studio's noisy
/// job and any other caller share (docs/noisy.md, "Command").
///
/// Frames are independent (noisy.hpp), so the range runs them in batches: when at least as many
/// frames are left to make as there are threads, a batch of that many frames runs in parallel
/// with one thread each, otherwise one frame at a time with all threads; either way every frame
/// is the same bytes. Frames whose output exists are skipped (resume); each output is written
/// atomically as soon as it is done, so a stopped range leaves whole frames and no partial file.

#include <cstddef>
#include <functional>
#include <span>
#include <string>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/noisy/noisy.hpp"

namespace exemplar::noisy {

/// Ok if `path` names a file that can hold an orientation field: angles in radians need a float
/// format (EXR or float TIFF, by the extension). InvalidArgument otherwise: `O.png: an
/// orientation field holds angles in radians and needs a float format (EXR or float TIFF)`.
Status check_orientation_file(const std::string& path);

/// Loads an orientation field (check_orientation_file first): its first channel. Errors as
/// check_orientation_file's, or the loader's naming the file.
Result<Image> load_orientation_field(const std::string& path);

/// Loads a noise map (values in [0, 1]): the first channel, so a grey map saved as RGB(A) works.
Result<Image> load_noise_map(const std::string& path);

/// Loads a source map for `sources` media: the first channel, grey level k (of 255) naming the
/// k-th medium, checked with check_source_map; its message names the file
/// (`M/0004.png: value 2 at (5, 9) has no source (2 given: 0..1)`).
Result<Image> load_source_map(const std::string& path, std::size_t sources);

/// A per-pixel input of a range (noise map, source map, frame orientation): none, one file for
/// every frame, or a file per frame.
struct RangeInput {
    /// The file of frame n; an empty function = the range has no such input.
    std::function<Result<std::string>(int n)> file;
    /// true: file(n) is read for each frame n; false: file(first) is read once, before any
    /// frame, and used for every frame.
    bool per_frame = false;
};

/// Where a range's frames come from and go to, and what to do with each finished one.
struct NoisyRange {
    int first = 0;  ///< First frame number; also the frame index the randomness is keyed by.
    int last = 0;   ///< Last frame number (≥ first).
    /// Reads reference frame R_n (errors should name the file). Called on the caller's thread in
    /// increasing n, once for every frame made, so a video decoder can serve it.
    std::function<Result<Image>(int n)> reference;
    /// The name of reference frame n in messages (its file, or a video's "clip.mp4 frame 3").
    std::function<std::string(int n)> reference_name;
    /// The output file of frame n; its extension picks the format.
    std::function<Result<std::string>(int n)> output_file;
    SaveOptions save;  ///< How outputs are written (save_image).
    /// Optional inputs, each on the reference's grid: the per-pixel noise strength
    /// (load_noise_map), the medium of each pixel (load_source_map; required with several
    /// media) and the frame's orientation field (load_orientation_field; needed when the media
    /// have orientation fields, refused otherwise).
    RangeInput noise_map, source_map, orientation;
    /// Skip frames whose output exists.
    bool resume = true;
    /// Called on the caller's thread after each frame written, in increasing n, with its output
    /// file. A non-ok status stops the range.
    std::function<Status(int n, const std::string& path)> on_frame;
};

/// Synthesizes frames first..last of `range` from `sources` (the media, in source-map order,
/// each with its orientation field or none) with `options`. Before any frame: the options are
/// validated and the one-file inputs read. Frames are read, checked and made in batches as the
/// file's comment says; a bad input stops the range before its batch (the frames before it
/// stay). Progress: with one frame at a time, the frame's events with the fraction over the
/// frames to make; with parallel frames, one event (stage "frame") after each batch. The cancel
/// token is checked before each batch and inside every frame (Cancelled: the frames finished so
/// far stay, whole). Errors (one line, naming the file): those of the readers and loaders; a
/// frame of another size than the first one read (`R/0003.png: is 40x32 but R/0001.png is
/// 32x32`); a map of another size than its frame (`M/0003.png: is 30x32 but R/0003.png is
/// 32x32`); synthesize_frame's, prefixed with the frame's name; write errors; on_frame's.
/// Deterministic for the inputs and options for any context.threads.
Status synthesize_range(std::span<const NoisySource> sources, const NoisyRange& range,
                        const NoisyOptions& options, const RunContext& context = {});

}  // namespace exemplar::noisy
