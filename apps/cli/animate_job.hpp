#pragma once
// The job file of `exemplar animate` (JSON, paths relative to the file); see docs/video.md.

#include <map>
#include <string>
#include <vector>

#include "exemplar/animate/animate.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::cli {

/// One painted keyframe of a job.
struct AnimateKeySpec {
    int frame = 0;      ///< Frame number (as in the frame pattern).
    std::string image;  ///< Painted frame; a 4th channel is its coverage when Ŝ has 3.
    std::string mask;   ///< Optional coverage image (channel 0), overrides the alpha.
};

/// Where one layer's inputs come from (the whole animation when the job has no layers).
struct AnimateSourceSpec {
    std::string frames;  ///< printf pattern, folder or video file.
    bool estimate_flow = true;
    bool flows_given = false;   ///< "flows" appeared (a layer without it inherits the job's).
    std::string forward_flow;   ///< Pattern: file n holds the flow n → n+1.
    std::string backward_flow;  ///< Pattern: file n holds the flow n → n−1.
    /// EXR layers of the forward and backward flow files ("" = the first 2 channels), e.g.
    /// `forward_flow` and `backward_flow` of one multi-layer render per frame.
    std::string forward_flow_layer, backward_flow_layer;
    std::string style_input, style_output;
    std::vector<AnimateKeySpec> keyframes;
    std::string style_lines;  ///< Line drawing of S (g_dt), with `lines`.
    std::string lines;        ///< Pattern of the frames' line drawings (frame numbers).
    std::string coverage;     ///< Layers: pattern of the layer's coverage per frame.
};

/// Everything a job file says. Paths are resolved against the job file's folder.
struct AnimateJob {
    AnimateSourceSpec base;                 ///< The top-level inputs.
    std::vector<AnimateSourceSpec> layers;  ///< Back to front; each inherits what it omits.
    int first = -1, last = -1;  ///< Frame numbers of a pattern, or part of a folder/video.
    std::string output;         ///< Pattern of the output frames.
    std::string mp4;            ///< Optional MP4 of the written range.
    double fps = 24.0;
    int chunk = 24;  ///< Frames per solve (0 = the whole range at once).
    animate::AnimateOptions options;
    /// The engine settings of the job file, kept apart so that a --quality given later can be
    /// applied under them (build_synthesis_options).
    std::string quality;                    ///< Empty = default.
    std::string usage;                      ///< Empty = the preset's.
    std::map<std::string, double> numeric;  ///< synthesis_option_specs() name -> value.
};

/// Sets job.options.synthesis: the quality preset (animate_synthesis_options), then the job's
/// usage and numeric options over it. Errors name `where` (the job file, or the flag).
Status build_synthesis_options(AnimateJob& job, const std::string& where);

/// Reads and checks a job file. One-line errors name the file and the key
/// (`job.json: unknown key 'framez'`).
Result<AnimateJob> load_animate_job(const std::string& path);

}  // namespace exemplar::cli
