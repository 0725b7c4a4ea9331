// `exemplar stylit`: the StyLit workflow. Without a sub-subcommand: stylize a target render from
// an exemplar painting and both renders' light-path buffers. `stylit sheet`: the printable
// low-contrast sheet with alignment marks. `stylit align`: a scan of the painted sheet warped
// back onto the render grid.

#include <cstdint>
#include <sstream>

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/stylit/align.hpp"
#include "exemplar/stylit/sheet.hpp"
#include "exemplar/stylit/stylit.hpp"
#include "option_help.hpp"
#include "output_files.hpp"
#include "progress_bar.hpp"

namespace exemplar::cli {

namespace {

constexpr const char* kFooter =
    "Buffers are listed in the same order for --source and --target (full render, direct\n"
    "diffuse, direct specular, indirect), or given as one multi-layer EXR or one folder each\n"
    "(exemplar render --output) whose layers or files --preset names (exemplar: fullgi,\n"
    "direct_diffuse, direct_specular, indirect_diffuse; cycles; arnold) or --layers lists:\n"
    "  exemplar stylit --exemplar painting.png --source s_full.png s_dirdif.png s_dirspc.png \\\n"
    "      s_indirb.png --target out/spot -o out.png\n"
    "Job files (--config job.json) take the same options as JSON keys, e.g.\n"
    "examples/stylit/stylit_job.json. Workflow and presets: docs/stylit.md.\n"
    "Sub-commands: stylit sheet, stylit align.";

void require(const CLI::App& app, bool given, const char* flag, const char* what) {
    if (!given) {
        throw CLI::RequiredError(std::string(flag) + " (" + what + ") is required for exemplar " +
                                 app.get_name());
    }
}

Status check_threads(int threads) {
    if (threads < 0) {
        return invalid_argument("--threads: " + std::to_string(threads) +
                                " is invalid (must be >= 0; 0 = all cores)");
    }
    return Status::ok();
}

}  // namespace

StylitCommand::StylitCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "stylit",
        "StyLit: transfer a painting of an exemplar render onto a new render through their "
        "light-path buffers (sub-commands: sheet, align)");
    app_->footer(kFooter);
    app_->require_subcommand(0, 1);
    CLI::App& app = *app_;
    app.add_option("--exemplar,-e", exemplar_,
                   "The artist's painting, aligned to the exemplar render (A')")
        ->group(kInputs);
    app.add_option("--source", source_,
                   "Buffers of the exemplar render: files in guide order, one multi-layer EXR, or "
                   "one folder of exemplar render")
        ->group(kInputs);
    app.add_option("--target", target_,
                   "Buffers of the target render, in the same order (or one multi-layer EXR or "
                   "folder)")
        ->group(kInputs);
    app.add_option("--preset", preset_,
                   "EXR layer or folder file names: exemplar (default; fullgi, direct_diffuse, "
                   "direct_specular, indirect_diffuse), cycles (Combined, DiffDir, GlossDir, "
                   "DiffInd) or arnold (RGBA, diffuse_direct, specular_direct, diffuse_indirect)")
        ->group(kInputs);
    app.add_option("--layers", layers_,
                   "EXR layer (or folder file) names in guide order, comma-separated (instead of "
                   "--preset)")
        ->group(kInputs);
    app.add_option("--config", config_,
                   "JSON job file with the same options (long names as keys; source and target "
                   "as arrays); flags override it")
        ->group(kInputs);
    app.add_option("--output,-o", output_, "Output image; format from the extension")
        ->group(kOutputs);
    app.add_option("--save-nnf", save_nnf_,
                   "Write the final NNF (EXR: x, y, angle, error) for apply-nnf (half size with "
                   "--preview)")
        ->group(kOutputs);
    app.add_option("--save-error", save_error_,
                   "Write the per-pixel patch error (EXR/TIFF: as is; PNG etc.: scaled, 99th "
                   "percentile = white)")
        ->group(kOutputs);
    app.add_option("--guidance-weight", guidance_weight_,
                   "Total weight of the buffers against the painting (mu of the paper), split "
                   "equally among them [0..100, default 2]")
        ->group(kSynthesis);
    app.add_option("--usage", usage_,
                   "Patch-usage strategy: error-budget (default), uniform, none, occurrence")
        ->group(kSynthesis);
    app.add_option("--quality", quality_,
                   "Search effort: fast (previews), default, best (closer to the exemplar, "
                   "slower); the presets of stylize --quality")
        ->group(kSynthesis);
    app.add_option("--seed", seed_, "Random seed [default 1]; same seed, same output")
        ->group(kSynthesis);
    app.add_flag("--preview", preview_,
                 "Preview mode: half resolution, buffers compressed by PCA, nearest-neighbour "
                 "patch usage instead of the error budget and fewer iterations (output at half "
                 "size; ~1/10 of the time)")
        ->group(kSynthesis);
    app.add_option("--threads,-j", threads_, "Threads; 0 = all cores (default)")->group(kRun);
    app.add_flag("--quiet,-q", quiet_, "No progress bar and no output path")->group(kRun);

    sheet_ = app.add_subcommand(
        "sheet", "The printable sheet: the exemplar render in low contrast with alignment marks");
    sheet_->footer(
        "Example: exemplar stylit sheet --render source_fullgi.png -o sheet.png --pdf sheet.pdf\n"
        "Paint over the print, scan it, then: exemplar stylit align. See docs/stylit.md.");
    sheet_->add_option("--render,-r", sheet_render_, "The exemplar render (its full buffer)")
        ->group(kInputs);
    sheet_->add_option("--output,-o", sheet_png_, "Sheet image (PNG)")->group(kOutputs);
    sheet_->add_option("--pdf", sheet_pdf_, "Sheet as a one-page PDF")->group(kOutputs);
    sheet_->add_option("--paper", paper_, "PDF paper: a4 (default), a3, letter")->group(kOutputs);
    sheet_
        ->add_option("--dpi", dpi_,
                     "PDF print resolution of the sheet; 0 = as large as fits (default)")
        ->group(kOutputs);
    sheet_
        ->add_option("--grey-range", grey_range_,
                     "Grey levels LOW HIGH the render is mapped to [default 0.72 0.95]")
        ->expected(2)
        ->group(kOutputs);
    sheet_->add_flag("--quiet,-q", quiet_, "No output paths")->group(kRun);

    align_ = app.add_subcommand(
        "align",
        "Find the alignment marks in a scan or photo of the painted sheet and warp it "
        "onto the render's pixel grid");
    align_->footer(
        "Example: exemplar stylit align --scan scan.jpg --render source_fullgi.png -o "
        "painting.png\nThe marks are those of exemplar stylit sheet for the same render.");
    align_->add_option("--scan", scan_, "Scan or photo of the painted sheet")->group(kInputs);
    align_
        ->add_option("--render,-r", align_render_,
                     "The exemplar render the sheet was made from (gives the grid)")
        ->group(kInputs);
    align_->add_option("--output,-o", align_output_, "The aligned painting")->group(kOutputs);
    align_->add_flag("--quiet,-q", quiet_, "No output path")->group(kRun);
}

