#include <gtest/gtest.h>

#include <algorithm>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <thread>
#include <vector>
#include <sys/wait.h>
#include <unistd.h>

#include "common/run_app.h"
#include "common/same_outputs.h"
#include "gridtopo/io/trajectory_io.h"

namespace fs = std::filesystem;
using gridtopo::testing_outputs::slurp;
using gridtopo::testing_outputs::statsWithoutTimeAndRss;
using gridtopo::testing_outputs::withoutLine;

namespace {
using Result = gridtopo::testing_app::AppRun;
Result run(const std::string& args) { return gridtopo::testing_app::runApp("gridtopo-slam", args); }
const std::string kIntel = std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz";
}  // namespace

TEST(SlamApp, WritesEveryOutputForAShortIntelSlice) {
  const fs::path out = gridtopo::test::scratchPath("slam_app_out");
  fs::remove_all(out);
  const Result r = run("-i " + kIntel + " -o " + out.string() + " -c " + GRIDTOPO_SOURCE_DIR +
                       "/config-ini/slam.ini -p 4 -t 2 -q --max-scans 400");
  ASSERT_EQ(r.status, 0) << r.output;
  // -q: the summary line alone ("gridtopo-slam: N scans, ..."), nothing else on stdout or stderr.
  EXPECT_EQ(r.output.rfind("gridtopo-slam: 400 scans, ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  for (const char* f : {"map.png", "map_trajectory.png", "map.pgm", "map.yaml", "map.gridmap.gz", "map.simplemap",
                        "trajectory.txt", "stats.txt", "options.ini"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto traj = gridtopo::io::readTrajectory((out / "trajectory.txt").string());
  EXPECT_EQ(traj.size(), 400u);  // a pose for every scan
  std::ifstream stats(out / "stats.txt");
  std::string line;
  int lines = 0;
  while (std::getline(stats, line)) lines += !line.empty() && line[0] != '#';
  EXPECT_GT(lines, 20);
  EXPECT_LT(lines, 400);
}

TEST(SlamApp, BadIniValuesFailWithFileSectionAndKey) {
  const fs::path ini = gridtopo::test::scratchPath("slam_app_bad.ini");
  const fs::path out = gridtopo::test::scratchPath("slam_app_bad_out");
  fs::remove_all(out);
  std::ofstream(ini) << "[slam]\nparticles = 0\n";
  Result r = run("-i " + kIntel + " -o " + out.string() + " -c " + ini.string() + " -q --max-scans 10");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find(ini.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("[slam] particles"), std::string::npos) << r.output;
  std::ofstream(ini) << "[slam]\nresolution = -0.05\n";
  r = run("-i " + kIntel + " -o " + out.string() + " -c " + ini.string() + " -q --max-scans 10");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("[slam] resolution"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out / "trajectory.txt"));  // nothing written
  r = run("-i " + kIntel + " -o " + out.string() + " -p 0 -q --max-scans 10");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("particles"), std::string::npos) << r.output;
  r = run("-i /nonexistent.clf -o " + out.string() + " -q");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("/nonexistent.clf"), std::string::npos) << r.output;
}

const char* const kOutputs[] = {"map.png", "map_trajectory.png", "map.pgm", "map.yaml", "map.gridmap.gz",
                                "map.simplemap", "trajectory.txt", "options.ini"};

// OUT/options.ini is the run's INI: [slam_run] with the absolute paths, then every option in [slam].
// `gridtopo-slam -c OUT/options.ini` reads its [slam] back (command-line overrides included) and gives the same run.
TEST(SlamApp, OptionsIniOfARunReproducesIt) {
  const fs::path out = gridtopo::test::scratchPath("slam_app_rerun_a");
  const fs::path again = gridtopo::test::scratchPath("slam_app_rerun_b");
  fs::remove_all(out);
  fs::remove_all(again);
  Result r = run("-i " + kIntel + " -o " + out.string() + " -p 3 -s 11 -t 2 --proposal mode-only -q --max-scans 150");
  ASSERT_EQ(r.status, 0) << r.output;
  r = run("-i " + kIntel + " -o " + again.string() + " -c " + (out / "options.ini").string() + " -q --max-scans 150");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string ini = slurp(out / "options.ini");
  EXPECT_EQ(ini.rfind("[slam_run]\ninput = " + fs::absolute(kIntel).lexically_normal().string() + "\noutput = " +
                          out.string() + "\nmax_scans = 150\n\n[slam]\n",
                      0),
            0u)
      << ini;
  EXPECT_NE(ini.find("\nparticles = 3\n"), std::string::npos) << ini;
  EXPECT_NE(ini.find("\nseed = 11\n"), std::string::npos) << ini;
  EXPECT_NE(ini.find("\nproposal = mode-only\n"), std::string::npos) << ini;
  EXPECT_EQ(withoutLine(slurp(again / "options.ini"), "output"), withoutLine(ini, "output"));
  EXPECT_EQ(gridtopo::io::readTrajectory((out / "trajectory.txt").string()).size(), 150u);
  for (const char* f : kOutputs) {
    if (std::string(f) == "options.ini") continue;
    EXPECT_EQ(slurp(again / f), slurp(out / f)) << f;
  }
  EXPECT_EQ(statsWithoutTimeAndRss(slurp(again / "stats.txt")), statsWithoutTimeAndRss(slurp(out / "stats.txt")));
  fs::remove_all(out);
  fs::remove_all(again);
}

