#pragma once
// Output files of the commands: checks made before a run starts (so that a long run does not end
// in "PNG cannot store 5 channels"), the bit depth of what is written, and the error map's scale.

#include <optional>
#include <ostream>
#include <string>
#include <string_view>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "exemplar/video/frame_sequence.hpp"

namespace exemplar::cli {

/// Checks that `path` can be created: it is not a folder, and its folder is writable or can be
/// created (writers create missing folders). `flag` names the parameter in messages (`--output
/// out/x/a.png: cannot create folder "out/x": out is a file, not a folder`).
Status check_output_path(std::string_view flag, const std::string& path);

/// Checks that the format chosen by `path`'s extension can store an image with the channels of
/// `like` in `options.format`, by writing a 1x1 image of that shape to the temporary folder.
/// The message names `flag` and `path` (e.g. `--output x.png: PNG cannot store 5 channels ...`).
Status check_output_format(std::string_view flag, const std::string& path, const Image& like,
                           const SaveOptions& options);

/// Sample format for writing a result computed from `reference` (the style, or apply-nnf's
/// source, read from `reference_path`) to `path`, so that the output keeps the input's
/// precision: PNG 16-bit if the reference file is a 16-bit PNG or its values are finer than the
/// 8-bit grid, else 8-bit; TIFF 8-bit, 16-bit or float likewise; other formats their natural
/// choice (EXR: half).
SaveOptions output_options(const Image& reference, const std::string& reference_path,
                           const std::string& path);

/// The error map as written to `path`: float formats (EXR, TIFF) keep the patch distances as
/// they are (written as float); other formats hold [0, 1], so the map is scaled to put its 99th
/// percentile at 1. Sets `options.format` accordingly.
Image error_map_for_file(const Image& error, const std::string& path, SaveOptions& options);

/// The files a synthesis run writes (`stylize`, `stylit`); empty = not written.
struct SynthesisOutputs {
    std::string output;      ///< --output: the stylized image.
    std::string save_nnf;    ///< --save-nnf: the final NNF (EXR only).
    std::string save_error;  ///< --save-error: the per-pixel patch error.
};

/// Checks made before the run: each file's folder is writable, no file is named twice, the NNF
/// is an .exr file. Messages name the flag and the path.
Status check_output_paths(const SynthesisOutputs& outputs);

/// Checks that --output can hold an image like `reference` written with `save` (its
/// `output_options`, chosen once by the caller, which writes with them too) and --save-error an
/// error map, before the run.
Status check_output_formats(const SynthesisOutputs& outputs, const Image& reference,
                            const SaveOptions& save);

/// Writes the --save-nnf and --save-error files of `result` (each atomically).
Status save_nnf_and_error(const SynthesisResult& result, const SynthesisOutputs& outputs);

/// The note printed after a run that saved an NNF: the patch size to give apply-nnf.
std::string nnf_note(const SynthesisResult& result, const SynthesisOutputs& outputs);

/// The note on what --guide-pca did ("" when it is off).
std::string guide_compression_note(const SynthesisResult& result, float guide_pca);

/// The note for SynthesisResult::unlabelled_levels: which levels could not keep the labels
/// apart (empty when all did).
std::string unlabelled_levels_note(const SynthesisResult& result);

/// True if both paths name the same file (after resolving `.`, `..` and symbolic links).
bool same_file(const std::string& a, const std::string& b);

/// Lower-case extension with the dot (".png"), or "" (the io module's).
using exemplar::lowercase_extension;

/// The end of a per-frame verb's range: closes the MP4 when one was opened and, unless `quiet`,
/// prints its path and "N frames written, M already done" (`count` frames in the range).
Status finish_frame_range(std::ostream& out, std::optional<video::Mp4Writer>& mp4,
                          const std::string& mp4_path, int written, int count, bool quiet);

}  // namespace exemplar::cli
