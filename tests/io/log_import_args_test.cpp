// gridtopo-import's reader and writer flags as LogImportOptions (io/log_import_args.h).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "gridtopo/io/log_import_args.h"

using namespace gridtopo;

namespace {
io::LogImportOptions parsed(std::vector<std::string> args) {
  TCLAP::CmdLine cmd("test", ' ', "0");
  io::LogImportArgs import_args(cmd);
  cmd.setExceptionHandling(false);
  args.insert(args.begin(), "test");
  cmd.parse(args);
  return import_args.options();
}
}  // namespace

TEST(LogImportArgs, DefaultsAreTheOptionsDefaults) {
  const io::LogImportOptions o = parsed({});
  const io::LogImportOptions d;
  EXPECT_EQ(o.layout, d.layout);
  EXPECT_EQ(o.odometry, d.odometry);
  EXPECT_EQ(o.motion_model, d.motion_model);
  EXPECT_EQ(o.compression, d.compression);
  EXPECT_EQ(o.gz, d.gz);
  EXPECT_EQ(o.sensor_label, d.sensor_label);
  EXPECT_EQ(o.max_range, d.max_range);
  EXPECT_EQ(o.skip_bad_lines, d.skip_bad_lines);
  EXPECT_EQ(o.rear_laser, d.rear_laser);
}

TEST(LogImportArgs, EveryFlagReachesItsOption) {
  const io::LogImportOptions o =
      parsed({"-l", "obs", "--odometry", "odom", "--motion-model", "thrun", "--compression", "6", "--gz",
              "--sensor-label", "FRONT", "--max-range", "20.5", "--skip-bad-lines", "--rear-laser"});
  EXPECT_EQ(o.layout, "obs");
  EXPECT_EQ(o.odometry, "odom");
  EXPECT_EQ(o.motion_model, "thrun");
  EXPECT_EQ(o.compression, 6);
  EXPECT_TRUE(o.gz);
  EXPECT_EQ(o.sensor_label, "FRONT");
  EXPECT_EQ(o.max_range, 20.5);
  EXPECT_TRUE(o.skip_bad_lines);
  EXPECT_TRUE(o.rear_laser);
  // The words are checked where they become the reader's and the writer's options.
  EXPECT_THROW(io::rawlogWriteOptions(parsed({"-l", "both"})), std::invalid_argument);
}