namespace {
struct RunIniFixture {
  fs::path dir = gridtopo::test::scratch("run_ini");
  fs::path ini = dir / "run.ini";
  fs::path out = dir / "out";
  void write(const std::string& text) const { std::ofstream(ini) << text; }
};
}  // namespace

// gridtopo-slam RUN.ini, as MRPT's rbpf-slam CONFIG.ini; the options.ini it writes, run again as RUN.ini, writes
// the same files byte for byte (stats.txt but for its wall-time and RSS columns).
TEST(SlamApp, RunIniRunsAndItsOptionsIniReproducesTheRun) {
  RunIniFixture f;
  f.write("; a run\n[slam_run]\ninput = " + kIntel + "\noutput = " + f.out.string() +
          "  ; the output directory\nmax_scans = 120\n\n[slam]\nparticles = 3\nseed = 4\nthreads = 2\n");
  Result r = run(f.ini.string() + " -q");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(gridtopo::io::readTrajectory((f.out / "trajectory.txt").string()).size(), 120u);
  const std::string ini = slurp(f.out / "options.ini");
  EXPECT_NE(ini.find("\nmax_scans = 120\n"), std::string::npos) << ini;
  EXPECT_NE(ini.find("\nparticles = 3\n"), std::string::npos) << ini;
  const fs::path saved = f.dir / "saved";
  fs::copy(f.out, saved);
  fs::remove_all(f.out);
  r = run((saved / "options.ini").string() + " -q");  // writes into out again
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* file : kOutputs) EXPECT_EQ(slurp(f.out / file), slurp(saved / file)) << file;
  EXPECT_EQ(statsWithoutTimeAndRss(slurp(f.out / "stats.txt")), statsWithoutTimeAndRss(slurp(saved / "stats.txt")));
}

TEST(SlamApp, FlagsOverrideTheRunIni) {
  RunIniFixture f;
  f.write("[slam_run]\ninput = " + kIntel + "\noutput = " + f.out.string() +
          "\nmax_scans = 120\n[slam]\nparticles = 3\nthreads = 2\n");
  const fs::path other = f.dir / "other";
  const Result r = run(f.ini.string() + " -o " + other.string() + " -p 2 --max-scans 60 -q");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(f.out));
  EXPECT_EQ(gridtopo::io::readTrajectory((other / "trajectory.txt").string()).size(), 60u);
  const std::string ini = slurp(other / "options.ini");
  EXPECT_NE(ini.find("\noutput = " + other.string() + "\nmax_scans = 60\n"), std::string::npos) << ini;
  EXPECT_NE(ini.find("\nparticles = 2\n"), std::string::npos) << ini;
  EXPECT_NE(ini.find("\nthreads = 2\n"), std::string::npos) << ini;
}

TEST(SlamApp, RunIniErrorsNameFileLineSectionAndKey) {
  RunIniFixture f;
  const std::string ini = f.ini.string();
  auto expectError = [&](const std::string& text, const std::string& message) {
    f.write(text);
    const Result r = run(ini + " -q");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("gridtopo-slam: error: " + ini + message), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(f.out));
  };
  expectError("[slam_run]\noutput = " + f.out.string() + "\n", ":1: [slam_run] input: missing");
  expectError("[slam_run]\ninput = /nonexistent/x.clf\noutput = " + f.out.string() + "\n",
              ":2: [slam_run] input: no such file '/nonexistent/x.clf'");
  expectError("[slam_run]\ninput = " + kIntel + "\n", ":1: [slam_run] output: missing");
  expectError("[slam_run]\ninput = " + kIntel + "\noutput = " + f.out.string() + "\nmax_scan = 5\n",
              ":4: [slam_run] max_scan: unknown key (did you mean 'max_scans'? expected input, output, max_scans)");
  expectError("[slam_run]\ninput = " + kIntel + "\noutput = " + f.out.string() + "\nmax_scans = ten\n",
              ":4: [slam_run] max_scans: cannot parse 'ten' as a non-negative integer");
  expectError("[slam_run]\ninput = " + kIntel + "\n[slma]\nparticles = 3\n",
              ":3: [slma]: unknown section (did you mean [slam]? expected slam_run, slam, loop_closure)");
  expectError("[slam_run]\ninput = " + kIntel + "\noutput = " + f.out.string() + "\n[slam]\nparticle = 3\n",
              ":5: [slam] particle: unknown key");
  expectError("[slam_run]\ninput = " + kIntel + "\noutput = " + f.out.string() + "\n[slam]\nparticles = 0\n",
              ":5: [slam] particles: must be in [1, 100000], got 0");
}