Status StylitCommand::run(const Streams& streams) {
    if (!sheet_->parsed() && !align_->parsed()) return run_stylize(streams);
    // Flags of the stylize run do nothing for sheet and align: refuse rather than ignore them.
    for (const CLI::Option* option : app_->get_options()) {
        if (option->count() > 0) {
            throw CLI::ValidationError(option->get_name(),
                                       "belongs to exemplar stylit, not to its sub-command " +
                                           std::string(sheet_->parsed() ? "sheet" : "align"));
        }
    }
    return sheet_->parsed() ? run_sheet(streams) : run_align(streams);
}

// Values of the --config file for every flag not given on the command line.
Status StylitCommand::apply_job_file() {
    std::string exemplar, output, preset, layers, usage, quality, save_nnf, save_error;
    std::vector<std::string> source, target;
    double guidance_weight = 0.0;
    long long seed = 0, threads = 0;
    bool preview = false, quiet = false;
    JobFields fields;
    fields.paths = {{"exemplar", &exemplar},
                    {"output", &output},
                    {"save-nnf", &save_nnf},
                    {"save-error", &save_error}};
    fields.path_lists = {{"source", &source}, {"target", &target}};
    fields.words = {
        {"preset", &preset}, {"layers", &layers}, {"usage", &usage}, {"quality", &quality}};
    fields.numbers = {{"guidance-weight", &guidance_weight}};
    fields.integers = {{"seed", &seed}, {"threads", &threads}};
    fields.flags = {{"preview", &preview}, {"quiet", &quiet}};
    std::vector<std::string> given;
    EXEMPLAR_RETURN_IF_ERROR(read_job_file(config_, fields, &given));
    if (seed < 0) return invalid_argument(config_ + ": key 'seed' must be >= 0");
    for (const std::string& key : given) {
        if (app_->get_option("--" + key)->count() > 0) continue;  // the flag wins
        if (key == "exemplar") exemplar_ = exemplar;
        if (key == "output") output_ = output;
        if (key == "save-nnf") save_nnf_ = save_nnf;
        if (key == "save-error") save_error_ = save_error;
        if (key == "source") source_ = source;
        if (key == "target") target_ = target;
        if (key == "preset") preset_ = preset;
        if (key == "layers") layers_ = layers;
        if (key == "usage") usage_ = usage;
        if (key == "quality") quality_ = quality;
        if (key == "guidance-weight") guidance_weight_ = static_cast<float>(guidance_weight);
        if (key == "seed") seed_ = static_cast<std::uint64_t>(seed);
        if (key == "threads") threads_ = static_cast<int>(threads);
        if (key == "preview") preview_ = preview;
        if (key == "quiet") quiet_ = quiet;
    }
    return Status::ok();
}

