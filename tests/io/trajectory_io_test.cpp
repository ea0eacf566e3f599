#include <gtest/gtest.h>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>

#include "gridtopo/core/error.h"
#include "gridtopo/io/trajectory_io.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::io;

TEST(TrajectoryIo, RoundTripsExactly) {
  const fs::path p = gridtopo::test::scratchPath("traj_roundtrip.txt");
  std::vector<TimedPose> in = {{1002560357.218569, {0.1, -2.0000000000000004, 3.14159}},
                               {1002560356.9, {1e-9, 12.5, -0.7}}};  // timestamps may step backwards
  writeTrajectory(p.string(), in, {"produced by a test"});
  const auto out = readTrajectory(p.string());
  ASSERT_EQ(out.size(), in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ(out[i].timestamp, in[i].timestamp);
    EXPECT_EQ(out[i].pose.x, in[i].pose.x);
    EXPECT_EQ(out[i].pose.y, in[i].pose.y);
    EXPECT_EQ(out[i].pose.phi, in[i].pose.phi);
  }
}

TEST(TrajectoryIo, MalformedLineNamesLineAndField) {
  const fs::path p = gridtopo::test::scratchPath("traj_bad.txt");
  std::ofstream(p) << "# header\n1 2 3 4\n5 6 nan 8\n";
  try {
    readTrajectory(p.string());
    FAIL();
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.line(), 3u);
    EXPECT_EQ(e.field(), "y");
  }
  std::ofstream(p) << "1 2 3\n";
  EXPECT_THROW(readTrajectory(p.string()), gridtopo::InputError);
  std::ofstream(p) << "1 2 3 4 5\n";
  EXPECT_THROW(readTrajectory(p.string()), gridtopo::InputError);
  EXPECT_THROW(readTrajectory("/nonexistent/traj.txt"), gridtopo::InputError);
}
