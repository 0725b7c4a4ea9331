#pragma once
// Help text of the numeric synthesis options, generated from synthesis_option_specs(). The same
// strings appear in `exemplar stylize --help` and in docs/cli.md (a test keeps them in step).

#include <string>

#include "exemplar/synth/options.hpp"

namespace exemplar::cli {

/// Group headings of `--help`, shared by the subcommands so their help reads alike.
inline constexpr const char* kInputs = "Inputs";
inline constexpr const char* kOutputs = "Outputs";
inline constexpr const char* kSynthesis = "Synthesis options";
inline constexpr const char* kRun = "Run";

/// A number as a person writes it: integers without exponent or decimals ("9007199254740992",
/// "1000000"), others with up to 6 significant digits ("0.95").
std::string format_number(double value);

/// "3..31 px": the inclusive range and the unit.
std::string format_range(const OptionSpec& spec);

/// The default of an option, formatted ("5", "0.95").
std::string format_default(const OptionSpec& spec);

/// True for options stored as integers (the flag takes INT).
bool is_integer_option(const OptionSpec& spec);

/// Full flag help: "<doc> [<range>, default <default>]".
std::string describe(const OptionSpec& spec);

/// Search-tuning knobs for experts: every numeric option but patch-size, style-weight and seed.
/// `--help` lists them only under `--help-all` (--quality sets them together).
bool is_expert_option(const OptionSpec& spec);

/// What a quality preset sets, as the flags that would set it:
/// "--finest-em-iterations 1 --second-finest-em-iterations 2 ..." (empty for Default). Listed by
/// `--help-all` and, word for word, by docs/cli.md.
std::string quality_flags(Quality quality);

/// The expert options as a help section ("Search tuning (experts) ..." with one
/// "  --name TYPE  description" entry each), for `--help-all`.
std::string expert_options_help();

}  // namespace exemplar::cli
