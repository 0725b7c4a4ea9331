// Help, version, and the CLI reference (docs/cli.md) agreeing with the option table.

#include <cctype>

#include "cli_fixture.hpp"
#include "option_help.hpp"

namespace exemplar::cli::testing {
namespace {

// The stylize flags besides the numeric options: in --help and in docs/cli.md.
constexpr const char* kStylizeFlags[] = {"--style",
                                         "--guide",
                                         "--weight",
                                         "--weight-map",
                                         "--output",
                                         "--config",
                                         "--usage",
                                         "--target-mask",
                                         "--source-mask",
                                         "--source-labels",
                                         "--target-labels",
                                         "--source-orientation",
                                         "--target-orientation",
                                         "--init",
                                         "--init-nnf",
                                         "--inpaint",
                                         "--size",
                                         "--save-nnf",
                                         "--save-error",
                                         "--style-weights",
                                         "--threads",
                                         "--quiet"};

// --help lists the everyday options and the quality dial; the search-tuning knobs only appear
// under --help-all, each with its range and default from the option table.
TEST(CliHelp, StylizeHelpIsGeneratedFromTheOptionTable) {
    const CliRun h = run({"stylize", "--help"});
    EXPECT_EQ(h.code, 0);
    EXPECT_TRUE(h.err.empty());
    const CliRun all = run({"stylize", "--help-all"});
    EXPECT_EQ(all.code, 0);
    EXPECT_TRUE(all.err.empty());
    int experts = 0;
    for (const OptionSpec& spec : synthesis_option_specs()) {
        const std::string flag = std::string("--").append(spec.name).append(" ");
        const std::string range = std::string("[").append(format_range(spec)).append(", default ");
        const std::string described = range + format_default(spec) + "]";
        EXPECT_NE(all.out.find(flag), std::string::npos) << flag;
        EXPECT_NE(all.out.find(described), std::string::npos) << flag;
        if (is_expert_option(spec)) {
            ++experts;
            EXPECT_EQ(h.out.find(flag), std::string::npos) << flag << " is for --help-all";
        } else {
            EXPECT_NE(h.out.find(described), std::string::npos) << flag;
        }
    }
    EXPECT_GE(experts, 15);
    EXPECT_NE(h.out.find("--help-all"), std::string::npos);
    EXPECT_NE(h.out.find("--quality"), std::string::npos);
    // --help-all tells what each preset sets, as flags.
    for (Quality q : {Quality::Fast, Quality::Best}) {
        const std::string line =
            std::string("--quality ").append(to_string(q)).append(" = ").append(quality_flags(q));
        EXPECT_NE(all.out.find(line + "\n"), std::string::npos) << line;
        EXPECT_EQ(h.out.find(line), std::string::npos) << line;
    }
    const auto flags = [](const std::string& text) {
        int count = 0;
        for (std::size_t at = text.find("\n  -"); at != std::string::npos;
             at = text.find("\n  -", at + 1)) {
            ++count;
        }
        return count;
    };
    EXPECT_LE(flags(h.out), 30) << h.out;  // 43 numeric and other flags before the dial
    EXPECT_GE(flags(all.out), flags(h.out) + experts);
    for (const char* flag : kStylizeFlags) {
        EXPECT_NE(h.out.find(flag), std::string::npos) << flag;
    }
    EXPECT_NE(h.out.find("a guide without --weight has weight 1"), std::string::npos);
}

TEST(CliHelp, TopLevelHelpVersionAndApplyNnfHelp) {
    const CliRun top = run({"--help"});
    EXPECT_EQ(top.code, 0);
    EXPECT_NE(top.out.find("stylize"), std::string::npos);
    EXPECT_NE(top.out.find("apply-nnf"), std::string::npos);
    const CliRun apply = run({"apply-nnf", "--help"});
    EXPECT_EQ(apply.code, 0);
    EXPECT_NE(apply.out.find("--patch-size"), std::string::npos);
    const CliRun version = run({"--version"});
    EXPECT_EQ(version.code, 0);
    EXPECT_EQ(version.out.rfind("exemplar ", 0), 0u) << version.out;
}

TEST(CliHelp, NumbersAreWrittenPlainly) {
    EXPECT_EQ(format_number(5), "5");
    EXPECT_EQ(format_number(0.95f), "0.95");
    EXPECT_EQ(format_number(1e6), "1000000");
    EXPECT_EQ(format_number(9007199254740992.0), "9007199254740992");
}

// docs/cli.md lists every numeric option as the table has it, and marks the expert ones: a row
// | `--name` | INT or FLOAT | doc | range | default | `--help` or `--help-all` |
// and tells what each quality preset sets, as `--help-all` does.
TEST(CliDocs, ReferenceAgreesWithTheOptionTable) {
    std::ifstream in(std::string(EXEMPLAR_SOURCE_DIR) + "/docs/cli.md");
    ASSERT_TRUE(in);
    std::vector<std::string> lines;
    std::string text;
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
        text.append(line).append("\n");
    }
    for (const OptionSpec& spec : synthesis_option_specs()) {
        std::string row = std::string("| `--").append(spec.name).append("` | ");
        row.append(is_integer_option(spec) ? "INT" : "FLOAT").append(" | ");
        row.append(spec.doc).append(" | ").append(format_range(spec)).append(" | ");
        row.append(format_default(spec)).append(" | ");
        row.append(is_expert_option(spec) ? "`--help-all`" : "`--help`").append(" |");
        EXPECT_NE(std::find(lines.begin(), lines.end(), row), lines.end())
            << "docs/cli.md should have the row\n"
            << row;
    }
    for (const char* flag : kStylizeFlags) {
        EXPECT_NE(text.find(std::string("`").append(flag)), std::string::npos)
            << "docs/cli.md should describe " << flag;
    }
    for (Quality q : {Quality::Fast, Quality::Best}) {
        const std::string says =
            std::string("`").append(to_string(q)).append("` = `").append(quality_flags(q)) + "`";
        EXPECT_NE(text.find(says), std::string::npos) << "docs/cli.md should say " << says;
    }
}

// The manual pages come from the parser itself: a page per verb and sub-verb, each listing every
// flag its --help shows and, for stylize, every tuning knob of the option table.
TEST(CliManPages, EveryVerbHasAPageWithEveryFlag) {
    const auto roff_flag = [](std::string flag) {
        std::string escaped;
        for (char c : flag) escaped += c == '-' ? std::string("\\-") : std::string(1, c);
        return escaped;
    };
    const auto pages = man_pages();
    ASSERT_FALSE(pages.empty());
    EXPECT_EQ(pages.front().first, "exemplar");
    int verbs = 0;
    for (const auto& [name, page] : pages) {
        EXPECT_EQ(page.rfind(".TH " + roff_flag(name) + " 1 ", 0), 0u) << name;
        EXPECT_NE(page.find(".SH NAME\n"), std::string::npos) << name;
        if (name == "exemplar") continue;
        ++verbs;
        // "exemplar-stylit-sheet" is `exemplar stylit sheet --help`.
        std::vector<std::string> args;
        std::istringstream words(name.substr(std::string("exemplar-").size()));
        for (std::string word; std::getline(words, word, '-');) args.push_back(word);
        if (args.front() == "apply") args = {"apply-nnf"};
        if (args.front() == "vectorize") args = {"vectorize-style"};
        args.push_back("--help");
        const CliRun help = run(args);
        ASSERT_EQ(help.code, 0) << name << ": " << help.err;
        int flags = 0;
        for (std::size_t at = help.out.find("--"); at != std::string::npos;
             at = help.out.find("--", at + 2)) {
            std::size_t end = at + 2;
            while (
                end < help.out.size() &&
                (std::isalnum(static_cast<unsigned char>(help.out[end])) || help.out[end] == '-'))
                ++end;
            const std::string flag = help.out.substr(at, end - at);
            if (flag.size() < 4 || (at > 0 && help.out[at - 1] != ' ' && help.out[at - 1] != ','))
                continue;
            ++flags;
            EXPECT_NE(page.find(roff_flag(flag)), std::string::npos) << name << " lacks " << flag;
        }
        EXPECT_GT(flags, 0) << name;
    }
    EXPECT_GE(verbs, 7);
    const auto stylize = std::find_if(pages.begin(), pages.end(), [](const auto& page) {
        return page.first == "exemplar-stylize";
    });
    ASSERT_NE(stylize, pages.end());
    for (const OptionSpec& spec : synthesis_option_specs())
        EXPECT_NE(stylize->second.find(roff_flag(std::string("--").append(spec.name))),
                  std::string::npos)
            << spec.name;
    // No line of a page starts with a dot that is not a request.
    for (const auto& [name, page] : pages) {
        std::istringstream lines(page);
        for (std::string line; std::getline(lines, line);) {
            if (line.empty() || line[0] != '.') continue;
            const std::string request = line.substr(0, line.find(' '));
            EXPECT_TRUE(request == ".TH" || request == ".SH" || request == ".TP" ||
                        request == ".B" || request == ".nf" || request == ".fi")
                << name << ": " << line;
        }
    }
}

}  // namespace
}  // namespace exemplar::cli::testing
