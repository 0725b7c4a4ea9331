#pragma once
// A `stylize` job: what the flags or a JSON job file ask for, before any file is read.

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
    std::vector<float> style_weights;
    std::string target_mask, source_mask, source_labels, target_labels;
    std::string source_orientation, target_orientation, init, init_nnf;
    std::string save_nnf, save_error;
    std::string size;  ///< "WxH" for unguided synthesis.
    std::optional<int> threads;
    std::optional<bool> quiet;
};

/// Reads a JSON job file. Keys are the long flag names ('-' or '_'); relative paths resolve
/// against the file's folder. Unknown keys and wrongly typed values are errors naming the file.
Result<StylizeJob> load_job_file(const std::string& path);

/// `over` wins wherever it sets something; guides are replaced as a whole.
StylizeJob merge_jobs(const StylizeJob& base, const StylizeJob& over);

}  // namespace exemplar::cli