TEST(SlamApp, UsageErrorsWithoutInputOrWithTwoOptionFiles) {
  RunIniFixture f;
  f.write("[slam_run]\ninput = " + kIntel + "\noutput = " + f.out.string() + "\n");
  Result r = run(f.ini.string() + " -c " + GRIDTOPO_SOURCE_DIR + "/config-ini/slam.ini -q");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("either in RUN.ini or with -c"), std::string::npos) << r.output;
  r = run("-o " + f.out.string() + " -q");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("gridtopo-slam: usage: name the log (-i)"), std::string::npos) << r.output;
}

// The reader's decisions against the log's word reach the user of gridtopo-slam, even with -q.
TEST(SlamApp, PrintsTheReadersWarnings) {
  const fs::path dir = gridtopo::test::scratchPath("slam_app_warn");
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream log(dir / "fov_radians.clf");
  log << "PARAM laser_front_laser_fov 3.14159 nohost 0\n";
  for (int i = 0; i < 5; ++i) {  // old FLASER lines: 181 readings, odometry x y theta twice, timestamps
    log << "FLASER 181";
    for (int k = 0; k < 181; ++k) log << " 3.0";
    log << " 0 0 0 0 0 0 " << 100 + i << " nohost " << 100 + i << "\n";
  }
  log.close();
  const Result r = run("-i " + (dir / "fov_radians.clf").string() + " -o " + (dir / "out").string() + " -p 2 -t 1 -q");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("gridtopo-slam: warning: " + (dir / "fov_radians.clf").string() +
                          ": PARAM laser_front_laser_fov 3.14159 read as radians (180 deg)"),
            std::string::npos)
      << r.output;
}

// issue 36: a -c INI is read as strictly as a RUN.ini: a typo in a key or a section is refused with file, line and
// a "did you mean"; a binary file is refused up front without echoing its bytes; nothing is written.
TEST(SlamApp, OptionsFileTyposAndBinaryFilesAreRefused) {
  const fs::path ini = gridtopo::test::scratchPath("slam_app_typo.ini");
  const fs::path out = gridtopo::test::scratchPath("slam_app_typo_out");
  fs::remove_all(out);
  const std::string base = "-i " + kIntel + " -o " + out.string() + " -q --max-scans 10 -c " + ini.string();
  std::ofstream(ini) << "[slam]\nparticlez = 30\n";
  Result r = run(base);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "gridtopo-slam: error: " + ini.string() +
                          ":2: [slam] particlez: unknown key (did you mean 'particles'? not an option of the filter; "
                          "see config-ini/slam.ini)\n");
  std::ofstream(ini) << "[slam]\nparticles = 30\n[slamm]\nparticles = 3\n";
  r = run(base);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "gridtopo-slam: error: " + ini.string() +
                          ":3: [slamm]: unknown section (did you mean [slam]? this app reads slam, loop_closure)\n");
  std::ofstream(ini) << "[loop_closure]\nenabled = false\n";
  r = run(base);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "gridtopo-slam: error: " + ini.string() + ": [slam]: section not found\n");
  r = run("-i " + kIntel + " -o " + out.string() + " -q --max-scans 10 -c " + GRIDTOPO_BIN_DIR + "/gridtopo-slam");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, std::string("gridtopo-slam: error: ") + GRIDTOPO_BIN_DIR +
                          "/gridtopo-slam: not a text INI file (byte 0 is 0x7F)\n");
  EXPECT_FALSE(fs::exists(out));
}

// issue 36 items 1, 2, 5: the output folder is one transaction.
namespace {
std::size_t trajectoryPoses(const fs::path& out) { return gridtopo::io::readTrajectory((out / "trajectory.txt").string()).size(); }
std::vector<std::string> hiddenEntries(const fs::path& dir) {
  std::vector<std::string> hidden;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string()[0] == '.') hidden.push_back(e.path().string());
  return hidden;
}
}  // namespace

