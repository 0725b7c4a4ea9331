#pragma once
// The subcommands of `exemplar`. Each registers its flags on a CLI11 subcommand and runs after
// parsing. Grammar errors found after CLI11's own parsing (a --weight before any --guide, a
// missing --style) are thrown as CLI::ParseError like CLI11's own, so that run_cli maps them to
// exit code 2 with the rest; every other problem is the returned Status (exit code 1).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "exemplar/core/status.hpp"
#include "exemplar/fluid/lazy_fluids.hpp"
#include "exemplar/noisy/noisy.hpp"
#include "exemplar/paint/directions.hpp"
#include "exemplar/paint/feature_brush.hpp"
#include "exemplar/paint/feature_fill.hpp"
#include "exemplar/paint/paint.hpp"
#include "exemplar/render/render.hpp"
#include "exemplar/synth/options.hpp"
#include "studio.hpp"
#include "stylize_job.hpp"

namespace exemplar::cli {

/// Where a command writes: normal output (the written file's path), errors and the progress bar.
struct Streams {
    std::ostream& out;
    std::ostream& err;
    bool err_is_terminal = false;
};

/// `exemplar stylize`: ebsynth-style guides, job files, input checks, the run and its outputs.
class StylizeCommand {
public:
    /// Adds the `stylize` subcommand and its flags to `app`.
    explicit StylizeCommand(CLI::App& app);
    StylizeCommand(const StylizeCommand&) = delete;
    StylizeCommand& operator=(const StylizeCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams);

private:
    StylizeJob job_from_flags();

