#include "cli.hpp"

#include <CLI/CLI.hpp>
#include <new>
#include <string>

#include "commands.hpp"

namespace exemplar::cli {

namespace {

// Messages are one line: CLI11's and the library's may end in (or contain) newlines.
std::string one_line(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    for (char& c : text) {
        if (c == '\n') c = ' ';
    }
    return text;
}

}  // namespace

// The one place where errors become exit codes.
int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            bool err_is_terminal) {
    CLI::App app{"exemplar: example-based stylization (guided patch-based synthesis)", "exemplar"};
    app.set_version_flag("--version", std::string("exemplar ") + EXEMPLAR_VERSION);
    app.require_subcommand(1);
    StylizeCommand stylize(app);
    ApplyNnfCommand apply_nnf(app);
    RenderCommand render(app);
    const Streams streams{out, err, err_is_terminal};

    Status status;
    try {
        app.parse(argc, argv);
        if (stylize.parsed()) {
            status = stylize.run(streams);
        } else if (apply_nnf.parsed()) {
            status = apply_nnf.run(streams);
        } else if (render.parsed()) {
            status = render.run(streams);
        }
    } catch (const CLI::CallForHelp&) {
        const auto subcommands = app.get_subcommands();
        out << (subcommands.empty() ? app.help() : subcommands.front()->help());
        return kExitOk;
    } catch (const CLI::CallForAllHelp&) {
        out << app.help("", CLI::AppFormatMode::All);
        return kExitOk;
    } catch (const CLI::CallForVersion& e) {
        out << e.what() << '\n';
        return kExitOk;
    } catch (const CLI::ParseError& e) {
        const auto subcommands = app.get_subcommands();
        const std::string help = subcommands.empty()
                                     ? std::string("exemplar --help")
                                     : "exemplar " + subcommands.front()->get_name() + " --help";
        err << "exemplar: " << one_line(e.what()) << " (see " << help << ")\n";
        return kExitUsage;
    } catch (const std::bad_alloc&) {
        status = Status(ErrorCode::Internal, "out of memory (are the images or --size too large?)");
    } catch (const std::exception& e) {
        status = Status(ErrorCode::Internal, std::string("internal error: ") + e.what());
    }
    if (!status.is_ok()) {
        err << "exemplar: " << one_line(status.message()) << '\n';
        return kExitFailure;
    }
    return kExitOk;
}

}  // namespace exemplar::cli
