// A program linked like gridtopo-slam (libgridtopo_slam_core, io_core and core only) reads a CARMEN log and runs the
// filter with neither MRPT's maps and observations nor OpenCV's image codecs loaded (about 170 shared libraries and
// 60 MB resident); it loads libgridtopo_slam, and with it those, for the output set only, and libgridtopo_io for a
// rawlog. These tests run in one process each (ctest), so "not loaded yet" is this test's own doing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/run_app.h"
#include "common/scratch.h"
#include "gridtopo/core/lazy_library.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/slam/slam_result.h"
#include "gridtopo/slam/slam_run.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
bool mrptMapsOrCodecsLoaded() {
  return sharedLibraryLoaded("libmrpt-maps.so") || sharedLibraryLoaded("libmrpt-obs.so") ||
         sharedLibraryLoaded("libopencv_imgcodecs.so") || sharedLibraryLoaded("libgdal.so");
}
}  // namespace

TEST(LazyLibraries, TheFilterRunsOnACarmenLogWithoutMrptMapsAndLoadsThemForTheOutputs) {
  ASSERT_FALSE(mrptMapsOrCodecsLoaded());
  ASSERT_FALSE(sharedLibraryLoaded(gridtopoLibrarySoname("slam")));
  auto records = std::make_shared<std::vector<ScanRecord>>(
      io::readScanLog(std::string(GRIDTOPO_DATA_DIR) + "/slam/mit-csail.clf.gz"));
  ASSERT_GT(records->size(), 1000u);
  records->resize(400);
  slam::SlamOptions o;
  o.particles = 5;
  o.threads = 1;
  slam::SlamRun run(records, o);
  run.runToEnd();
  slam::SlamResult result = run.finishResult({"lazy test"});
  EXPECT_GT(result.scan_indices.size(), 10u);
  EXPECT_EQ(result.scan_indices.size(), result.scan_poses.size());
  EXPECT_EQ(result.trajectory.size(), 400u);
  EXPECT_FALSE(mrptMapsOrCodecsLoaded()) << "the filter loaded MRPT's maps or OpenCV's codecs";
  const std::size_t rss_before_kb = processMemory().rss_kb;

  const fs::path dir = test::scratch("lazy_outputs");
  slam::writeSlamResultLoadingExport(dir.string(), result);
  EXPECT_TRUE(sharedLibraryLoaded(gridtopoLibrarySoname("slam")));
  EXPECT_TRUE(sharedLibraryLoaded("libmrpt-maps.so"));
  for (const char* f : {"map.png", "map_trajectory.png", "map.pgm", "map.yaml", "map.gridmap.gz", "map.simplemap",
                        "trajectory.txt", "stats.txt", "options.ini"}) {
    ASSERT_TRUE(fs::exists(dir / f)) << f;
    EXPECT_GT(fs::file_size(dir / f), 0u) << f;
  }
  // What the libraries cost: tens of megabytes resident (60 MB on Debian 12), which the run above did without.
  const std::size_t rss_after_kb = processMemory().rss_kb;
  std::printf("resident before the outputs %zu kB, after %zu kB\n", rss_before_kb, rss_after_kb);
  EXPECT_GT(rss_after_kb, rss_before_kb + 20000);
}

TEST(LazyLibraries, ARawlogIsReadThroughTheMrptIoLibraryLoadedThenWithTheSameScans) {
  const std::string clf = std::string(GRIDTOPO_DATA_DIR) + "/slam/mit-csail.clf.gz";
  const fs::path rawlog = test::scratch("lazy_rawlog") / "csail.rawlog";
  const auto import = testing_app::runApp("gridtopo-import", "-q -l obs -i " + clf + " -o " + rawlog.string());
  ASSERT_EQ(import.status, 0) << import.output;

  const std::vector<ScanRecord> carmen = io::readScanLog(clf);
  EXPECT_FALSE(sharedLibraryLoaded(gridtopoLibrarySoname("io")));
  EXPECT_FALSE(mrptMapsOrCodecsLoaded());
  io::ScanLogInfo info;
  const std::vector<ScanRecord> raw = io::readScanLog(rawlog.string(), {}, info);
  EXPECT_TRUE(sharedLibraryLoaded(gridtopoLibrarySoname("io")));
  EXPECT_EQ(info.format, io::LogFormat::Rawlog);
  EXPECT_FALSE(info.rawlog_has_actions);
  ASSERT_EQ(raw.size(), carmen.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const LaserScan &a = carmen[i].scan, &b = raw[i].scan;
    // The CARMEN reader gives its scans MRPT's geometry without MRPT (useMrptScanGeometry): the same bits.
    differ += !(a.timestamp == b.timestamp && a.max_range == b.max_range && a.start_angle == b.start_angle &&
                a.angle_increment == b.angle_increment && a.sensor_pose.phi == b.sensor_pose.phi &&
                a.ranges == b.ranges && a.valid == b.valid);
  }
  EXPECT_EQ(differ, 0u);
}

TEST(LazyLibraries, AMissingLibraryOrFunctionIsNamed) {
  try {
    lazyLibrarySymbol("no_such_library", "gridtopo_nothing");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("libgridtopo_no_such_library.so"), std::string::npos) << e.what();
  }
  try {
    lazyLibrarySymbol("io", "gridtopo_io_no_such_function");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("gridtopo_io_no_such_function"), std::string::npos) << e.what();
  }
}
