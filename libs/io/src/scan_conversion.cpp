#include "gridtopo/io/scan_conversion.h"

#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace gridtopo::io {

mrpt::obs::CObservation2DRangeScan::Ptr toMrptScan(const LaserScan& scan, const ScanConversionOptions& options) {
  if (const char* why = whyMrptScanCannotHold(scan)) throw std::invalid_argument(why);
  const std::size_t n = scan.ranges.size();

  auto obs = mrpt::obs::CObservation2DRangeScan::Create();
  obs->sensorLabel = options.sensor_label;
  obs->timestamp = toMrptTime(scan.timestamp);
  const double span = static_cast<double>(n - 1) * scan.angle_increment;  // signed, end - start
  obs->aperture = static_cast<float>(std::abs(span));
  obs->rightToLeft = scan.angle_increment > 0.0;
  obs->maxRange = static_cast<float>(scan.max_range);
  obs->stdError = options.std_error;
  const double centre = scan.start_angle + 0.5 * span;
  obs->sensorPose =
      mrpt::poses::CPose3D(scan.sensor_pose.x, scan.sensor_pose.y, 0.0, scan.sensor_pose.phi + centre, 0.0, 0.0);
  obs->resizeScan(n);
  for (std::size_t k = 0; k < n; ++k) {
    float r = scan.ranges[k];
    bool valid = scan.valid[k] != 0;
    if (std::isnan(r) || r < 0.0f) {
      r = 0.0f;
      valid = false;
    } else if (std::isinf(r)) {
      r = static_cast<float>(scan.max_range);
      valid = false;
    }
    obs->setScanRange(k, r);
    obs->setScanRangeValidity(k, valid);
  }
  return obs;
}

LaserScan fromMrptScan(const mrpt::obs::CObservation2DRangeScan& obs) {
  const std::size_t n = obs.getScanSize();
  if (n < 2) throw std::invalid_argument("MRPT scan with fewer than 2 beams");
  LaserScan s;
  s.timestamp = fromMrptTime(obs.timestamp);
  s.max_range = static_cast<double>(obs.maxRange);
  const double inc = incrementOfMrptAperture(obs.aperture, n);
  const double half = 0.5 * static_cast<double>(n - 1) * inc;
  // MRPT beam k: -aperture/2 + k * step (rightToLeft) or +aperture/2 - k * step.
  double start = obs.rightToLeft ? -half : half;
  double step = obs.rightToLeft ? inc : -inc;
  // Planar heading of the laser's x axis; a laser whose z axis points down (upside down) mirrors its beams.
  const auto& R = obs.sensorPose.getRotationMatrix();
  const bool mirrored = R(0, 0) * R(1, 1) - R(1, 0) * R(0, 1) < 0.0;
  if (mirrored) {
    start = -start;
    step = -step;
  }
  s.sensor_pose = {obs.sensorPose.x(), obs.sensorPose.y(), std::atan2(R(1, 0), R(0, 0))};
  // A pure-yaw pose gives back its yaw exactly (atan2 of its own sin / cos up to rounding): use it directly.
  if (!mirrored && std::abs(obs.sensorPose.pitch()) < 1e-12 && std::abs(obs.sensorPose.roll()) < 1e-12)
    s.sensor_pose.phi = obs.sensorPose.yaw();
  s.start_angle = start;
  s.angle_increment = step;
  s.ranges.resize(n);
  s.valid.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    s.ranges[k] = obs.getScanRange(k);
    s.valid[k] = obs.getScanRangeValidity(k) ? 1 : 0;
  }
  return s;
}

mrpt::math::TPoint2D beamEndpointInRobotFrame(const LaserScan& scan, std::size_t k) {
  const double a = scan.sensor_pose.phi + scan.beamAngle(k);
  const double r = scan.ranges[k];
  return {scan.sensor_pose.x + r * std::cos(a), scan.sensor_pose.y + r * std::sin(a)};
}

}  // namespace gridtopo::io
