#pragma once
// A `stylize` job: what the flags or a JSON job file ask for, before any file is read; and the
// JSON job-file reader that `stylize` and `stylit` share.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "exemplar/core/status.hpp"

namespace exemplar::cli {

struct GuideSpec {
    std::string source;
    std::string target;
    float weight = 1.0f;
    std::string weight_map;  ///< Optional per-pixel weight map on the target grid.
};

struct StylizeJob {
    std::string style;
    std::vector<GuideSpec> guides;
    std::string output;
    std::map<std::string, double> numeric;  ///< synthesis_option_specs() name -> value.
    std::string usage;                      ///< Empty = default.
    std::string vote;                       ///< Empty = default.
    std::string quality;                    ///< Empty = default; fast, default, best.
    std::vector<float> style_weights;
    std::string target_mask, source_mask, source_labels, target_labels;
    std::string source_orientation, target_orientation, init, init_nnf;
    std::string inpaint;  ///< Inpainting mask (black = the hole); sets init and both masks.
    std::string save_nnf, save_error;
    std::string size;  ///< "WxH" for unguided synthesis.
    std::optional<int> threads;
    std::optional<bool> quiet;
};

/// Where the values of a JSON job file go, by key: the long flag name without "--" ('-' or '_'
/// between words). Keys not listed are errors; a listed key absent from the file leaves its
/// destination untouched. Use `given` to see which keys the file set.
struct JobFields {
    std::map<std::string, std::string*> paths;  ///< Strings, resolved against the file's folder.
    std::map<std::string, std::vector<std::string>*> path_lists;  ///< A string or array of them.
    std::map<std::string, std::string*> words;                    ///< Strings as they are.
    std::map<std::string, double*> numbers;
    std::map<std::string, long long*> integers;
    std::map<std::string, bool*> flags;  ///< true or false.
};

/// Reads a JSON job file into `fields`; `given` (if not null) receives the keys it set, in
/// canonical '-' form. Errors name the file (and the key): missing or unreadable file, not JSON,
/// not an object, an unknown key, a value of the wrong type.
Status read_job_file(const std::string& path, const JobFields& fields,
                     std::vector<std::string>* given = nullptr);

/// Reads a `stylize` JSON job file. Keys are the long flag names ('-' or '_'); relative paths
/// resolve against the file's folder. Unknown keys and wrongly typed values are errors naming the
/// file.
Result<StylizeJob> load_job_file(const std::string& path);

/// `over` wins wherever it sets something; guides are replaced as a whole.
StylizeJob merge_jobs(const StylizeJob& base, const StylizeJob& over);

}  // namespace exemplar::cli
