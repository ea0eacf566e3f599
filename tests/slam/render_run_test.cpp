// gridtopo-render's run (slam/render_run.h): the simulated pillar room re-rendered from its true poses.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/scratch.h"
#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/io/rawlog_io.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/render_run.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
slam::RenderRunSpec pillarRoom(const fs::path& dir) {
  const auto log = sim::simulatePillarRoom(150);
  slam::RenderRunSpec spec;
  spec.input = (dir / "room.rawlog").string();
  spec.trajectory = (dir / "truth.txt").string();
  io::writeRawlog(spec.input, log.records);
  io::writeTrajectory(spec.trajectory, log.timedTruth(), {"truth"});
  spec.resolution = 0.05;
  return spec;
}
}  // namespace

TEST(RenderRun, AWindowAroundAPointAndTheWholeMap) {
  const fs::path dir = test::scratch("render");
  slam::RenderRunSpec spec = pillarRoom(dir);
  spec.center = "6 3";
  spec.size = 2;
  const slam::RenderRun window = slam::renderRun(spec);
  EXPECT_EQ(window.image.cols, 41);  // 2 m at 5 cm, the cells of both edges included
  EXPECT_EQ(window.image.rows, 41);
  EXPECT_DOUBLE_EQ(window.window.x0, 5.0);
  EXPECT_EQ(window.loop_text, "");
  EXPECT_NE(window.report_json.find("\"window_m\""), std::string::npos);
  EXPECT_EQ(window.report_json.find("loop_closure"), std::string::npos);

  spec.center.reset();
  const slam::RenderRun whole = slam::renderRun(spec);
  // The room is 12 m x 6 m: the whole map covers it (the beams reach the walls).
  EXPECT_GE(whole.image.cols, 200);
  EXPECT_GE(whole.image.rows, 100);
}

TEST(RenderRun, BadWindowsAreUsageErrorsAndNoLoopClosureIsBadInput) {
  const fs::path dir = test::scratch("render_bad");
  slam::RenderRunSpec spec = pillarRoom(dir);
  spec.center = "6";
  EXPECT_THROW(slam::renderRun(spec), UsageError);
  spec.center.reset();
  spec.resolution = 0;
  EXPECT_THROW(slam::renderRun(spec), UsageError);
  spec.resolution = 0.05;
  spec.loop_closure = true;
  spec.min_travel = 1000;  // the ellipse is ~21 m round: never 1000 m between two visits
  try {
    slam::renderRun(spec);
    FAIL() << "a loop closure found";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), spec.trajectory);
    EXPECT_NE(e.message().find("no loop closure"), std::string::npos);
  }
}
