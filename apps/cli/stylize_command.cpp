// `exemplar stylize`: flags -> job (+ job file) -> options and output checks -> input files ->
// validate_input -> synthesize -> write the outputs.

#include <algorithm>
#include <sstream>

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "option_help.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"
#include "stylize_input.hpp"

namespace exemplar::cli {

namespace {

constexpr const char* kFooter =
    "Guides follow ebsynth's order: each --weight (and --weight-map) applies to the --guide\n"
    "before it; a guide without --weight has weight 1. Example:\n"
    "  exemplar stylize --style S.png --guide A1.png B1.png --weight 0.5 \\\n"
    "                   --guide A2.png B2.png -o out.png --save-nnf out_nnf.exr\n"
    "Job files (--config) take the same options as JSON keys; see docs/cli.md.";

std::vector<float> parse_floats(const std::string& text, const char* flag) {
    std::vector<float> values;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        std::size_t used = 0;
        float value = 0.0f;
        try {
            value = std::stof(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != item.size()) {
            throw CLI::ValidationError(flag, "'" + item + "' is not a number (expected w1,w2,...)");
        }
        values.push_back(value);
    }
    return values;
}

Status build_options(const StylizeJob& job, SynthesisOptions& options) {
    // The quality preset first (default when not given), so that explicit options override it.
    auto quality =
        job.quality.empty() ? Result<Quality>(Quality::Default) : parse_quality(job.quality);
    if (!quality.ok()) return quality.status();
    options = SynthesisOptions::preset(*quality);
    for (const auto& [name, value] : job.numeric) {
        const OptionSpec* spec = find_option(name);
        if (spec == nullptr) return invalid_argument("unknown option '" + name + "'");
        EXEMPLAR_RETURN_IF_ERROR(set_option(options, *spec, value));
    }
    if (!job.usage.empty()) {
        auto usage = parse_usage_strategy(job.usage);
        if (!usage.ok()) return usage.status();
        options.usage = *usage;
    }
    if (!job.vote.empty()) {
        auto vote = parse_vote_mode(job.vote);
        if (!vote.ok()) return vote.status();
        options.vote = *vote;
    }
    return Status::ok();
}

SynthesisOutputs outputs_of(const StylizeJob& job) {
    return {job.output, job.save_nnf, job.save_error};
}

Status with_names(const Status& status, const StylizeInput& loaded) {
    if (status.is_ok()) return status;
    return Status(status.code(), loaded.name_files(status.message()));
}

}  // namespace

StylizeCommand::StylizeCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "stylize",
        "Transfer the style of an exemplar onto a target through guide pairs (image analogies "
        "A : A' :: B : B')");
    // --help-all adds the search-tuning knobs, which --help leaves out.
    app_->footer([this] { return help_all_ ? expert_options_help() + "\n" + kFooter : kFooter; });
    app_->add_flag_callback(
            "--help-all",
            [this] {
                help_all_ = true;
                throw CLI::CallForHelp();
            },
            "Print this help with the search-tuning options for experts and exit")
        ->trigger_on_parse();
    // Unexpected arguments are reported after the guide checks (job_from_flags), which explain
    // `--guide a.png -w 1` better than "1 was not expected".
    app_->allow_extras();
    CLI::App& app = *app_;

    app.add_option("--style,-s", flag_job_.style, "Style exemplar A' (any channels; alpha is one)")
        ->group(kInputs);
    guide_flag_ = app.add_option("--guide,-g", guide_files_,
                                 "Guide pair SRC TGT: SRC on the style's grid (A_i), TGT on the "
                                 "target grid (B_i); repeat for more guides")
                      ->allow_extra_args(false)
                      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
                      ->group(kInputs);
    weight_flag_ = app.add_option("--weight,-w", weights_,
                                  "Weight (>= 0) of the preceding --guide; a guide without one has "
                                  "weight 1")
                       ->expected(1)
                       ->allow_extra_args(false)
                       ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
                       ->group(kInputs);
    weight_map_flag_ = app.add_option("--weight-map", weight_maps_,
                                      "Per-pixel multiplier (grey, >= 0, target size) of the "
                                      "preceding --guide's weight")
                           ->expected(1)
                           ->allow_extra_args(false)
                           ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
                           ->group(kInputs);
    app.add_option("--style-weights", style_weights_,
                   "Comma-separated weights of the style channels (default 1 each)")
        ->group(kInputs);
    app.add_option("--target-mask", flag_job_.target_mask,
                   "Synthesize only where this grey mask is > 0.5; keep --init elsewhere")
        ->group(kInputs);
    app.add_option("--source-mask", flag_job_.source_mask,
                   "Use only style patches entirely inside this grey mask (> 0.5)")
        ->group(kInputs);
    app.add_option("--inpaint", flag_job_.inpaint,
                   "Fill the hole of --style where this mask is black (<= 0.5) from the rest, "
                   "which stays as it is (sets --init and both masks; JPEG masks are fine)")
        ->group(kInputs);
    app.add_option("--source-labels", flag_job_.source_labels,
                   "Label map on the style's grid (each distinct colour is a label); with "
                   "--target-labels")
        ->group(kInputs);
    app.add_option("--target-labels", flag_job_.target_labels,
                   "Label map on the target grid: a pixel takes only patches of its label")
        ->group(kInputs);
    app.add_option("--source-orientation", flag_job_.source_orientation,
                   "Orientation field of the style (1 channel, radians, float file such as EXR)")
        ->group(kInputs);
    app.add_option("--target-orientation", flag_job_.target_orientation,
                   "Orientation field of the target: patches rotate by the difference")
        ->group(kInputs);
    app.add_option("--init", flag_job_.init, "Initial target image (the style's channels)")
        ->group(kInputs);
    app.add_option("--init-nnf", flag_job_.init_nnf, "Initial NNF, as written by --save-nnf")
        ->group(kInputs);
    app.add_option("--size", flag_job_.size,
                   "Target size WxH for unguided texture synthesis (no --guide)")
        ->group(kInputs);
    app.add_option("--config", config_,
                   "JSON job file with the same options (long names as keys); flags override it")
        ->group(kInputs);

    app.add_option("--output,-o", flag_job_.output,
                   "Output image; format from the extension (required, here or in --config)")
        ->group(kOutputs);
    app.add_option("--save-nnf", flag_job_.save_nnf,
                   "Write the final NNF (EXR: x, y, angle, error) for apply-nnf")
        ->group(kOutputs);
    app.add_option("--save-error", flag_job_.save_error,
                   "Write the per-pixel patch error (EXR/TIFF: as is; PNG etc.: scaled, 99th "
                   "percentile = white)")
        ->group(kOutputs);

    app.add_option("--usage", flag_job_.usage,
                   "Patch-usage strategy: none, uniform, error-budget (default), occurrence")
        ->group(kSynthesis);
    app.add_option("--vote", flag_job_.vote, "Voting: average or weighted (default)")
        ->group(kSynthesis);
    app.add_option("--quality", flag_job_.quality,
                   "Search effort: fast (previews), default, best (closer to the exemplar, "
                   "slower); the tuning flags of --help-all override it")
        ->group(kSynthesis);
    for (const OptionSpec& spec : synthesis_option_specs()) {
        const std::string name(spec.name);
        // The tuning knobs are hidden from --help (group ""); --help-all lists them.
        numeric_flags_[name] = app.add_option("--" + name, numeric_values_[name], describe(spec))
                                   ->type_name(is_integer_option(spec) ? "INT" : "FLOAT")
                                   ->group(is_expert_option(spec) ? "" : kSynthesis);
    }

    threads_flag_ = app.add_option("--threads,-j", threads_,
                                   "Threads; 0 = all cores (default). The output is the same for "
                                   "any count")
                        ->group(kRun);
    quiet_flag_ =
        app.add_flag("--quiet,-q", quiet_, "No progress bar and no output path")->group(kRun);
}