// An unusable -o is said before the computation: a full Intel run would outlast the 30 s timeout.
TEST(SlamApp, UnusableOutputFolderIsRefusedBeforeTheRun) {
  const fs::path file = gridtopo::test::scratchPath("slam_app_output_is_a_file");
  std::ofstream(file) << "x";
  // Under `timeout 30`: a run that checked its output only at the end would be killed (status 124).
  const auto timed = [](const std::string& args) {
    FILE* p = popen(("timeout 30 " + std::string(GRIDTOPO_BIN_DIR) + "/gridtopo-slam " + args + " 2>&1").c_str(), "r");
    std::string text;
    char buf[4096];
    for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) text.append(buf, n);
    const int st = pclose(p);
    return Result{WIFEXITED(st) ? WEXITSTATUS(st) : -1, text};
  };
  Result r = timed("-i " + kIntel + " -o " + file.string() + " -q");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(r.output, "gridtopo-slam: error: " + file.string() + ": cannot write the output folder: it exists and is not a folder\n");
  r = timed("-i " + kIntel + " -o /proc/gridtopo-x -q");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(r.output.rfind("gridtopo-slam: error: /proc/gridtopo-x: ", 0), 0u) << r.output;
}

// A full disk (a 64 KiB tmpfs; the outputs of 200 scans take 117 KiB): exit 1, the final file's name and the system's reason, nothing left behind.
TEST(SlamApp, FullDiskNamesTheFileAndLeavesNothing) {
  const fs::path mnt = gridtopo::test::scratchPath("slam_app_tmpfs");
  fs::create_directories(mnt);
  if (std::system(("mount -t tmpfs -o size=64k tmpfs " + mnt.string() + " 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  const Result r = run("-i " + kIntel + " -o " + (mnt / "out").string() + " -p 2 -t 1 -q --max-scans 200");
  const bool empty = fs::is_empty(mnt);
  std::system(("umount " + mnt.string()).c_str());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("gridtopo-slam: error: " + (mnt / "out").string() + "/"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(": cannot write: No space left on device\n"), std::string::npos) << r.output;
  EXPECT_TRUE(empty);
}

// SIGTERM while gridtopo-slam writes its outputs (its stage folder holds trajectory.txt, the first file written):
// the process dies of the signal, the earlier run's folder is intact, no temporary file or stage is left. Killed
// from outside, polling for the write phase; a run that ended before the kill must then be complete.
TEST(SlamApp, SigtermDuringTheWritePhaseLeavesTheEarlierFolderIntact) {
  const fs::path parent = gridtopo::test::scratchPath("slam_app_sigterm");
  fs::remove_all(parent);
  fs::create_directories(parent);
  const fs::path out = parent / "out";
  const std::string common = "-i " + kIntel + " -o " + out.string() + " -p 2 -t 1 -q --max-scans ";
  ASSERT_EQ(run(common + "150").status, 0);
  ASSERT_EQ(trajectoryPoses(out), 150u);
  int killed = 0;
  for (int attempt = 0; attempt < 6 && killed == 0; ++attempt) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      const std::string exe = std::string(GRIDTOPO_BIN_DIR) + "/gridtopo-slam";
      ::execl(exe.c_str(), exe.c_str(), "-i", kIntel.c_str(), "-o", out.c_str(), "-p", "2", "-t", "1", "-q",
              "--max-scans", "400", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    int status = 0;
    bool sent = false;
    for (;;) {
      if (::waitpid(child, &status, WNOHANG) == child) break;
      if (!sent)
        for (const auto& e : fs::directory_iterator(parent))
          if (e.path().filename().string().rfind(".out.tmp-", 0) == 0 && fs::exists(e.path() / "trajectory.txt")) {
            ::kill(child, SIGTERM);
            sent = true;
            break;
          }
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    ASSERT_TRUE(fs::is_directory(out));
    EXPECT_TRUE(hiddenEntries(parent).empty()) << hiddenEntries(parent).front();
    if (WIFSIGNALED(status)) {
      EXPECT_EQ(WTERMSIG(status), SIGTERM);
      EXPECT_EQ(trajectoryPoses(out), 150u);  // the earlier folder, whole
      for (const char* f : {"map.png", "map.pgm", "map.yaml", "map.gridmap.gz", "map.simplemap", "stats.txt"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
      ++killed;
    } else {
      ASSERT_TRUE(WIFEXITED(status));
      EXPECT_EQ(WEXITSTATUS(status), 0);
      EXPECT_EQ(trajectoryPoses(out), 400u);  // done before the kill: the new folder, whole
      ASSERT_EQ(run(common + "150").status, 0);  // the earlier state again for the next attempt
    }
  }
  EXPECT_EQ(killed, 1) << "the write phase was never caught";
}