    CLI::App* app_ = nullptr;
    StylizeJob flag_job_;  // paths and words bound directly by CLI11
    std::string config_;
    std::vector<std::pair<std::string, std::string>> guide_files_;  // (SRC, TGT) per --guide
    std::vector<float> weights_;
    std::vector<std::string> weight_maps_;
    std::string style_weights_;
    std::map<std::string, double> numeric_values_;
    std::map<std::string, CLI::Option*> numeric_flags_;
    int threads_ = 0;
    bool quiet_ = false;
    bool help_all_ = false;  // --help-all: the help lists the expert options too
    CLI::Option* guide_flag_ = nullptr;
    CLI::Option* weight_flag_ = nullptr;
    CLI::Option* weight_map_flag_ = nullptr;
    CLI::Option* threads_flag_ = nullptr;
    CLI::Option* quiet_flag_ = nullptr;
};

/// `exemplar apply-nnf`: re-applies a saved NNF to another image on the style's grid.
class ApplyNnfCommand {
public:
    /// Adds the `apply-nnf` subcommand and its flags to `app`.
    explicit ApplyNnfCommand(CLI::App& app);
    ApplyNnfCommand(const ApplyNnfCommand&) = delete;
    ApplyNnfCommand& operator=(const ApplyNnfCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    std::string nnf_, source_, output_, vote_ = "weighted";
    int patch_size_ = 0;
    int vote_size_ = 3;  // as stylize's --final-vote-size default
    float vote_coherence_ = SynthesisOptions{}.vote_coherence;  // as stylize's default
    bool vote_seams_ = false;                                   // as stylize's default
    int threads_ = 0;
    bool quiet_ = false;
};

/// `exemplar render`: path-traces a built-in or JSON scene into light-path buffers.
class RenderCommand {
public:
    /// Adds the `render` subcommand and its flags to `app`.
    explicit RenderCommand(CLI::App& app);
    RenderCommand(const RenderCommand&) = delete;
    RenderCommand& operator=(const RenderCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    std::string scene_, output_, format_ = "png", frames_;
    int frame_ = 0;
    render::RenderOptions options_;
    int threads_ = 0;
    bool quiet_ = false;
};

/// `exemplar stylit` (+ `stylit sheet`, `stylit align`): the StyLit workflow; see docs/stylit.md.
class StylitCommand {
public:
    /// Adds the `stylit` subcommand, its sub-subcommands and their flags to `app`.
    explicit StylitCommand(CLI::App& app);
    StylitCommand(const StylitCommand&) = delete;
    StylitCommand& operator=(const StylitCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command (stylize, sheet or align).
    Status run(const Streams& streams);

private:
    Status run_stylize(const Streams& streams);
    Status apply_job_file();
    Status run_sheet(const Streams& streams);
    Status run_align(const Streams& streams);

    CLI::App* app_ = nullptr;
    CLI::App* sheet_ = nullptr;
    CLI::App* align_ = nullptr;
    std::string exemplar_, output_, preset_ = "exemplar", layers_, usage_, quality_;
    std::string save_nnf_, save_error_, config_;
    std::vector<std::string> source_, target_;
    float guidance_weight_ = 2.0f;
    std::uint64_t seed_ = 1;
    bool preview_ = false;
    int threads_ = 0;
    bool quiet_ = false;
    std::string sheet_render_, sheet_png_, sheet_pdf_, paper_ = "a4";
    double dpi_ = 0.0;
    std::vector<float> grey_range_ = {0.72f, 0.95f};
    std::string scan_, align_render_, align_output_;
};

/// `exemplar flow`: optical flow between two frames, backward flow and occlusion mask.
class FlowCommand {
public:
    /// Adds the `flow` subcommand and its flags to `app`.
    explicit FlowCommand(CLI::App& app);
    FlowCommand(const FlowCommand&) = delete;
    FlowCommand& operator=(const FlowCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    std::string from_, to_, output_, backward_, occlusion_, preset_ = "medium";
    float epsilon_ = 2.0f;
    bool quiet_ = false;
};

/// `exemplar directions`: the signed direction field of an exemplar and its preview.
class DirectionsCommand {
public:
    /// Adds the `directions` subcommand and its flags to `app`.
    explicit DirectionsCommand(CLI::App& app);
    DirectionsCommand(const DirectionsCommand&) = delete;
    DirectionsCommand& operator=(const DirectionsCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    std::string input_, output_, preview_;
    paint::DirectionAnalysisOptions options_;
    int threads_ = 0;
    bool quiet_ = false;
};

/// `exemplar paint`: Brushables texture painting along strokes from a JSON or SVG file.
class PaintCommand {
public:
    /// Adds the `paint` subcommand and its flags to `app`.
    explicit PaintCommand(CLI::App& app);
    PaintCommand(const PaintCommand&) = delete;
    PaintCommand& operator=(const PaintCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    std::string source_, source_mask_, source_directions_, source_labels_, strokes_, output_,
        canvas_;
    std::string save_directions_;
    std::string usage_ = "none";
    int width_ = 0;
    int height_ = 0;
    paint::PaintOptions options_;
    int threads_ = 0;
    bool quiet_ = false;
};

/// `exemplar brush`: paints paths with a line feature selected in a palette image (Painting by
/// Feature, docs/feature.md).
class BrushCommand {
public:
    /// Adds the `brush` subcommand and its flags to `app`.
    explicit BrushCommand(CLI::App& app);
    BrushCommand(const BrushCommand&) = delete;
    BrushCommand& operator=(const BrushCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    std::string palette_, feature_, path_, output_, canvas_, walk_ = "randomized";
    int width_ = 0;
    int height_ = 0;
    float brush_width_ = 0.0f;
    std::uint64_t seed_ = 1;
    bool snap_ = true;
    std::map<std::string, double> numeric_values_;
    std::map<std::string, CLI::Option*> numeric_flags_;
    int threads_ = 0;
    bool quiet_ = false;
};

/// `exemplar fill`: fills a canvas region with the texture of a palette region (Painting by
/// Feature's area-feature fill, docs/feature.md).
class FillCommand {
public:
    /// Adds the `fill` subcommand and its flags to `app`.
    explicit FillCommand(CLI::App& app);
    FillCommand(const FillCommand&) = delete;
    FillCommand& operator=(const FillCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    std::string palette_, source_region_, target_region_, canvas_, output_;
    std::string usage_{to_string(paint::FeatureFillOptions{}.usage)};
    std::uint64_t seed_ = 1;
    std::map<std::string, double> numeric_values_;
    std::map<std::string, CLI::Option*> numeric_flags_;
    int threads_ = 0;
    bool quiet_ = false;
};

/// `exemplar vectorize-style`: renders an SVG drawing with line features on its stroked paths and
/// area features in its filled shapes (Painting by Feature's vector stylization, docs/feature.md).
class VectorizeStyleCommand {
public:
    /// Adds the `vectorize-style` subcommand and its flags to `app`.
    explicit VectorizeStyleCommand(CLI::App& app);
    VectorizeStyleCommand(const VectorizeStyleCommand&) = delete;
    VectorizeStyleCommand& operator=(const VectorizeStyleCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    std::string drawing_, palette_, output_, walk_ = "randomized";
    std::string usage_{to_string(paint::FeatureFillOptions{}.usage)};
    int width_ = 0;
    std::uint64_t seed_ = 1;
    std::map<std::string, double> numeric_values_;
    std::map<std::string, CLI::Option*> numeric_flags_;
    int threads_ = 0;
    bool quiet_ = false;
};

/// `exemplar beautify`: ShipShape beautification of an SVG sketch, stroke by stroke.
class BeautifyCommand {
public:
    /// Adds the `beautify` subcommand and its flags to `app`.
    explicit BeautifyCommand(CLI::App& app);
    BeautifyCommand(const BeautifyCommand&) = delete;
    BeautifyCommand& operator=(const BeautifyCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    std::string input_, output_, report_, suggestions_, preview_;
    int max_suggestions_ = 10;
    double fit_px_ = 0.0;
    bool quiet_ = false;
};

/// `exemplar animate`: temporally coherent stylization of a frame sequence from a job file.
class AnimateCommand {
public:
    /// Adds the `animate` subcommand and its flags to `app`.
    explicit AnimateCommand(CLI::App& app);
    AnimateCommand(const AnimateCommand&) = delete;
    AnimateCommand& operator=(const AnimateCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    CLI::Option* seed_flag_ = nullptr;
    std::string job_path_, frames_, output_, mp4_, quality_;
    int chunk_ = -1;
    int threads_ = 0;
    std::uint64_t seed_ = 1;
    bool resume_ = true;
    bool quiet_ = false;
};

/// `exemplar fluid` (+ `fluid simulate`): LazyFluids over a frame range, and targets from the
/// stable-fluids solver; see docs/fluid.md.
class FluidCommand {
public:
    /// Adds the `fluid` subcommand, its `simulate` subcommand and their flags to `app`.
    explicit FluidCommand(CLI::App& app);
    FluidCommand(const FluidCommand&) = delete;
    FluidCommand& operator=(const FluidCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command (the transfer or the simulation).
    Status run(const Streams& streams);

private:
    Status run_transfer(const Streams& streams);
    Status run_simulate(const Streams& streams) const;
    Status apply_config(fluid::FluidOptions& options);

    CLI::App* app_ = nullptr;
    CLI::App* simulate_ = nullptr;
    CLI::Option* seed_flag_ = nullptr;
    std::string config_, exemplar_, exemplar_alpha_, alpha_, motion_, motion_layer_, output_, mp4_;
    std::string usage_;
    std::optional<int> first_, last_;
    double fps_ = 24.0;
    std::map<std::string, double> numeric_values_;
    std::map<std::string, CLI::Option*> numeric_flags_;
    bool rotations_ = false;
    int threads_ = 0;
    std::uint64_t seed_ = 1;
    bool resume_ = true;
    bool quiet_ = false;
    // simulate
    std::string scene_, sim_output_;
    int width_ = 256;
    int height_ = 256;
    int frames_ = 0;
};

/// `exemplar noisy`: Color Me Noisy over a frame range (docs/noisy.md).
class NoisyCommand {
public:
    /// Adds the `noisy` subcommand and its flags to `app`.
    explicit NoisyCommand(CLI::App& app);
    NoisyCommand(const NoisyCommand&) = delete;
    NoisyCommand& operator=(const NoisyCommand&) = delete;
    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command.
    Status run(const Streams& streams);

private:
    using NoisyOptions = noisy::NoisyOptions;
    Status apply_config();
    CLI::App* app_ = nullptr;
    // Several --exemplar (and as many --exemplar-orientation) with a --source-map (§4.3.3).
    std::vector<std::string> exemplars_, exemplar_orientations_;
    std::string frames_, output_, noise_map_, source_map_, mp4_, filter_ = "box", config_;
    std::string frame_orientation_;
    int first_ = 0, last_ = 0;
    bool first_given_ = false, last_given_ = false;
    double fps_ = 24.0;
    std::uint64_t seed_ = 1;
    int threads_ = 0;
    bool resume_ = true;
    bool quiet_ = false;
    std::map<std::string, double> numeric_values_;
    std::map<std::string, CLI::Option*> numeric_flags_;
    std::set<std::string> numeric_from_config_;
};

/// `exemplar npr`: image-space stippling, hatching and halftoning of the frame folders of
/// `exemplar render --frames`; see docs/npr.md.
class NprCommand {
public:
    /// Adds the `npr` subcommand and its flags to `app`.
    explicit NprCommand(CLI::App& app);
    NprCommand(const NprCommand&) = delete;
    NprCommand& operator=(const NprCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Runs the parsed command over the frame range.
    Status run(const Streams& streams);

private:
    CLI::App* app_ = nullptr;
    std::string pattern_, frames_, output_, mp4_, paper_;
    double fps_ = 24.0;
    std::string style_ = "stipple";
    std::optional<std::string> tone_;
    std::optional<std::string> orientation_;
    int first_ = 0;
    int last_ = 0;
    // The library's option table (levels, patch-size, coherence-weight), by name
    int bidirectional_ = 0;
    std::map<std::string, double> numeric_values_;
    std::map<std::string, CLI::Option*> numeric_flags_;
    int threads_ = 0;
    std::uint64_t seed_ = 1;
    bool lines_ = true;
    bool tone_correction_ = true;
    bool resume_ = true;
    bool quiet_ = false;
};

/// `exemplar studio`: the local web app (docs/studio.md) until SIGINT or SIGTERM.
class StudioCommand {
public:
    /// Adds the `studio` subcommand and its flags to `app`.
    explicit StudioCommand(CLI::App& app);
    StudioCommand(const StudioCommand&) = delete;
    StudioCommand& operator=(const StudioCommand&) = delete;

    bool parsed() const { return app_->parsed(); }
    /// Serves until a signal arrives, then shuts down cleanly.
    Status run(const Streams& streams) const;

private:
    CLI::App* app_ = nullptr;
    studio::StudioOptions options_;
    double max_upload_mib_ = 32.0;
};

}  // namespace exemplar::cli
