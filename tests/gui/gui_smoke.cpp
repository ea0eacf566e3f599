// Smoke test of the real gridtopo-gui binary under Xvfb: a short slice of Intel run through the test hooks
// (--run-steps, --screenshot, --quit), the same with the live topology over the SLAM map (--live-topology), the
// topology view on a floor plan with a scripted mouse click on a cell (wxUIActionSimulator through XTest), and a bad
// file, and a run with the loop closure on. Screenshots are checked for map pixels, particles, the
// trajectory and the label overlay (not a blank or black window).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "test_helpers.h"

using namespace gridtopo;

namespace {
const std::string kGui = GRIDTOPO_BIN_DIR "/gridtopo-gui";

int runGui(const std::string& args, const std::string& log) {
  const std::string cmd = std::string(GRIDTOPO_XVFB_RUN) + " -a -s '-screen 0 1400x1000x24' " + kGui + " " + args +
                          " > " + log + " 2>&1";
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}
std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
// Pixels within `tol` of a BGR colour.
int countColour(const cv::Mat& img, cv::Vec3b c, int tol = 0) {
  int n = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int x = 0; x < img.cols; ++x) {
      const cv::Vec3b v = img.at<cv::Vec3b>(r, x);
      if (std::abs(v[0] - c[0]) <= tol && std::abs(v[1] - c[1]) <= tol && std::abs(v[2] - c[2]) <= tol) ++n;
    }
  return n;
}
int countIf(const cv::Mat& img, const std::function<bool(const cv::Vec3b&)>& f) {
  int n = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int x = 0; x < img.cols; ++x) n += f(img.at<cv::Vec3b>(r, x));
  return n;
}
}  // namespace

