#pragma once
// Help text of the numeric synthesis options, generated from synthesis_option_specs(). The same
// strings appear in `exemplar stylize --help` and in docs/cli.md (a test keeps them in step).

#include <CLI/CLI.hpp>
#include <map>
#include <span>
#include <string>

#include "exemplar/core/option_table.hpp"
#include "exemplar/core/status.hpp"
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

/// Adds one flag per entry of a module's option table (npr, brush): `--<name>` with help
/// "<doc> [<min>..<max> <unit>, default <default>]", storing into values[name]; flags[name] is
/// the flag (its count says whether it was given). `get(defaults, spec)` reads a default.
template <class Options, class Spec, class Get>
void add_table_flags(CLI::App& app, std::span<const Spec> specs, const Options& defaults, Get get,
                     std::map<std::string, double>& values,
                     std::map<std::string, CLI::Option*>& flags) {
    for (const Spec& spec : specs) {
        const std::string name(spec.name);
        const std::string unit = spec.unit.empty() ? "" : " " + std::string(spec.unit);
        flags[name] = app.add_option("--" + name, values[name],
                                     std::string(spec.doc) + " [" + format_number(spec.min) + ".." +
                                         format_number(spec.max) + unit + ", default " +
                                         format_number(get(defaults, spec)) + "]");
    }
}

/// Sets the table options whose flags were given (see add_table_flags) with `set(options, spec,
/// value)` (ModuleSetOption{}: the module's set_option); its error gets the flag's "--" in front.
template <class Options, class Spec, class Set>
Status set_given_table_flags(Options& options, std::span<const Spec> specs, Set set,
                             const std::map<std::string, double>& values,
                             const std::map<std::string, CLI::Option*>& flags) {
    for (const Spec& spec : specs) {
        const std::string name(spec.name);
        if (flags.at(name)->count() == 0) continue;
        if (const Status s = set(options, spec, values.at(name)); !s.is_ok())
            return invalid_argument("--" + s.message());
    }
    return Status::ok();
}

}  // namespace exemplar::cli