Status StylitCommand::run_stylize(const Streams& streams) {
    if (!config_.empty()) EXEMPLAR_RETURN_IF_ERROR(apply_job_file());
    require(*app_, !exemplar_.empty(), "--exemplar", "the painting");
    require(*app_, !source_.empty(), "--source", "the exemplar render's buffers");
    require(*app_, !target_.empty(), "--target", "the target render's buffers");
    require(*app_, !output_.empty(), "--output", "the output image");

    // Checks that need no input file.
    StylitOptions options;
    auto quality = quality_.empty() ? Result<Quality>(Quality::Default) : parse_quality(quality_);
    if (!quality.ok()) return quality.status();
    options.synthesis = SynthesisOptions::preset(*quality);
    options.preview = preview_;
    options.guidance_weight = guidance_weight_;
    options.synthesis.seed = seed_;
    if (!usage_.empty()) {
        auto usage = parse_usage_strategy(usage_);
        if (!usage.ok())
            return Status(usage.status().code(), "--usage: " + usage.status().message());
        options.synthesis.usage = *usage;
    }
    EXEMPLAR_RETURN_IF_ERROR(check_threads(threads_));
    auto preset = layers_.empty() ? find_layer_preset(preset_) : custom_layer_preset(layers_);
    if (!preset.ok()) return preset.status();
    const SynthesisOutputs outputs{output_, save_nnf_, save_error_};
    EXEMPLAR_RETURN_IF_ERROR(check_output_paths(outputs));

    // Inputs.
    auto exemplar = load_image(exemplar_);
    if (!exemplar.ok()) return exemplar.status();
    auto source = load_lpe_buffers(source_, *preset);
    if (!source.ok()) return source.status();
    auto target = load_lpe_buffers(target_, *preset);
    if (!target.ok()) return target.status();
    auto input = stylit_input(*exemplar, *source, *target, options);
    if (!input.ok()) return input.status();
    EXEMPLAR_RETURN_IF_ERROR(validate_input(*input, options.synthesis));
    const SaveOptions save = output_options(*exemplar, exemplar_, output_);
    EXEMPLAR_RETURN_IF_ERROR(check_output_formats(outputs, *exemplar, save));

    // Run.
    ProgressBar bar(streams.err, options.preview ? "stylit preview" : "stylit",
                    !quiet_ && streams.err_is_terminal);
    RunContext context(threads_);
    context.progress = [&bar](const ProgressEvent& event) { bar.update(event); };
    auto result = stylize_render(*exemplar, *source, *target, options, context);
    bar.finish();
    if (!result.ok()) return result.status();

    EXEMPLAR_RETURN_IF_ERROR(save_image(result->synthesis.image, output_, save));
    EXEMPLAR_RETURN_IF_ERROR(save_nnf_and_error(result->synthesis, outputs));
    if (!quiet_) {
        streams.out << output_ << '\n';
        streams.err << nnf_note(result->synthesis, outputs);
        if (options.preview) {
            std::ostringstream note;
            note.precision(3);
            note << "exemplar: note: preview at " << result->synthesis.image.width() << "x"
                 << result->synthesis.image.height() << ", buffers compressed to "
                 << result->guide_channels << " channels (" << 100.0 * result->explained_variance
                 << "% of their variance)\n";
            streams.err << note.str();
        }
    }
    return Status::ok();
}

