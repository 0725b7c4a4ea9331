#pragma once
// The `exemplar` command line. Flag parsing, job files, progress bar and the mapping of library
// errors to exit codes live here and nowhere else; the library never prints or exits.

#include <ostream>

namespace exemplar::cli {

/// Exit codes of the `exemplar` command.
enum ExitCode : int {
    kExitOk = 0,
    kExitFailure = 1,  ///< Bad input, unreadable/unwritable file, failed run.
    kExitUsage = 2,    ///< Unknown flag, missing required flag, malformed value.
};

/// Runs the command line `argv` (argv[0] is the program name). Normal output goes to `out`,
/// errors (one line, `exemplar: ...`) and the progress bar to `err`; the bar is drawn only when
/// `err_is_terminal`. Returns the exit code.
int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            bool err_is_terminal = false);

}  // namespace exemplar::cli
