#pragma once
// Reading the files of a `stylize` job into a SynthesisInput. File-level problems (missing,
// corrupt, wrong kind of file) are reported here; the semantic checks (sizes, channel counts,
// empty masks, NaN) are exemplar::validate_input's, whose messages name inputs the library's way
// ("target mask: is empty"); `name_files` turns those names into the flags and files the user
// typed ("--target-mask hole.png: is empty").

#include <string>
#include <utility>
#include <vector>

#include "exemplar/core/status.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "stylize_job.hpp"

namespace exemplar::cli {

/// The loaded inputs of a job and what each is called on the command line.
struct StylizeInput {
    SynthesisInput input;
    /// Library input name -> flag and file, e.g. {"target mask", "--target-mask hole.png"}.
    std::vector<std::pair<std::string, std::string>> names;
    /// Label maps are stored as dense indices into this list of colours (all channels of a
    /// label map pixel), shared by the source and target maps.
    std::vector<std::vector<float>> label_colours;

    /// Rewrites a message of validate_input so that it names flags and files.
    std::string name_files(const std::string& library_message) const;
};

/// Loads every file `job` names. Errors name the flag and file:
/// `style.png: no such file` (from io), `--source-labels a.png: has 3 channels but
/// --target-labels b.exr has 1`, `--target-orientation t.png: ...must be a float image...`.
Result<StylizeInput> load_stylize_input(const StylizeJob& job);

/// A mask or weight map: a 1-channel image, or a colour image whose colour channels are equal
/// (grey stored as RGB); an alpha channel must be opaque (masks are read from grey values, never
/// from transparency).
Result<Image> load_grey(const std::string& flag, const std::string& path);

/// Parses "WxH" (both ≥ 1).
Result<std::pair<int, int>> parse_size(const std::string& text);

}  // namespace exemplar::cli
