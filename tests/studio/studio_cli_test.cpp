// `exemplar studio`'s refusals before it serves: one line, exit code 1 or 2, nothing left
// waiting. (Serving until SIGINT is the browser test's: it signals the real process.)

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli.hpp"
#include "studio.hpp"

namespace exemplar::studio {
namespace {

struct CliRun {
    int code = -1;
    std::string out, err;
};

CliRun run(std::vector<std::string> args) {
    args.insert(args.begin(), "exemplar");
    std::vector<const char*> argv;
    for (const std::string& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    const int code = cli::run_cli(static_cast<int>(argv.size()), argv.data(), out, err);
    return {code, out.str(), err.str()};
}

TEST(StudioCli, RefusesBadLimitsAndABusyPortWithOneLine) {
    const CliRun upload = run({"studio", "--max-upload-mb", "0"});
    EXPECT_EQ(upload.code, 1);
    EXPECT_NE(upload.err.find("--max-upload-mb"), std::string::npos) << upload.err;
    const CliRun jobs = run({"studio", "--max-jobs", "0", "--port", "0"});
    EXPECT_EQ(jobs.code, 1);
    EXPECT_NE(jobs.err.find("max-jobs: 0 is invalid (must be 1..16)"), std::string::npos)
        << jobs.err;
    EXPECT_EQ(run({"studio", "--port", "http"}).code, 2);

    // A port another server holds.
    StudioOptions options;
    options.port = 0;
    options.workspace = ::testing::TempDir() + "studio_cli_ws";
    auto busy = StudioServer::create(options);
    ASSERT_TRUE(busy.ok()) << busy.status().message();
    const CliRun taken = run(
        {"studio", "--port", std::to_string((*busy)->port()), "--workspace", options.workspace});
    EXPECT_EQ(taken.code, 1);
    EXPECT_NE(taken.err.find("cannot listen"), std::string::npos) << taken.err;
    EXPECT_EQ(std::count(taken.err.begin(), taken.err.end(), '\n'), 1) << taken.err;
}

TEST(StudioCli, HelpNamesEveryFlag) {
    const CliRun help = run({"studio", "--help"});
    EXPECT_EQ(help.code, 0);
    for (const char* flag :
         {"--port", "--bind", "--workspace", "--max-upload-mb", "--max-jobs", "--threads"}) {
        EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
    }
}

}  // namespace
}  // namespace exemplar::studio
