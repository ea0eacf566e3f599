// The beam geometry checked against real data with MRPT's own map building: half of the Intel scans inserted
// into an MRPT occupancy grid at the poses GMapping's authors corrected (intel.gfs.log.gz), the other half's
// beam end points land on its walls most often with our conversion; with a wrong geometry (a 180 deg aperture
// for 180 beams, or symmetric beams without the centre-yaw rotation, or all beams turned) they miss more.
#include <gtest/gtest.h>

#include "common/scratch.h"
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "gridtopo/io/carmen_log.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/io/scan_conversion.h"

using namespace gridtopo;
using namespace gridtopo::io;

namespace {
enum class Geometry { Ours, NoCentreYaw, Aperture180 };

mrpt::obs::CObservation2DRangeScan::Ptr convert(const LaserScan& s, Geometry geometry, double extra_yaw) {
  auto obs = toMrptScan(s);
  obs->sensorPose.setYawPitchRoll(obs->sensorPose.yaw() + extra_yaw, 0, 0);
  if (geometry != Geometry::Ours)  // symmetric beams about the laser's x axis, no centre-yaw rotation
    obs->sensorPose = mrpt::poses::CPose3D(s.sensor_pose.x, s.sensor_pose.y, 0, s.sensor_pose.phi + extra_yaw, 0, 0);
  if (geometry == Geometry::Aperture180) obs->aperture = static_cast<float>(M_PI);
  return obs;
}

// Builds an MRPT grid from the even scans, then returns the fraction of the odd scans' valid beam end points
// (closer than 10 m) that land exactly on a cell the even scans made occupied (p_free < 0.4). `extra_yaw`
// turns every scan on the robot.
double hitRate(const std::vector<ScanRecord>& scans, Geometry geometry, double extra_yaw = 0.0) {
  mrpt::maps::COccupancyGridMap2D grid(-40, 40, -40, 40, 0.05f);
  grid.insertionOptions.maxDistanceInsertion = 15.0f;
  for (std::size_t i = 0; i < scans.size(); i += 2) {
    const auto& r = scans[i];
    grid.insertObservation(*convert(r.scan, geometry, extra_yaw),
                           mrpt::poses::CPose3D(r.odometry.x, r.odometry.y, 0, r.odometry.phi, 0, 0));
  }
  std::size_t hits = 0, total = 0;
  for (std::size_t i = 1; i < scans.size(); i += 2) {
    const auto& r = scans[i];
    const auto obs = convert(r.scan, geometry, extra_yaw);
    const auto back = fromMrptScan(*obs);  // the beams as MRPT sees them
    for (std::size_t k = 0; k < back.size(); ++k) {
      if (!back.valid[k] || back.ranges[k] > 10.0f) continue;
      const auto p = beamEndpointInRobotFrame(back, k);
      const double c = std::cos(r.odometry.phi), s = std::sin(r.odometry.phi);
      const double x = r.odometry.x + c * p.x - s * p.y, y = r.odometry.y + s * p.x + c * p.y;
      const int cx = grid.x2idx(x), cy = grid.y2idx(y);
      bool hit = false;
      for (int dy = -0; dy <= 0 && !hit; ++dy)
        for (int dx = -0; dx <= 0 && !hit; ++dx) hit = grid.getCell(cx + dx, cy + dy) < 0.4f;
      hits += hit;
      ++total;
    }
  }
  return static_cast<double>(hits) / static_cast<double>(total);
}
}  // namespace

TEST(ScanGeometryOnRealData, CorrectedIntelScansAgreeBestWithOurGeometry) {
  const auto log = readCarmenLog(std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.gfs.log.gz");
  ASSERT_EQ(log.scans.size(), 910u);
  const double ours = hitRate(log.scans, Geometry::Ours);
  const double no_yaw = hitRate(log.scans, Geometry::NoCentreYaw);
  const double ap180 = hitRate(log.scans, Geometry::Aperture180);
  std::printf("hit rate: ours %.4f, without centre yaw %.4f, aperture 180 deg %.4f\n", ours, no_yaw, ap180);
  EXPECT_GT(ours, no_yaw + 0.01);
  EXPECT_GT(ours, ap180 + 0.01);
  // Turning all beams by a fraction of a degree either way only makes things worse: the data agree with the
  // -90 .. +89 deg geometry, not with a shifted one.
  for (const double deg : {-1.0, -0.5, -0.25, 0.25, 0.5, 1.0}) {
    const double r = hitRate(log.scans, Geometry::Ours, deg * M_PI / 180.0);
    std::printf("hit rate with %+.2f deg: %.4f\n", deg, r);
    EXPECT_LT(r, ours) << deg;
  }
}

TEST(ScanGeometryOnRealData, MapOfTheCorrectedIntelScans) {
  // All 910 corrected scans in one MRPT grid, written as PNG for a look (doc/img/intel_gfs_map.png).
  const auto log = readCarmenLog(std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.gfs.log.gz");
  mrpt::maps::COccupancyGridMap2D grid(-20, 20, -30, 20, 0.05f);
  grid.insertionOptions.maxDistanceInsertion = 15.0f;
  for (const auto& r : log.scans)
    grid.insertObservation(*toMrptScan(r.scan),
                           mrpt::poses::CPose3D(r.odometry.x, r.odometry.y, 0, r.odometry.phi, 0, 0));
  const std::string png = (gridtopo::test::scratchPath("intel_gfs_map.png")).string();
  writeMapPng(grid, png);
  const auto back = readGridMap(png, MapReadOptions{0.05, -20.0, -30.0});
  EXPECT_EQ(back->getSizeX(), 800u);
  EXPECT_EQ(back->getSizeY(), 1000u);
  std::size_t occupied = 0, free = 0;
  for (unsigned y = 0; y < grid.getSizeY(); ++y)
    for (unsigned x = 0; x < grid.getSizeX(); ++x) {
      occupied += grid.getCell(x, y) < 0.3f;
      free += grid.getCell(x, y) > 0.7f;
    }
  std::printf("wrote %s: %zu occupied, %zu free cells\n", png.c_str(), occupied, free);
  // Measured with MRPT 2.5.8 (default insertion options, 15 m): 201462 free, 16767 occupied cells.
  EXPECT_NEAR(static_cast<double>(free), 201462.0, 2000.0);
  EXPECT_NEAR(static_cast<double>(occupied), 16767.0, 200.0);
}
