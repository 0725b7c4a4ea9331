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

// The innermost parsed subcommand (`stylit sheet`), or nullptr: its help is the one asked for.
const CLI::App* innermost(const CLI::App& app) {
    const CLI::App* found = nullptr;
    for (const CLI::App* level = &app; !level->get_subcommands().empty();) {
        level = level->get_subcommands().front();
        found = level;
    }
    return found;
}

// "exemplar stylit sheet": the command path of a subcommand.
std::string command_path(const CLI::App* sub) {
    std::string path;
    for (; sub != nullptr && sub->get_parent() != nullptr; sub = sub->get_parent()) {
        path.insert(0, " " + sub->get_name());
    }
    return "exemplar" + path;
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
    StylitCommand stylit(app);
    FlowCommand flow(app);
    BeautifyCommand beautify(app);
    AnimateCommand animate(app);
    FluidCommand fluid(app);
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
        } else if (stylit.parsed()) {
            status = stylit.run(streams);
        } else if (flow.parsed()) {
            status = flow.run(streams);
        } else if (beautify.parsed()) {
            status = beautify.run(streams);
        } else if (animate.parsed()) {
            status = animate.run(streams);
        } else if (fluid.parsed()) {
            status = fluid.run(streams);
        }
    } catch (const CLI::CallForHelp&) {
        const CLI::App* sub = innermost(app);
        out << (sub == nullptr ? app.help() : sub->help());
        return kExitOk;
    } catch (const CLI::CallForAllHelp&) {
        out << app.help("", CLI::AppFormatMode::All);
        return kExitOk;
    } catch (const CLI::CallForVersion& e) {
        out << e.what() << '\n';
        return kExitOk;
    } catch (const CLI::ParseError& e) {
        const std::string help = command_path(innermost(app)) + " --help";
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