// The job the flags describe. --weight and --weight-map bind to the --guide before them; CLI11
// collects each flag's values, and parse_order() (one entry per value, in command-line order)
// tells how they interleave.
StylizeJob StylizeCommand::job_from_flags() {
    StylizeJob job = flag_job_;
    std::size_t guide_values = 0, weights = 0, maps = 0;
    std::vector<bool> weighted, mapped;
    for (const CLI::Option* option : app_->parse_order()) {
        if (option == guide_flag_) {
            // One entry per value: a pair is complete after its second file.
            if (++guide_values % 2 == 0) {
                const auto& [source, target] = guide_files_.at(guide_values / 2 - 1);
                // CLI11 takes the next two arguments whatever they are: `--guide a.png -o x`
                // would read "-o" as the target file.
                for (const std::string* file : {&source, &target}) {
                    if (file->size() > 1 && file->front() == '-') {
                        throw CLI::ValidationError(
                            "--guide", "takes two files SRC TGT, but '" + *file + "' is a flag");
                    }
                }
                job.guides.push_back({source, target, 1.0f, {}});
                weighted.push_back(false);
                mapped.push_back(false);
            }
            continue;
        }
        const bool is_weight = option == weight_flag_;
        if (!is_weight && option != weight_map_flag_) continue;
        const char* flag = is_weight ? "--weight" : "--weight-map";
        if (job.guides.empty()) {
            throw CLI::ValidationError(flag,
                                       "must follow the --guide it applies to (--guide SRC TGT "
                                       "--weight W)");
        }
        const std::size_t g = job.guides.size() - 1;
        std::vector<bool>& given = is_weight ? weighted : mapped;
        if (given[g]) {
            throw CLI::ValidationError(flag, "given twice for guide " + std::to_string(g + 1) +
                                                 " (" + job.guides[g].source + ", " +
                                                 job.guides[g].target + ")");
        }
        given[g] = true;
        if (is_weight) {
            job.guides[g].weight = weights_.at(weights++);
        } else {
            job.guides[g].weight_map = weight_maps_.at(maps++);
        }
    }
    if (std::vector<std::string> extras = app_->remaining(); !extras.empty()) {
        std::reverse(extras.begin(), extras.end());  // ExtrasError lists them in reverse
        throw CLI::ExtrasError(extras);
    }
    for (const auto& [name, flag] : numeric_flags_) {
        if (flag->count() > 0) job.numeric[name] = numeric_values_[name];
    }
    if (!style_weights_.empty())
        job.style_weights = parse_floats(style_weights_, "--style-weights");
    if (threads_flag_->count() > 0) job.threads = threads_;
    if (quiet_flag_->count() > 0) job.quiet = quiet_;
    return job;
}

