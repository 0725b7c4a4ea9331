#include "cli.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <new>
#include <string>
#include <utility>
#include <vector>

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

// The whole command line: the top-level app and every verb with its flags. Built once per run
// (and by man_pages, so the pages list exactly what the parser accepts).
struct CommandLine {
    // Configures the top-level app; called by the first verb's initializer, after `app`.
    static CLI::App& make_app(CLI::App& a) {
        a.set_version_flag("--version", std::string("exemplar ") + EXEMPLAR_VERSION);
        a.require_subcommand(1);
        return a;
    }
    CLI::App app{"exemplar: example-based stylization (guided patch-based synthesis)", "exemplar"};
    StylizeCommand stylize{make_app(app)};
    ApplyNnfCommand apply_nnf{app};
    RenderCommand render{app};
    StylitCommand stylit{app};
    FlowCommand flow{app};
    BeautifyCommand beautify{app};
    AnimateCommand animate{app};
    FluidCommand fluid{app};
    NoisyCommand noisy{app};
    DirectionsCommand directions{app};
    PaintCommand paint{app};
    BrushCommand brush{app};
    FillCommand fill{app};
    VectorizeStyleCommand vectorize_style{app};
    NprCommand npr{app};
    StudioCommand studio{app};
};

// roff text: a backslash as \e, a hyphen as \- (so flags copy and search as typed), and a
// dot or quote at the start of a line behind \& (it would otherwise read as a request).
std::string roff(const std::string& text) {
    std::string out;
    bool line_start = true;
    for (char c : text) {
        if (line_start && (c == '.' || c == '\'')) out += "\\&";
        line_start = c == '\n';
        if (c == '\\') {
            out += "\\e";
        } else if (c == '-') {
            out += "\\-";
        } else {
            out += c;
        }
    }
    return out;
}

std::string man_page(const CLI::App& verb, const std::string& name) {
    std::string page =
        ".TH " + roff(name) + " 1 \"\" \"exemplar " + EXEMPLAR_VERSION + "\" \"exemplar manual\"\n";
    page += ".SH NAME\n" + roff(name) + " \\- " + roff(verb.get_description()) + "\n";
    page += ".SH SYNOPSIS\n.B " + roff(name) + "\n[\\fIOPTIONS\\fR]\n";
    // Groups in the order --help shows them; group "" (the search-tuning knobs that only
    // --help-all shows) last.
    std::vector<std::pair<std::string, std::vector<const CLI::Option*>>> groups;
    for (const CLI::Option* option : verb.get_options()) {
        auto group = std::find_if(groups.begin(), groups.end(),
                                  [&](const auto& g) { return g.first == option->get_group(); });
        if (group == groups.end()) group = groups.insert(groups.end(), {option->get_group(), {}});
        group->second.push_back(option);
    }
    std::stable_partition(groups.begin(), groups.end(),
                          [](const auto& g) { return !g.first.empty(); });
    for (const auto& [group, options] : groups) {
        std::string heading = group.empty() ? "TUNING OPTIONS" : group;
        std::transform(heading.begin(), heading.end(), heading.begin(),
                       [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
        page += ".SH " + roff(heading) + "\n";
        for (const CLI::Option* option : options) {
            // get_name() is empty for the hidden group, so the names are put together here.
            std::string names;
            for (const std::string& short_name : option->get_snames())
                names += (names.empty() ? "-" : ", -") + short_name;
            for (const std::string& long_name : option->get_lnames())
                names += (names.empty() ? "--" : ", --") + long_name;
            if (names.empty()) names = option->get_single_name();
            const std::string type = option->get_type_name();
            page += ".TP\n.B " + roff(names) + (type.empty() ? "" : " \\fI" + roff(type) + "\\fR") +
                    "\n" + roff(option->get_description());
            const std::string fallback = option->get_default_str();
            if (!fallback.empty()) page += " (default: " + roff(fallback) + ")";
            page += "\n";
        }
    }
    for (const CLI::App* sub : verb.get_subcommands({})) {
        page += ".SH COMMAND " + roff(sub->get_name()) + "\n" + roff(sub->get_description()) +
                "\nSee \\fB" + roff(name + "-" + sub->get_name()) + "\\fR(1).\n";
    }
    if (!verb.get_footer().empty())
        page += ".SH EXAMPLES\n.nf\n" + roff(verb.get_footer()) + "\n.fi\n";
    page += ".SH SEE ALSO\n\\fBexemplar\\fR(1)\n";
    return page;
}

void add_pages(const CLI::App& verb, const std::string& name,
               std::vector<std::pair<std::string, std::string>>& pages) {
    pages.emplace_back(name, man_page(verb, name));
    for (const CLI::App* sub : verb.get_subcommands({}))
        add_pages(*sub, name + "-" + sub->get_name(), pages);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> man_pages() {
    CommandLine cli;
    std::vector<std::pair<std::string, std::string>> pages;
    pages.emplace_back("exemplar", man_page(cli.app, "exemplar"));
    for (const CLI::App* verb : cli.app.get_subcommands({}))
        add_pages(*verb, "exemplar-" + verb->get_name(), pages);
    return pages;
}

// The one place where errors become exit codes.
int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err,
            bool err_is_terminal) {
    CommandLine cli;
    CLI::App& app = cli.app;
    const Streams streams{out, err, err_is_terminal};

    Status status;
    try {
        app.parse(argc, argv);
        if (cli.stylize.parsed()) {
            status = cli.stylize.run(streams);
        } else if (cli.apply_nnf.parsed()) {
            status = cli.apply_nnf.run(streams);
        } else if (cli.render.parsed()) {
            status = cli.render.run(streams);
        } else if (cli.stylit.parsed()) {
            status = cli.stylit.run(streams);
        } else if (cli.flow.parsed()) {
            status = cli.flow.run(streams);
        } else if (cli.beautify.parsed()) {
            status = cli.beautify.run(streams);
        } else if (cli.animate.parsed()) {
            status = cli.animate.run(streams);
        } else if (cli.fluid.parsed()) {
            status = cli.fluid.run(streams);
        } else if (cli.noisy.parsed()) {
            status = cli.noisy.run(streams);
        } else if (cli.directions.parsed()) {
            status = cli.directions.run(streams);
        } else if (cli.paint.parsed()) {
            status = cli.paint.run(streams);
        } else if (cli.brush.parsed()) {
            status = cli.brush.run(streams);
        } else if (cli.fill.parsed()) {
            status = cli.fill.run(streams);
        } else if (cli.vectorize_style.parsed()) {
            status = cli.vectorize_style.run(streams);
        } else if (cli.npr.parsed()) {
            status = cli.npr.run(streams);
        } else if (cli.studio.parsed()) {
            status = cli.studio.run(streams);
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