TEST(GuiSmoke, SlamViewShowsMapParticlesAndTrajectory) {
  guitest::TempDir tmp;
  const int rc = runGui("--max-scans 400 --particles 10 --run-steps 40 --size 1100x800 --screenshot " + (tmp / "slam.png") +
                            " --export-view " + (tmp / "view.png") + " --quit " GRIDTOPO_DATA_DIR "/slam/intel.clf.gz",
                        tmp / "log.txt");
  ASSERT_EQ(rc, 0) << slurp(tmp / "log.txt");
  EXPECT_NE(slurp(tmp / "log.txt").find("40 updates"), std::string::npos) << slurp(tmp / "log.txt");
  const cv::Mat shot = cv::imread(tmp / "slam.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(shot.empty());
  EXPECT_EQ(shot.cols, 1100);
  cv::Scalar mean, sd;
  cv::meanStdDev(shot, mean, sd);
  EXPECT_GT(sd[0] + sd[1] + sd[2], 30.0) << "blank window";
  EXPECT_GT(mean[0] + mean[1] + mean[2], 60.0) << "black window";
  // Map: free cells white, occupied cells dark; particles: the best one pure red (BGR 0,0,255); trajectory: the
  // best particle's path (BGR 0,0,230).
  const int free_px = countColour(shot, {255, 255, 255}, 6);
  const int wall_px = countIf(shot, [](const cv::Vec3b& v) { return v[0] < 40 && v[1] < 40 && v[2] < 40; });
  const int best_particle = countColour(shot, {0, 0, 255}, 0);
  const int path_px = countColour(shot, {0, 0, 230}, 0);
  EXPECT_GT(free_px, 5000);
  EXPECT_GT(wall_px, 200);
  EXPECT_GE(best_particle, 15);
  EXPECT_GE(path_px, 30);
  // The other particles: colour (255 (1 - w), 60, 255 w) by weight.
  const int other_particles = countIf(shot, [](const cv::Vec3b& v) { return v[1] == 60 && std::abs(v[0] + v[2] - 255) <= 3; });
  EXPECT_GE(other_particles, 5);
  std::cerr << "free " << free_px << " walls " << wall_px << " best particle " << best_particle << " other particles "
            << other_particles << " path " << path_px << "\n";
  // The exported view is the canvas alone and shows the same layers.
  const cv::Mat view = cv::imread(tmp / "view.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(view.empty());
  EXPECT_GT(countColour(view, {0, 0, 230}, 0), 30);
  EXPECT_LT(view.cols, shot.cols);
}

TEST(GuiSmoke, LiveTopologyDrawsLabelsAndGraphOnTheGrowingSlamMap) {
  guitest::TempDir tmp;
  // Every 100 updates and at the pause: the topology of 100 updates, then of 200 (the pause adds no third request).
  const int rc = runGui("--max-scans 1500 --particles 8 --run-steps 200 --live-topology 100 --size 1100x800"
                        " --export-view " + (tmp / "view.png") + " --screenshot " + (tmp / "shot.png") +
                            " --quit " GRIDTOPO_DATA_DIR "/slam/intel.clf.gz",
                        tmp / "log.txt");
  const std::string log = slurp(tmp / "log.txt");
  ASSERT_EQ(rc, 0) << log;
  EXPECT_NE(log.find("200 updates, run"), std::string::npos) << log;
  EXPECT_NE(log.find("live topology of scan "), std::string::npos) << log;
  EXPECT_NE(log.find(" (200 updates): "), std::string::npos) << log;
  EXPECT_NE(log.find("2 computed, 0 dropped"), std::string::npos) << log;
  // The SLAM view (no topology view was opened) shows room and corridor colours over the map, and the graph's nodes.
  const cv::Mat view = cv::imread(tmp / "view.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(view.empty());
  const int room_px = countIf(view, [](const cv::Vec3b& v) { return v[0] > v[1] + 40 && v[0] > v[2] + 60; });
  const int corr_px = countIf(view, [](const cv::Vec3b& v) { return v[1] > v[0] + 40 && v[1] > v[2] + 40; });
  const int free_px = countColour(view, {255, 255, 255}, 6);
  std::cerr << "live topology view: room " << room_px << " corridor " << corr_px << " free " << free_px << "\n";
  EXPECT_GT(room_px, 3000);
  EXPECT_GT(corr_px, 2000);
  EXPECT_GT(countColour(view, {220, 120, 40}, 0), 20);  // room nodes (labelColour(0)), drawn opaque
  EXPECT_GT(countColour(view, {0, 0, 230}, 0), 30);     // the best particle's path is still drawn on top
  EXPECT_FALSE(cv::imread(tmp / "shot.png", cv::IMREAD_COLOR).empty());
}

// A SLAM INI that turns the loop closure on reaches the run (through the option grid the GUI applies before each
// run), and the closures are drawn as they are found: magenta lines where the robot comes back (Intel's first 1500
// scans, 8 particles, seed 1: 2 closures). --particle-map shows the map before the optimisation.
TEST(GuiSmoke, LoopClosuresAreDrawnAndTheMapBeforeOptimisationCanBeShown) {
  guitest::TempDir tmp;
  std::ofstream(tmp / "lc.ini") << "[slam]\nparticles = 8\nseed = 1\nthreads = 2\n[loop_closure]\nenabled = true\n";
  for (const std::string map : {"optimised", "particle"}) {
    const std::string view = tmp / (map + ".png");
    const int rc = runGui("--ini " + (tmp / "lc.ini") + " --max-scans 1500 --run-to-end --size 1100x800" +
                              (map == "particle" ? " --particle-map" : "") + " --export-view " + view +
                              " --quit " GRIDTOPO_DATA_DIR "/slam/intel.clf.gz",
                          tmp / "log.txt");
    ASSERT_EQ(rc, 0) << slurp(tmp / "log.txt");
    EXPECT_NE(slurp(tmp / "log.txt").find("1500 scans"), std::string::npos) << slurp(tmp / "log.txt");
  }
  const cv::Mat after = cv::imread(tmp / "optimised.png", cv::IMREAD_COLOR);
  const cv::Mat before = cv::imread(tmp / "particle.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(after.empty());
  ASSERT_FALSE(before.empty());
  const int closure_px = countColour(after, {255, 0, 255}, 0);  // session::kClosureColour
  std::cerr << "closure pixels " << closure_px << "\n";
  EXPECT_GT(closure_px, 30);
  EXPECT_GT(countColour(before, {255, 0, 255}, 0), 30);
  // Same run, same layers: only the map under them differs.
  ASSERT_EQ(after.size(), before.size());
  cv::Mat diff;
  cv::absdiff(after, before, diff);
  EXPECT_GT(cv::countNonZero(diff.reshape(1)), 100) << "the optimised map should differ from the best particle's";
}

TEST(GuiSmoke, TopologyViewAndAClickedCellShowItsLabel) {
  guitest::TempDir tmp;
  cv::imwrite(tmp / "plan.png", guitest::floorPlan());
  guitest::handMadeModel().save(tmp / "model.yml");
  struct Click {
    int col, row;
    const char* label;
  };
  for (const Click& c : {Click{25, 25, "label: room"}, Click{60, 96, "label: corridor"}}) {
    const std::string shot = tmp / ("topo_" + std::to_string(c.col) + ".png");
    const int rc = runGui("--model " + (tmp / "model.yml") + " --resolution 0.05 --run-topology --view topology"
                              " --size 1000x700 --click-cell " + std::to_string(c.col) + "," + std::to_string(c.row) +
                              " --inspector-out " + (tmp / "insp.txt") + " --screenshot " + shot + " --quit " +
                              (tmp / "plan.png"),
                          tmp / "log.txt");
    ASSERT_EQ(rc, 0) << slurp(tmp / "log.txt");
    const std::string insp = slurp(tmp / "insp.txt");
    EXPECT_NE(insp.find("cell (col " + std::to_string(c.col) + ", row " + std::to_string(c.row) + ")"), std::string::npos)
        << insp;
    EXPECT_NE(insp.find(c.label), std::string::npos) << insp;
    EXPECT_NE(insp.find("after relaxation"), std::string::npos) << insp;
    EXPECT_NE(insp.find("min_chord"), std::string::npos) << insp;
    const cv::Mat img = cv::imread(shot, cv::IMREAD_COLOR);
    ASSERT_FALSE(img.empty());
    // Room overlay (blue dominant) and corridor overlay (green dominant) both visible.
    const int room_px = countIf(img, [](const cv::Vec3b& v) { return v[0] > v[1] + 40 && v[0] > v[2] + 60; });
    const int corr_px = countIf(img, [](const cv::Vec3b& v) { return v[1] > v[0] + 40 && v[1] > v[2] + 40; });
    EXPECT_GT(room_px, 5000);
    EXPECT_GT(corr_px, 2000);
  }
}

TEST(GuiSmoke, TopologyOfALabelledFloorPlanWithTheShippedModel) {
  const std::string model = GRIDTOPO_DATA_DIR "/models/places_model.yml";
  if (!std::filesystem::exists(model)) GTEST_SKIP() << "no shipped model " << model;
  guitest::TempDir tmp;
  // lab_intel (763 x 708 cells), a cell deep inside a room of the labelled map training_intel.png.
  const cv::Mat truth = cv::imread(GRIDTOPO_DATA_DIR "/places/labelled/training_intel.png", cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(truth.at<unsigned char>(180, 330), 77);
  const int rc = runGui("--model " + model + " --resolution 0.05 --run-topology --view topology --size 1300x1000"
                        " --click-cell 330,180 --inspector-out " + (tmp / "insp.txt") + " --screenshot " +
                            (tmp / "shot.png") + " --quit " GRIDTOPO_DATA_DIR "/places/maps/lab_intel.png",
                        tmp / "log.txt");
  ASSERT_EQ(rc, 0) << slurp(tmp / "log.txt");
  const std::string insp = slurp(tmp / "insp.txt");
  EXPECT_NE(insp.find("cell (col 330, row 180)"), std::string::npos) << insp;
  EXPECT_NE(insp.find("label: room"), std::string::npos) << insp;
  const cv::Mat img = cv::imread(tmp / "shot.png", cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_GT(countIf(img, [](const cv::Vec3b& v) { return v[0] > v[1] + 40 && v[0] > v[2] + 60; }), 20000);
  EXPECT_GT(countIf(img, [](const cv::Vec3b& v) { return v[1] > v[0] + 40 && v[1] > v[2] + 40; }), 5000);
}

// The option grids' description boxes (wxPropertyGridManager, wxPG_DESCRIPTION) are laid out without asking GTK for
// a negative width (wx 3.2 did, once per grid, at their first size event; apps/gui/option_grid.cpp).
TEST(GuiSmoke, StartsWithoutGtkSizeRequestCriticals) {
  guitest::TempDir tmp;
  const int rc = runGui("--size 1280x860 --show-options --screenshot " + (tmp / "options.png") +
                            " --quit " GRIDTOPO_DATA_DIR "/slam/intel.clf.gz",
                        tmp / "log.txt");
  const std::string log = slurp(tmp / "log.txt");
  ASSERT_EQ(rc, 0) << log;
  EXPECT_EQ(log.find("gtk_widget_set_size_request"), std::string::npos) << log;
  EXPECT_FALSE(cv::imread(tmp / "options.png", cv::IMREAD_COLOR).empty());
}

TEST(GuiSmoke, BadFileExitsNonZeroWithFileAndLine) {
  guitest::TempDir tmp;
  std::ofstream(tmp / "bad.clf") << "# comment\nODOM 0 0 0 0 0 0 1.0 h 1.0\nFLASER 3 1.0 x 1.0 0 0 0 0 0 0 2 h 2\n";
  const int rc = runGui("--quit " + (tmp / "bad.clf"), tmp / "log.txt");
  EXPECT_EQ(rc, 1);
  EXPECT_NE(slurp(tmp / "log.txt").find("bad.clf:3"), std::string::npos) << slurp(tmp / "log.txt");
}

TEST(GuiSmoke, BadUsageExitsTwoAndBadValueOneBeforeAnyWindow) {
  // The app shell of every gridtopo app (core/app_shell.h): usage errors 2, bad values 1, --help 0.
  guitest::TempDir tmp;
  EXPECT_EQ(runGui("--max-scans many --quit", tmp / "usage.txt"), 2) << slurp(tmp / "usage.txt");
  EXPECT_NE(slurp(tmp / "usage.txt").find("gridtopo-gui: usage:"), std::string::npos) << slurp(tmp / "usage.txt");
  EXPECT_EQ(runGui("--view sideways --quit", tmp / "value.txt"), 1) << slurp(tmp / "value.txt");
  EXPECT_NE(slurp(tmp / "value.txt").find("gridtopo-gui: error: --view"), std::string::npos) << slurp(tmp / "value.txt");
  EXPECT_EQ(runGui("--help", tmp / "help.txt"), 0) << slurp(tmp / "help.txt");
  EXPECT_NE(slurp(tmp / "help.txt").find("--live-topology"), std::string::npos);
  // An unknown option is not a file to open.
  EXPECT_EQ(runGui("--no-such-option --quit", tmp / "unknown.txt"), 2) << slurp(tmp / "unknown.txt");
  EXPECT_NE(slurp(tmp / "unknown.txt").find("gridtopo-gui: usage: --no-such-option: unknown argument"),
            std::string::npos)
      << slurp(tmp / "unknown.txt");
  // Without a display: a clear error and exit 1, not GTK's.
  const std::string no_display = "env -u DISPLAY -u WAYLAND_DISPLAY " + kGui + " --quit > " +
                                 (tmp / "nodisplay.txt") + " 2>&1";
  const int rc = std::system(no_display.c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 1) << slurp(tmp / "nodisplay.txt");
  EXPECT_NE(slurp(tmp / "nodisplay.txt").find("gridtopo-gui: error: no display"), std::string::npos)
      << slurp(tmp / "nodisplay.txt");
}
