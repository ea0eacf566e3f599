// An experiment whose runner is killed (SIGKILL, no chance to clean up) resumes: the run in progress dies with it
// (no orphan keeps writing), the runs recorded before are not run again, and the next call completes the rest.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "common/run_app.h"
#include "experiment/experiment_files.h"
#include "gridtopo/experiment/subprocess.h"

namespace fs = std::filesystem;
using namespace gridtopo;

namespace {
const std::string kQuick = std::string(GRIDTOPO_SOURCE_DIR) + "/config-ini/experiments/quick.ini";

std::vector<fs::path> results(const fs::path& out) {
  std::vector<fs::path> found;
  if (!fs::exists(out / "runs")) return found;
  for (const auto& d : fs::directory_iterator(out / "runs"))
    if (fs::exists(d.path() / "result.json")) found.push_back(d.path() / "result.json");
  return found;
}

/// Processes whose command line mentions `text` (read from /proc; for the no-orphan check only).
int processesMentioning(const std::string& text) {
  int n = 0;
  for (const auto& p : fs::directory_iterator("/proc")) {
    const std::string name = p.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmd = test::readText(p.path() / "cmdline");
    for (char& c : cmd) c = c == '\0' ? ' ' : c;
    n += cmd.find(text) != std::string::npos;
  }
  return n;
}
}  // namespace

TEST(ExperimentResume, AKilledRunnerResumes) {
  const fs::path out = test::scratch("resume");
  const std::string exe = std::string(GRIDTOPO_BIN_DIR) + "/gridtopo-experiment";
  const pid_t pid = experiment::spawnProcess({exe, kQuick, "-o", out.string(), "-j", "1", "-q"},
                                             (out.parent_path() / "first.log").string());
  const auto t0 = std::chrono::steady_clock::now();
  while (results(out).empty() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(pid, SIGKILL);
  experiment::ProcessResult pr;
  experiment::reapChild(pid, true, pr);
  EXPECT_EQ(pr.signal, SIGKILL);
  const auto done = results(out);
  ASSERT_EQ(done.size(), 1u) << test::readText(out.parent_path() / "first.log");
  const std::string first_record = test::readText(done[0]);
  // The gridtopo-slam of the second run died with its runner.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(processesMentioning(out.string() + "/runs/"), 0);
  EXPECT_FALSE(fs::exists(out / "results.csv"));

  const auto r = testing_app::runApp("gridtopo-experiment", kQuick + " -o " + out.string() + " -j 2");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("1 of 4 runs already done"), std::string::npos) << r.output;
  EXPECT_EQ(test::readText(done[0]), first_record);  // not run again
  EXPECT_EQ(results(out).size(), 4u);
  const std::string csv = test::readText(out / "results.csv");
  EXPECT_EQ(test::countLines(csv), 5u);
  EXPECT_EQ(csv.find(",failed,"), std::string::npos);
  EXPECT_EQ(csv.find(",crashed,"), std::string::npos);
}
