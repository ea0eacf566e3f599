#include <gtest/gtest.h>

#include "common/scratch.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/same_outputs.h"
#include "gridtopo/core/error.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/options_ini.h"
#include "gridtopo/slam/slam_outputs.h"
#include "gridtopo/slam/slam_run.h"

using namespace gridtopo;
using testing_outputs::expectSameTrajectory;
using testing_outputs::statsWithoutTimeAndRss;
namespace fs = std::filesystem;

namespace {
// The first three legs of the simulated office loop: 204 scans, of which the update policy processes 70.
std::shared_ptr<const std::vector<ScanRecord>> simulatedLog() {
  static const auto log = [] {
    auto wp = sim::officeLoopWaypoints(1);
    wp.resize(3);
    return std::make_shared<const std::vector<ScanRecord>>(
        sim::simulate(sim::FloorPlan::officeLoop(), wp, sim::SimOptions{}).records);
  }();
  return log;
}
constexpr std::size_t kScans = 204, kSteps = 70;

slam::SlamOptions smallOptions() {
  slam::SlamOptions o;
  o.particles = 6;
  o.seed = 5;
  o.threads = 2;
  return o;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}
std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}
}  // namespace

TEST(SlamRun, StatsRowsOnePerProcessedScanWithTheProcessRss) {
  slam::SlamRun run(simulatedLog(), smallOptions());
  EXPECT_EQ(run.scanLimit(), kScans);
  run.runToEnd();
  EXPECT_TRUE(run.atEnd());
  EXPECT_EQ(run.scansFed(), kScans);
  ASSERT_EQ(run.filter().stepsProcessed(), kSteps);
  auto rows = lines(run.statsText());
  // After the step rows, with loop closure, its table and summary ('#' lines).
  while (rows.size() > kSteps + 1 && rows.back().rfind("# ", 0) == 0) rows.pop_back();
  ASSERT_EQ(rows.size(), kSteps + 1);
  EXPECT_EQ(rows[0], std::string("# ") + slam::kStatsColumns + " rss_kb");
  const auto& stats = run.filter().stats();
  for (std::size_t i = 0; i < kSteps; ++i) {
    const auto w = words(rows[i + 1]);
    ASSERT_EQ(w.size(), 14u) << rows[i + 1];
    // The row is statsRow's, then the resident memory in kB (a live process holds more than a megabyte).
    EXPECT_EQ(rows[i + 1].rfind(slam::statsRow(stats[i]) + ' ', 0), 0u) << rows[i + 1];
    EXPECT_EQ(std::stoul(w[0]), i);
    EXPECT_EQ(std::stoul(w[1]), stats[i].scan_index);
    EXPECT_EQ(w[6], "6");  // particles
    // The distinct histories 40 processed scans back: one at the start (every particle's root is the first
    // pose), at most one per particle.
    EXPECT_EQ(std::stoi(w[11]), stats[i].lineages);
    EXPECT_GE(stats[i].lineages, 1);
    EXPECT_LE(stats[i].lineages, 6);
    if (i < slam::kLineageLag) {
      EXPECT_EQ(stats[i].lineages, 1) << i;
    }
    // Processed scans back to the particles' common ancestor: at most the path's length; the lineages 40 scans
    // back are one only where the particles met at or after that.
    EXPECT_EQ(std::stoul(w[12]), stats[i].coalescence);
    EXPECT_LE(stats[i].coalescence, i);
    if (stats[i].coalescence <= slam::kLineageLag) {
      EXPECT_EQ(stats[i].lineages, 1) << i;
    }
    if (stats[i].lineages > 1) {
      EXPECT_GT(stats[i].coalescence, slam::kLineageLag) << i;
    }
    EXPECT_GT(std::stoul(w[13]), 1024u);
  }
  EXPECT_EQ(stats.front().scan_index, 0u);
  EXPECT_GT(run.filterSeconds(), 0.0);
}

TEST(SlamRun, StepByStepIsTheSameRunAsToTheEnd) {
  slam::SlamRun stepped(simulatedLog(), smallOptions());
  std::size_t processed = 0;
  while (!stepped.atEnd()) processed += stepped.step();
  EXPECT_EQ(processed, kSteps);
  EXPECT_THROW(stepped.step(), std::logic_error);

  slam::SlamRun whole(simulatedLog(), smallOptions());
  std::vector<std::size_t> reported;
  whole.runToEnd([&](std::size_t fed, std::size_t total) {
    EXPECT_EQ(total, kScans);
    reported.push_back(fed);
  });
  // Every 64 scans and once at the end.
  EXPECT_EQ(reported, (std::vector<std::size_t>{0, 64, 128, 192, kScans}));

  expectSameTrajectory(stepped.filter().trajectory(), whole.filter().trajectory());
  EXPECT_EQ(statsWithoutTimeAndRss(stepped.statsText()), statsWithoutTimeAndRss(whole.statsText()));
}