Status StylitCommand::run_sheet(const Streams& streams) {
    require(*sheet_, !sheet_render_.empty(), "--render", "the exemplar render");
    if (sheet_png_.empty() && sheet_pdf_.empty()) {
        throw CLI::RequiredError("--output (PNG) or --pdf is required for exemplar stylit sheet");
    }
    const float low = grey_range_[0], high = grey_range_[1];
    if (!(low >= 0.0f && low <= high && high <= 1.0f)) {
        return invalid_argument("--grey-range " + std::to_string(low) + " " + std::to_string(high) +
                                ": is invalid (need 0 <= LOW <= HIGH <= 1)");
    }
    if (!sheet_png_.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", sheet_png_));
        EXEMPLAR_RETURN_IF_ERROR(
            check_output_format("--output", sheet_png_, Image(1, 1, 1), SaveOptions{}));
    }
    if (!sheet_pdf_.empty()) EXEMPLAR_RETURN_IF_ERROR(check_output_path("--pdf", sheet_pdf_));
    if (!sheet_png_.empty() && !sheet_pdf_.empty() && same_file(sheet_png_, sheet_pdf_)) {
        return invalid_argument("--pdf " + sheet_pdf_ + ": is also the --output file");
    }

    auto render = load_image(sheet_render_);
    if (!render.ok()) return render.status();
    const SheetLayout layout = sheet_layout(render->width(), render->height());
    const Image light = low_contrast(*render, low, high);
    auto sheet = make_sheet(light, layout);
    if (!sheet.ok()) return sheet.status();

    // Both outputs are checked before either is written.
    const PdfOptions pdf{paper_, dpi_};
    if (!sheet_pdf_.empty())
        EXEMPLAR_RETURN_IF_ERROR(save_sheet_pdf(light, layout, sheet_pdf_, pdf));
    if (!sheet_png_.empty()) EXEMPLAR_RETURN_IF_ERROR(save_image(*sheet, sheet_png_));
    if (!quiet_) {
        if (!sheet_png_.empty()) streams.out << sheet_png_ << '\n';
        if (!sheet_pdf_.empty()) streams.out << sheet_pdf_ << '\n';
    }
    return Status::ok();
}

Status StylitCommand::run_align(const Streams& streams) {
    require(*align_, !scan_.empty(), "--scan", "the scan or photo");
    require(*align_, !align_render_.empty(), "--render", "the exemplar render");
    require(*align_, !align_output_.empty(), "--output", "the aligned painting");
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", align_output_));

    auto render_size = load_image(align_render_);
    if (!render_size.ok()) return render_size.status();
    auto scan = load_image(scan_);
    if (!scan.ok()) return scan.status();
    const SaveOptions save = output_options(*scan, scan_, align_output_);
    EXEMPLAR_RETURN_IF_ERROR(check_output_format("--output", align_output_, *scan, save));

    auto aligned = align_scan(*scan, sheet_layout(render_size->width(), render_size->height()));
    if (!aligned.ok()) {
        return Status(aligned.status().code(), scan_ + ": " + aligned.status().message());
    }
    EXEMPLAR_RETURN_IF_ERROR(save_image(aligned->image, align_output_, save));
    if (!quiet_) streams.out << align_output_ << '\n';
    return Status::ok();
}

}  // namespace exemplar::cli
