#include "gridtopo/io/scan_conversion.h"

#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace gridtopo::io {
namespace {

constexpr double kTicksPerSecond = 1e7;  // mrpt::Clock counts 100 ns ticks

// Ticks of mrpt::Clock at Unix time 0 (MRPT counts from 1601-01-01, like Windows FILETIME).
mrpt::Clock::rep unixEpochTicks() {
  static const mrpt::Clock::rep ticks = mrpt::Clock::fromDouble(0.0).time_since_epoch().count();
  return ticks;
}

// The increment recovered from MRPT's float aperture: the nearest whole number of 1e-4 deg, else of 1e-7 deg,
// if writing that value gives back the same float aperture; else the float-precision value.
double recoverIncrement(float aperture, std::size_t n) {
  const double steps = static_cast<double>(n - 1);
  const double raw = static_cast<double>(aperture) / steps;
  const double deg = raw * 180.0 / M_PI;
  for (const double per_degree : {1e4, 1e7}) {
    const double cand_deg = std::round(deg * per_degree) / per_degree;
    const double cand = cand_deg * (M_PI / 180.0);
    if (static_cast<float>(steps * cand) == aperture) return cand;
  }
  return raw;
}

// What toMrptScan refuses in a scan, or null.
const char* whyMrptCannotHold(const LaserScan& scan) {
  const std::size_t n = scan.ranges.size();
  if (n < 2) return "a scan needs at least 2 beams to be written as an MRPT scan";
  if (scan.valid.size() != n) return "scan: ranges and validity flags differ in size";
  if (!std::isfinite(scan.angle_increment) || scan.angle_increment == 0.0 || !std::isfinite(scan.start_angle))
    return "scan: the angle increment must be finite and non-zero";
  if (!std::isfinite(scan.sensor_pose.x) || !std::isfinite(scan.sensor_pose.y) || !std::isfinite(scan.sensor_pose.phi))
    return "scan: the laser's mounting pose must be finite";
  if (!std::isfinite(scan.timestamp)) return "scan: the timestamp must be finite";
  if (!(scan.max_range > 0.0) || !std::isfinite(scan.max_range))
    return "scan: max range must be a positive finite number";
  return nullptr;
}

}  // namespace

mrpt::Clock::time_point toMrptTime(double seconds) {
  if (!std::isfinite(seconds)) throw std::invalid_argument("timestamp is not a finite number");
  // Split whole seconds (exact in ticks) from the fraction so the rounding happens at the tick, not at the
  // ~1e-7 s resolution of a double holding a Unix time.
  const double whole = std::floor(seconds);
  const double frac = seconds - whole;  // exact (Sterbenz)
  const auto ticks = static_cast<mrpt::Clock::rep>(whole) * static_cast<mrpt::Clock::rep>(kTicksPerSecond) +
                     static_cast<mrpt::Clock::rep>(std::llround(frac * kTicksPerSecond));
  return mrpt::Clock::time_point(mrpt::Clock::duration(ticks + unixEpochTicks()));
}

double fromMrptTime(mrpt::Clock::time_point t) {
  const mrpt::Clock::rep ticks = t.time_since_epoch().count() - unixEpochTicks();
  // Whole seconds and remaining ticks separately: exact for any 100 ns multiple representable as a double.
  const mrpt::Clock::rep per_s = static_cast<mrpt::Clock::rep>(kTicksPerSecond);
  mrpt::Clock::rep whole = ticks / per_s, rest = ticks % per_s;
  if (rest < 0) {
    rest += per_s;
    whole -= 1;
  }
  // (whole * 1e7 + rest) / 1e7 as one correctly rounded division when it fits a double exactly.
  if (std::llabs(ticks) < (1LL << 53)) return static_cast<double>(ticks) / kTicksPerSecond;
  return static_cast<double>(whole) + static_cast<double>(rest) / kTicksPerSecond;
}

mrpt::obs::CObservation2DRangeScan::Ptr toMrptScan(const LaserScan& scan, const ScanConversionOptions& options) {
  if (const char* why = whyMrptCannotHold(scan)) throw std::invalid_argument(why);
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
  const double inc = recoverIncrement(obs.aperture, n);
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

void useMrptScanGeometry(LaserScan& scan) {
  if (whyMrptCannotHold(scan)) return;
  // The round trip itself: whatever MRPT does to the pose's yaw or the increment, it is done here too.
  const LaserScan back = fromMrptScan(*toMrptScan(scan));
  scan.timestamp = back.timestamp;
  scan.max_range = back.max_range;
  scan.sensor_pose = back.sensor_pose;
  scan.start_angle = back.start_angle;
  scan.angle_increment = back.angle_increment;
}

mrpt::math::TPoint2D beamEndpointInRobotFrame(const LaserScan& scan, std::size_t k) {
  const double a = scan.sensor_pose.phi + scan.beamAngle(k);
  const double r = scan.ranges[k];
  return {scan.sensor_pose.x + r * std::cos(a), scan.sensor_pose.y + r * std::sin(a)};
}

}  // namespace gridtopo::io
