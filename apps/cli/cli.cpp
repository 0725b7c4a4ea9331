#include "cli.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "progress_bar.hpp"
#include "stylize_job.hpp"

namespace exemplar::cli {

namespace {

// The flags of `stylize`, bound to CLI11. Numeric synthesis options are generated from
// synthesis_option_specs(), so the help text, validation and JSON keys share one description.
struct StylizeFlags {
    StylizeJob job;
    std::string config;
    std::vector<std::string> guide_pairs;  // SRC TGT SRC TGT ...
    std::vector<float> weights;
    std::vector<std::string> weight_maps;
    std::string style_weights;
    std::map<std::string, double> numeric_values;
    std::map<std::string, CLI::Option*> numeric_flags;
    int threads = 0;
    CLI::Option* guide_flag = nullptr;
    CLI::Option* weight_flag = nullptr;
    CLI::Option* weight_map_flag = nullptr;
    CLI::Option* threads_flag = nullptr;
    CLI::Option* quiet_flag = nullptr;
    bool quiet = false;
};

std::string describe(const OptionSpec& spec) {
    std::ostringstream out;
    out << spec.doc << " [" << spec.min << ".." << spec.max;
    if (!spec.unit.empty()) out << ' ' << spec.unit;
    SynthesisOptions defaults;
    out << ", default " << get_option(defaults, spec) << ']';
    return out.str();
}

void add_stylize_flags(CLI::App& app, StylizeFlags& f) {
    app.add_option("--style,-s", f.job.style, "Style exemplar A' (any image; alpha is a channel)");
    f.guide_flag = app.add_option("--guide,-g", f.guide_pairs,
                                  "Guide pair SRC TGT: SRC on the style's grid (A_i), TGT on the "
                                  "target grid (B_i); repeat for more guides")
                       ->expected(2)
                       ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    f.weight_flag = app.add_option("--weight,-w", f.weights,
                                   "Weight of the preceding --guide (>= 0, default 1)")
                        ->take_all();
    f.weight_map_flag =
        app.add_option("--weight-map", f.weight_maps,
                       "Per-pixel weight map (1 channel, target size) of the preceding --guide")
            ->take_all();
    app.add_option("--output,-o", f.job.output, "Output image (format from the extension)");
    app.add_option("--config", f.config,
                   "JSON job file with the same options (long names as keys); flags override it");
    f.threads_flag = app.add_option("--threads,-j", f.threads, "Threads; 0 = all cores (default)");
    app.add_option("--usage", f.job.usage,
                   "Patch-usage strategy: none, uniform, error-budget (default), occurrence");
    app.add_option("--vote", f.job.vote, "Voting: average or weighted (default)");
    for (const OptionSpec& spec : synthesis_option_specs()) {
        const std::string name(spec.name);
        f.numeric_flags[name] = app.add_option("--" + name, f.numeric_values[name], describe(spec));
    }
    app.add_option("--style-weights", f.style_weights,
                   "Comma-separated weights of the style channels (default 1 each)");
    app.add_option("--target-mask", f.job.target_mask,
                   "Synthesize only where this mask is > 0.5; keep --init elsewhere");
    app.add_option("--source-mask", f.job.source_mask,
                   "Use only style patches entirely inside this mask (> 0.5)");
    app.add_option("--source-labels", f.job.source_labels,
                   "Label map of the style (1 channel); with --target-labels");
    app.add_option("--target-labels", f.job.target_labels,
                   "Label map of the target: pixels take only patches of their label");
    app.add_option("--source-orientation", f.job.source_orientation,
                   "Orientation field of the style (1 channel, radians)");
    app.add_option("--target-orientation", f.job.target_orientation,
                   "Orientation field of the target: patches rotate by the difference");
    app.add_option("--init", f.job.init, "Initial target image (style channels)");
    app.add_option("--init-nnf", f.job.init_nnf, "Initial NNF (as written by --save-nnf)");
    app.add_option("--size", f.job.size, "Target size WxH when there are no guides");
    app.add_option("--save-nnf", f.job.save_nnf,
                   "Write the final NNF (EXR: x, y, angle, error) for apply-nnf");
    app.add_option("--save-error", f.job.save_error, "Write the per-pixel error map");
    f.quiet_flag = app.add_flag("--quiet,-q", f.quiet, "No progress bar and no output path");
}

// Guides from the flags: every --weight / --weight-map binds to the --guide before it. CLI11
// collects each flag's values in order but not how the flags interleave, so the order comes
// from the raw arguments.
Status collect_guides(const std::vector<std::string>& args, StylizeFlags& f) {
    std::size_t guide = 0, weight = 0, map = 0;
    for (const std::string& arg : args) {
        const bool is_guide = arg == "--guide" || arg == "-g";
        const bool is_weight = arg == "--weight" || arg == "-w" || arg.rfind("--weight=", 0) == 0;
        const bool is_map = arg == "--weight-map" || arg.rfind("--weight-map=", 0) == 0;
        if (is_guide && 2 * guide + 1 < f.guide_pairs.size()) {
            GuideSpec g;
            g.source = f.guide_pairs[2 * guide];
            g.target = f.guide_pairs[2 * guide + 1];
            f.job.guides.push_back(g);
            ++guide;
        } else if (is_weight || is_map) {
            if (f.job.guides.empty()) {
                return invalid_argument(std::string(is_weight ? "--weight" : "--weight-map") +
                                        " must follow the --guide it applies to");
            }
            if (is_weight && weight < f.weights.size()) {
                f.job.guides.back().weight = f.weights[weight++];
            } else if (is_map && map < f.weight_maps.size()) {
                f.job.guides.back().weight_map = f.weight_maps[map++];
            }
        }
    }
    return Status::ok();
}

Result<std::vector<float>> parse_floats(const std::string& text, const char* what) {
    std::vector<float> out;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        try {
            std::size_t used = 0;
            out.push_back(std::stof(item, &used));
            if (used != item.size()) throw std::invalid_argument(item);
        } catch (const std::exception&) {
            return invalid_argument(std::string(what) + ": '" + item + "' is not a number");
        }
    }
    return out;
}

Result<Image> load_single(const std::string& path) {
    if (!std::filesystem::exists(path)) return io_error(path + ": no such file");
    return load_image(path);
}

// Loads an optional single-channel map (first channel if it has more).
Status load_map(const std::string& path, Image& into, bool first_channel_only) {
    if (path.empty()) return Status::ok();
    auto image = load_single(path);
    if (!image.ok()) return image.status();
    into = first_channel_only && image->channels() > 1 ? extract_channels(*image, 0, 1)
                                                       : std::move(image).value();
    return Status::ok();
}

// A library message about an input, prefixed with nothing: validate_input names the input.
Status build_input(const StylizeJob& job, SynthesisInput& in) {
    if (job.style.empty()) return invalid_argument("--style: is required");
    auto style = load_single(job.style);
    if (!style.ok()) return style.status();
    in.style = std::move(style).value();
    for (std::size_t i = 0; i < job.guides.size(); ++i) {
        const GuideSpec& g = job.guides[i];
        GuidePair pair;
        pair.name = "guide " + std::to_string(i + 1) + " (" + g.source + ", " + g.target + ")";
        auto a = load_single(g.source);
        if (!a.ok()) return a.status();
        auto b = load_single(g.target);
        if (!b.ok()) return b.status();
        pair.source = std::move(a).value();
        pair.target = std::move(b).value();
        pair.weight = g.weight;
        EXEMPLAR_RETURN_IF_ERROR(load_map(g.weight_map, pair.target_weight_map, true));
        in.guides.push_back(std::move(pair));
    }
    // Masks and labels are read from their first channel (a grey PNG has one anyway).
    EXEMPLAR_RETURN_IF_ERROR(load_map(job.target_mask, in.target_mask, true));
    EXEMPLAR_RETURN_IF_ERROR(load_map(job.source_mask, in.source_mask, true));
    EXEMPLAR_RETURN_IF_ERROR(load_map(job.source_labels, in.source_labels, true));
    EXEMPLAR_RETURN_IF_ERROR(load_map(job.target_labels, in.target_labels, true));
    EXEMPLAR_RETURN_IF_ERROR(load_map(job.source_orientation, in.source_orientation, true));
    EXEMPLAR_RETURN_IF_ERROR(load_map(job.target_orientation, in.target_orientation, true));
    EXEMPLAR_RETURN_IF_ERROR(load_map(job.init, in.initial_target, false));
    if (!job.init_nnf.empty()) {
        Image nnf_image;
        EXEMPLAR_RETURN_IF_ERROR(load_map(job.init_nnf, nnf_image, false));
        auto nnf = nnf_from_image(nnf_image);
        if (!nnf.ok()) return invalid_argument(job.init_nnf + ": " + nnf.status().message());
        in.initial_nnf = std::move(nnf).value();
    }
    in.style_channel_weights = job.style_weights;
    if (!job.size.empty()) {
        int w = 0, h = 0;
        char x = 0;
        std::istringstream size(job.size);
        if (!(size >> w >> x >> h) || x != 'x' || w <= 0 || h <= 0 || !size.eof()) {
            return invalid_argument("--size: '" + job.size + "' is invalid (must be WxH)");
        }
        in.target_width = w;
        in.target_height = h;
    }
    return Status::ok();
}

Status build_options(const StylizeJob& job, SynthesisOptions& options) {
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

Status run_stylize(const std::vector<std::string>& args, StylizeFlags& f, std::ostream& out,
                   std::ostream& err, bool err_is_terminal) {
    EXEMPLAR_RETURN_IF_ERROR(collect_guides(args, f));
    for (const auto& [name, flag] : f.numeric_flags) {
        if (flag->count() > 0) f.job.numeric[name] = f.numeric_values[name];
    }
    if (!f.style_weights.empty()) {
        auto weights = parse_floats(f.style_weights, "--style-weights");
        if (!weights.ok()) return weights.status();
        f.job.style_weights = std::move(weights).value();
    }
    if (f.threads_flag->count() > 0) f.job.threads = f.threads;
    if (f.quiet_flag->count() > 0) f.job.quiet = f.quiet;

    StylizeJob job = f.job;
    if (!f.config.empty()) {
        auto file = load_job_file(f.config);
        if (!file.ok()) return file.status();
        job = merge_jobs(*file, f.job);
    }
    if (job.output.empty()) return invalid_argument("--output: is required");
    if (job.threads && *job.threads < 0) {
        return invalid_argument("--threads: " + std::to_string(*job.threads) +
                                " is invalid (must be >= 0; 0 = all cores)");
    }

    SynthesisOptions options;
    EXEMPLAR_RETURN_IF_ERROR(build_options(job, options));
    SynthesisInput input;
    EXEMPLAR_RETURN_IF_ERROR(build_input(job, input));
    EXEMPLAR_RETURN_IF_ERROR(validate_input(input, options));

    const bool quiet = job.quiet.value_or(false);
    ProgressBar bar(err, "stylize", !quiet && err_is_terminal);
    RunContext context(job.threads.value_or(0));
    context.progress = [&](const ProgressEvent& e) { bar.update(e); };
    auto result = synthesize(input, options, context);
    bar.finish();
    if (!result.ok()) return result.status();

    EXEMPLAR_RETURN_IF_ERROR(save_image(result->image, job.output));
    if (!job.save_nnf.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(
            save_image(nnf_to_image(result->nnf), job.save_nnf, SaveOptions{PixelFormat::Float}));
    }
    if (!job.save_error.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(save_image(result->error, job.save_error));
    }
    if (!quiet) {
        out << job.output << '\n';
        if (!job.save_nnf.empty()) {
            out << job.save_nnf << " (apply with --patch-size " << result->nnf_patch_size << ")\n";
        }
    }
    return Status::ok();
}

struct ApplyNnfFlags {
    std::string nnf, source, output, vote = "weighted";
    int patch_size = 3;
    int threads = 0;
};

void add_apply_nnf_flags(CLI::App& app, ApplyNnfFlags& f) {
    app.add_option("--nnf", f.nnf, "NNF written by `stylize --save-nnf`")->required();
    app.add_option("--source", f.source,
                   "Image on the style's grid to copy from (e.g. a 16-bit or extra-channel "
                   "version of the style)")
        ->required();
    app.add_option("--output,-o", f.output, "Output image")->required();
    app.add_option("--patch-size", f.patch_size,
                   "Patch size the NNF was made with; stylize prints it (default 3: its final "
                   "3x3 pass)");
    app.add_option("--vote", f.vote, "average or weighted (default; as stylize)");
    app.add_option("--threads,-j", f.threads, "Threads; 0 = all cores (default)");
}

Status run_apply_nnf(const ApplyNnfFlags& f, std::ostream& out) {
    auto vote = parse_vote_mode(f.vote);
    if (!vote.ok()) return vote.status();
    if (f.threads < 0) return invalid_argument("--threads: must be >= 0");
    auto nnf_image = load_single(f.nnf);
    if (!nnf_image.ok()) return nnf_image.status();
    auto nnf = nnf_from_image(*nnf_image);
    if (!nnf.ok()) return invalid_argument(f.nnf + ": " + nnf.status().message());
    auto source = load_single(f.source);
    if (!source.ok()) return source.status();
    if (!all_finite(*source)) return invalid_argument(f.source + ": contains NaN or infinity");
    auto result = apply_nnf(*nnf, *source, f.patch_size, *vote, f.threads);
    if (!result.ok()) return result.status();
    // 16-bit PNG/TIFF keep the precision of high-bit-depth sources (the point of re-applying).
    SaveOptions save;
    const std::string ext = std::filesystem::path(f.output).extension().string();
    if (ext == ".png" || ext == ".PNG" || ext == ".tif" || ext == ".tiff") {
        save.format = PixelFormat::UInt16;
    }
    EXEMPLAR_RETURN_IF_ERROR(save_image(*result, f.output, save));
    out << f.output << '\n';
    return Status::ok();
}

std::string one_line(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    for (char& c : text) {
        if (c == '\n') c = ' ';
    }
    return text;
}

}  // namespace

int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            bool err_is_terminal) {
    CLI::App app{"exemplar: example-based stylization (guided patch-based synthesis)", "exemplar"};
    app.set_version_flag("--version", "exemplar 0.1.0");
    app.require_subcommand(1);

    StylizeFlags stylize_flags;
    CLI::App* stylize = app.add_subcommand(
        "stylize",
        "Transfer the style of an exemplar onto a target through guide pairs (image analogies)");
    add_stylize_flags(*stylize, stylize_flags);

    ApplyNnfFlags apply_flags;
    CLI::App* apply = app.add_subcommand(
        "apply-nnf", "Re-apply a saved nearest-neighbour field to another source image");
    add_apply_nnf_flags(*apply, apply_flags);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        out << (app.get_subcommands().empty() ? app.help() : app.get_subcommands()[0]->help());
        return kExitOk;
    } catch (const CLI::CallForAllHelp&) {
        out << app.help("", CLI::AppFormatMode::All);
        return kExitOk;
    } catch (const CLI::CallForVersion& e) {
        out << e.what() << '\n';
        return kExitOk;
    } catch (const CLI::ParseError& e) {
        err << "exemplar: " << one_line(e.what()) << " (see exemplar --help)\n";
        return kExitUsage;
    }

    Status status;
    try {
        if (stylize->parsed()) {
            status = run_stylize(std::vector<std::string>(argv + 1, argv + argc), stylize_flags,
                                 out, err, err_is_terminal);
        } else if (apply->parsed()) {
            status = run_apply_nnf(apply_flags, out);
        }
    } catch (const std::exception& e) {
        status = Status(ErrorCode::Internal, e.what());
    }
    if (!status.is_ok()) {
        err << "exemplar: " << one_line(status.message()) << '\n';
        return kExitFailure;
    }
    return kExitOk;
}

}  // namespace exemplar::cli
