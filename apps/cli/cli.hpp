#pragma once
// The `exemplar` command line. Flag parsing, job files, progress bar and the mapping of errors to
// exit codes live here and nowhere else; the library never prints or exits.

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace exemplar::cli {

/// Exit codes of the `exemplar` command.
enum ExitCode : int {
    kExitOk = 0,
    /// Bad input (missing, corrupt or inconsistent file, out-of-range value), unwritable output,
    /// failed run.
    kExitFailure = 1,
    /// Command-line grammar: unknown flag, missing required flag, wrong number of values, a
    /// value that is not a number, --weight before any --guide.
    kExitUsage = 2,
};

/// Runs the command line `argv` (argv[0] is the program name). Normal output (the written file's
/// path, help, version) goes to `out`; errors (one line, `exemplar: ...`) and the progress bar go
/// to `err`; the bar is drawn only when `err_is_terminal`. Never throws; returns the exit code.
int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            bool err_is_terminal = false);

/// The manual pages of the command, generated from the parser's own option tables: ("exemplar",
/// page), then ("exemplar-VERB", page) per verb (and "exemplar-VERB-SUB" per sub-verb), in roff
/// (man(7)). Every flag the parser accepts is listed, including the tuning knobs that `--help`
/// leaves out.
std::vector<std::pair<std::string, std::string>> man_pages();

}  // namespace exemplar::cli