Status StylizeCommand::run(const Streams& streams) {
    // The job: flags over the job file.
    StylizeJob job = job_from_flags();
    if (!config_.empty()) {
        auto file = load_job_file(config_);
        if (!file.ok()) return file.status();
        job = merge_jobs(*file, job);
    }
    if (job.style.empty()) {
        throw CLI::ValidationError("--style", "is required (a flag, or \"style\" in the job file)");
    }
    if (job.output.empty()) {
        throw CLI::ValidationError("--output",
                                   "is required (a flag, or \"output\" in the job file)");
    }

    // Checks that need no input file.
    SynthesisOptions options;
    EXEMPLAR_RETURN_IF_ERROR(build_options(job, options));
    const int threads = job.threads.value_or(0);
    if (threads < 0) {
        return invalid_argument("--threads: " + std::to_string(threads) +
                                " is invalid (must be >= 0; 0 = all cores)");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_output_paths(outputs_of(job)));

    // The input files, then the library's semantic checks, then the output formats.
    auto loaded = load_stylize_input(job);
    if (!loaded.ok()) return loaded.status();
    SynthesisInput& input = loaded->input;
    EXEMPLAR_RETURN_IF_ERROR(with_names(validate_input(input, options), *loaded));
    // Chosen now: the engine releases the inputs' images once it no longer needs them.
    const SaveOptions save = output_options(input.style, job.style, job.output);
    EXEMPLAR_RETURN_IF_ERROR(check_output_formats(outputs_of(job), input.style, save));

    // Run.
    const bool quiet = job.quiet.value_or(false);
    ProgressBar bar(streams.err, "stylize", !quiet && streams.err_is_terminal);
    RunContext context(threads);
    context.progress = [&bar](const ProgressEvent& event) { bar.update(event); };
    auto result = synthesize(std::move(input), options, context);
    bar.finish();
    if (!result.ok()) return with_names(result.status(), *loaded);

    // Write the outputs (each atomically).
    EXEMPLAR_RETURN_IF_ERROR(save_image(result->image, job.output, save));
    EXEMPLAR_RETURN_IF_ERROR(save_nnf_and_error(*result, outputs_of(job)));
    if (!quiet) {
        streams.out << job.output << '\n';
        streams.err << nnf_note(*result, outputs_of(job));
        streams.err << guide_compression_note(*result, options.guide_pca);
        streams.err << unlabelled_levels_note(*result);
    }
    return Status::ok();
}

}  // namespace exemplar::cli
