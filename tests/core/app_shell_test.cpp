// Every command-line app shares one shell (core/app_shell.h): exit 2 and "<app>: usage: ..." on bad usage, exit 1
// and "<app>: error: <file>..." on bad input, exit 0 on --help.
#include <gtest/gtest.h>

#include <string>

#include "common/run_app.h"
#include "gridtopo/core/app_shell.h"

namespace {
using Result = gridtopo::testing_app::AppRun;
Result run(const std::string& app, const std::string& args) { return gridtopo::testing_app::runApp(app, args); }
const char* kApps[] = {"gridtopo-slam",  "gridtopo-eval",  "gridtopo-import",          "gridtopo-topology",
                       "gridtopo-train", "gridtopo-topology-eval", "gridtopo-topology-compare",
                       "gridtopo-simulate-maps"};
}  // namespace

TEST(AppShell, EveryAppExitsWithTwoOnAnUnknownArgument) {
  for (const char* app : kApps) {
    const Result r = run(app, "--no-such-flag");
    EXPECT_EQ(r.status, 2) << app << "\n" << r.output;
    EXPECT_NE(r.output.find(std::string(app) + ": usage: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(see " + std::string(app) + " --help)"), std::string::npos) << r.output;
  }
}

TEST(AppShell, EveryAppExitsWithZeroOnHelp) {
  for (const char* app : kApps) {
    const Result r = run(app, "--help");
    EXPECT_EQ(r.status, 0) << app << "\n" << r.output;
    EXPECT_NE(r.output.find("USAGE"), std::string::npos) << app << "\n" << r.output;
  }
}

TEST(AppShell, BadInputExitsWithOneAndNamesTheFile) {
  const std::string missing = "/nonexistent/gridtopo_missing.clf";
  for (const auto& [app, args] : std::initializer_list<std::pair<const char*, std::string>>{
           {"gridtopo-slam", "-i " + missing + " -o /tmp/gridtopo_app_shell_out -q"},
           {"gridtopo-import", "-i " + missing + " -o /tmp/gridtopo_app_shell_out.rawlog"},
           {"gridtopo-eval", "-r " + missing + " -l " + missing + " --baseline-odometry"}}) {
    const Result r = run(app, args);
    EXPECT_EQ(r.status, 1) << app << "\n" << r.output;
    EXPECT_NE(r.output.find(std::string(app) + ": error: /nonexistent/gridtopo_missing.clf"), std::string::npos)
        << app << "\n" << r.output;
  }
}

TEST(AppShell, RunAppMapsExceptionsToExitCodes) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(gridtopo::runApp("x", [] { return 0; }), 0);
  EXPECT_EQ(gridtopo::runApp("x", []() -> int { throw gridtopo::UsageError("--a and --b exclude each other"); }), 2);
  EXPECT_EQ(gridtopo::runApp("x", []() -> int { throw gridtopo::InputError("f.ini", 3, "[s] k", "bad"); }), 1);
  EXPECT_EQ(gridtopo::runApp("x", []() -> int { throw std::runtime_error("boom"); }), 1);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("x: usage: --a and --b exclude each other (see x --help)"), std::string::npos) << err;
  EXPECT_NE(err.find("x: error: f.ini:3: [s] k: bad"), std::string::npos) << err;
  EXPECT_NE(err.find("x: error: boom"), std::string::npos) << err;
}