TEST(SlamRun, MaxScansFeedsTheFirstScansOnly) {
  slam::SlamRun run(simulatedLog(), smallOptions(), 40);
  EXPECT_EQ(run.scanLimit(), 40u);
  run.runToEnd();
  EXPECT_EQ(run.filter().trajectory().size(), 40u);
  slam::SlamRun all(simulatedLog(), smallOptions(), 100000);
  EXPECT_EQ(all.scanLimit(), kScans);
}

// outputs() leaves the run going; finish() gives the same set after freeing all particles but the best.
TEST(SlamRun, FinishGivesTheOutputsOfTheRunAndEndsIt) {
  slam::SlamRun run(simulatedLog(), smallOptions());
  EXPECT_THROW(run.outputs({"h"}), std::runtime_error);  // nothing processed yet
  run.runToEnd();
  const slam::SlamOutputs live = run.outputs({"a header"});
  EXPECT_FALSE(run.finished());
  EXPECT_EQ(live.options_ini, slam::slamOptionsIni(smallOptions()));
  EXPECT_EQ(live.simplemap.size(), kSteps);
  EXPECT_EQ(live.trajectory.size(), kScans);
  const slam::SlamOutputs last = run.finish({"a header"}, "[slam_run]\n");
  EXPECT_TRUE(run.finished());
  EXPECT_THROW(run.step(), std::logic_error);
  EXPECT_THROW(run.filter(), std::logic_error);
  EXPECT_EQ(last.options_ini, "[slam_run]\n");
  EXPECT_EQ(last.stats, live.stats);
  EXPECT_EQ(last.trajectory_header, std::vector<std::string>{"a header"});
  expectSameTrajectory(last.trajectory, live.trajectory);
  ASSERT_EQ(last.simplemap.size(), live.simplemap.size());
  ASSERT_EQ(last.grid.getSizeX(), live.grid.getSizeX());
  ASSERT_EQ(last.grid.getSizeY(), live.grid.getSizeY());
  for (unsigned y = 0; y < last.grid.getSizeY(); ++y)
    for (unsigned x = 0; x < last.grid.getSizeX(); ++x)
      ASSERT_EQ(last.grid.getCell(x, y), live.grid.getCell(x, y)) << x << "," << y;
}

TEST(SlamRun, FinishAndWriteWritesTheWholeSet) {
  const fs::path dir = gridtopo::test::scratchPath("slam_run_test_out");
  fs::remove_all(dir);
  slam::SlamRun run(simulatedLog(), smallOptions());
  run.runToEnd();
  const std::string stats = run.statsText();
  run.finishAndWrite(dir.string(), {"slam_run_test", "second line"});
  for (const char* f : {"map.png", "map_trajectory.png", "map.pgm", "map.yaml", "map.gridmap.gz", "map.simplemap",
                        "trajectory.txt", "stats.txt", "options.ini"})
    EXPECT_TRUE(fs::is_regular_file(dir / f)) << f;
  EXPECT_EQ(io::readTrajectory((dir / "trajectory.txt").string()).size(), kScans);
  std::ostringstream text;
  text << std::ifstream(dir / "stats.txt").rdbuf();
  EXPECT_EQ(text.str(), stats);
  mrpt::maps::CSimpleMap sm;
  mrpt::io::CFileGZInputStream f((dir / "map.simplemap").string());
  auto a = mrpt::serialization::archiveFrom(f);
  a >> sm;
  EXPECT_EQ(sm.size(), kSteps);
  fs::remove_all(dir);
}

// A run without a log (the MRPT builder's): the same run as over the log, keeping only the processed scans' ranges.
TEST(SlamRun, FedScanByScanIsTheSameRunAndKeepsOnlyTheProcessedRanges) {
  slam::SlamRun fed(smallOptions());
  EXPECT_THROW(fed.step(), std::logic_error);  // nothing to step through
  std::size_t processed = 0;
  for (const auto& r : *simulatedLog()) processed += fed.feed(r);
  EXPECT_EQ(processed, kSteps);
  EXPECT_EQ(fed.scansFed(), kScans);
  slam::SlamRun over_log(simulatedLog(), smallOptions());
  over_log.runToEnd();
  EXPECT_THROW(over_log.feed(simulatedLog()->front()), std::logic_error);
  expectSameTrajectory(fed.filter().trajectory(), over_log.filter().trajectory());
  std::size_t with_ranges = 0;
  for (const auto& r : fed.scans()) with_ranges += !r.scan.ranges.empty();
  EXPECT_EQ(with_ranges, kSteps);
  EXPECT_EQ(fed.simpleMap().size(), kSteps);
}

TEST(SlamRun, BadOptionsAndEmptyLogsAreInputErrors) {
  auto o = smallOptions();
  o.particles = 0;
  EXPECT_THROW(slam::SlamRun(simulatedLog(), o), InputError);
  EXPECT_THROW(slam::SlamRun{o}, InputError);
  EXPECT_THROW(slam::SlamRun(std::make_shared<const std::vector<ScanRecord>>(), smallOptions()), InputError);
}
