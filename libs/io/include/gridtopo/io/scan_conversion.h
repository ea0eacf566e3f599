#pragma once
// Conversion between gridtopo's LaserScan and MRPT's CObservation2DRangeScan, with the right geometry.
//
// MRPT describes a planar scan by its field of view ("aperture"), its beam count N and its direction: beam k
// points at -aperture/2 + k * aperture/(N-1) (rightToLeft) or +aperture/2 - k * aperture/(N-1), i.e. the beams
// are always symmetric about the laser's x axis. A CARMEN 180-beam scan (-90 deg .. +89 deg, 1 deg apart) is
// not: it is written with aperture = (N-1)*|increment| = 179 deg and the sensor pose yawed by the centre angle
// (start + end)/2 = -0.5 deg, so every beam keeps its exact direction in the robot frame. The same rotation
// carries interleaved start angles (e.g. -90 deg / -89.5 deg alternating) and left-to-right scans (negative
// increment -> rightToLeft = false).
#include <mrpt/core/Clock.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>

#include <cstddef>
#include <string>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/scan_geometry.h"  // toMrptTime, fromMrptTime, useMrptScanGeometry

namespace gridtopo::io {

struct ScanConversionOptions {
  std::string sensor_label = "LASER";  ///< CObservation::sensorLabel of the scans written
  float std_error = 0.01f;             ///< CObservation2DRangeScan::stdError (metres)
};

/// LaserScan (laser frame + mounting pose) -> CObservation2DRangeScan, timestamp toMrptTime(scan.timestamp).
/// Every reading is kept in the range vector: no-return readings
/// (range >= max_range) with their logged value and valid = false; non-finite or negative readings become
/// max_range (+inf) or 0 (NaN, negative) with valid = false. Throws std::invalid_argument for fewer than 2
/// beams, a zero or non-finite increment, a non-finite pose / timestamp / max range, or inconsistent sizes.
mrpt::obs::CObservation2DRangeScan::Ptr toMrptScan(const LaserScan& scan, const ScanConversionOptions& options = {});

/// CObservation2DRangeScan -> LaserScan: sensor_pose = (x, y, yaw) of the MRPT sensor pose, start_angle /
/// angle_increment from the aperture and direction (an upside-down laser, roll = 180 deg, flips the
/// direction), so the beams have the same directions in the robot frame. MRPT stores the aperture as a float;
/// the increment is recovered exactly when it is a whole number of 1e-4 or 1e-7 degrees (1 deg, 0.5 deg,
/// 0.25 deg, 360/1024 deg, ...) and otherwise to float precision (~1e-7 rad). Throws std::invalid_argument for
/// fewer than 2 beams.
LaserScan fromMrptScan(const mrpt::obs::CObservation2DRangeScan& obs);

/// End point of beam k in the robot frame (the scan's sensor_pose applied to range k along its beam).
mrpt::math::TPoint2D beamEndpointInRobotFrame(const LaserScan& scan, std::size_t k);

}  // namespace gridtopo::io
