// `exemplar apply-nnf`: a saved NNF applied to another image on the style's grid (a 16-bit or
// extra-channel version of the style), voting as the synthesis did.

#include "commands.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/synth/nnf.hpp"
#include "output_files.hpp"

namespace exemplar::cli {

ApplyNnfCommand::ApplyNnfCommand(CLI::App& parent) {
    app_ = parent.add_subcommand(
        "apply-nnf", "Re-apply an NNF saved by `stylize --save-nnf` to another source image");
    app_->footer(
        "Example: exemplar apply-nnf --nnf out_nnf.exr --source style_16bit.png --patch-size 5 "
        "--vote-size 3 -o out16.png");
    app_->add_option("--nnf", nnf_, "NNF written by `stylize --save-nnf`")->required();
    app_->add_option("--source", source_,
                     "Image on the style's grid to copy from (e.g. a 16-bit or extra-channel "
                     "version of the style)")
        ->required();
    app_->add_option("--patch-size", patch_size_,
                     "Patch size the NNF was made with (stylize --save-nnf prints it: its "
                     "--patch-size, or 3 after a final 3x3 pass)")
        ->required();
    app_->add_option("--vote-size", vote_size_,
                     "Central part of each patch that votes, as the stylize run's "
                     "--final-vote-size (default 3; 0 = whole patches)");
    app_->add_flag("--vote-seams", vote_seams_,
                   "Seams blended as by the stylize run's --final-vote-seams 1 (--quality best)");
    app_->add_option("--output,-o", output_,
                     "Output image; PNG/TIFF keep the source's bit depth (16-bit in, 16-bit out)")
        ->required();
    app_->add_option("--vote", vote_, "average or weighted (default), as the stylize run");
    app_->add_option("--vote-coherence", vote_coherence_,
                     "Coherence weighting of the weighted vote, as the stylize run's "
                     "--vote-coherence (default 0 = off)");
    app_->add_option("--threads,-j", threads_, "Threads; 0 = all cores (default)");
    app_->add_flag("--quiet,-q", quiet_, "Do not print the output path");
}

Status ApplyNnfCommand::run(const Streams& streams) const {
    // Checks that need no file.
    auto vote = parse_vote_mode(vote_);
    if (!vote.ok()) return vote.status();
    SynthesisOptions options;
    EXEMPLAR_RETURN_IF_ERROR(set_option(options, *find_option("patch-size"), patch_size_));
    // --vote-size is stylize's final-vote-size: the same rule, under this command's flag name.
    const OptionSpec& vote_size = *find_option("final-vote-size");
    if (const Status s = set_option(options, vote_size, vote_size_); !s.is_ok()) {
        return invalid_argument("--vote-size" + s.message().substr(vote_size.name.size()));
    }
    EXEMPLAR_RETURN_IF_ERROR(set_option(options, *find_option("vote-coherence"), vote_coherence_));
    if (threads_ < 0) {
        return invalid_argument("--threads: " + std::to_string(threads_) +
                                " is invalid (must be >= 0; 0 = all cores)");
    }
    EXEMPLAR_RETURN_IF_ERROR(check_output_path("--output", output_));

    // The NNF.
    auto nnf_image = load_image(nnf_);
    if (!nnf_image.ok()) return nnf_image.status();
    auto nnf = nnf_from_image(*nnf_image);
    if (!nnf.ok()) return invalid_argument("--nnf " + nnf_ + ": " + nnf.status().message());

    // The source.
    auto source = load_image(source_);
    if (!source.ok()) return source.status();
    if (!all_finite(*source)) {
        return invalid_argument("--source " + source_ + ": contains NaN or infinity");
    }
    const SaveOptions save = output_options(*source, source_, output_);
    EXEMPLAR_RETURN_IF_ERROR(check_output_format("--output", output_, *source, save));

    auto result = apply_nnf(*nnf, *source, patch_size_, *vote, threads_, vote_size_,
                            vote_coherence_, vote_seams_);
    if (!result.ok()) {
        return Status(result.status().code(), "--nnf " + nnf_ + " with --source " + source_ + ": " +
                                                  result.status().message());
    }
    EXEMPLAR_RETURN_IF_ERROR(save_image(*result, output_, save));
    if (!quiet_) streams.out << output_ << '\n';
    return Status::ok();
}

}  // namespace exemplar::cli
