#include "gridtopo/io/scan_geometry.h"

#include <mrpt/math/wrap2pi.h>

#include <cmath>
#include <stdexcept>

namespace gridtopo::io {
namespace {

constexpr double kTicksPerSecond = 1e7;  // mrpt::Clock counts 100 ns ticks

// Ticks of mrpt::Clock at Unix time 0 (MRPT counts from 1601-01-01, like Windows FILETIME).
mrpt::Clock::rep unixEpochTicks() {
  static const mrpt::Clock::rep ticks = mrpt::Clock::fromDouble(0.0).time_since_epoch().count();
  return ticks;
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

const char* whyMrptScanCannotHold(const LaserScan& scan) {
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

double incrementOfMrptAperture(float aperture, std::size_t beams) {
  const double steps = static_cast<double>(beams - 1);
  const double raw = static_cast<double>(aperture) / steps;
  const double deg = raw * 180.0 / M_PI;
  for (const double per_degree : {1e4, 1e7}) {
    const double cand_deg = std::round(deg * per_degree) / per_degree;
    const double cand = cand_deg * (M_PI / 180.0);
    if (static_cast<float>(steps * cand) == aperture) return cand;
  }
  return raw;
}

void useMrptScanGeometry(LaserScan& scan) {
  if (whyMrptScanCannotHold(scan)) return;
  const std::size_t n = scan.ranges.size();
  // toMrptScan: the aperture a float, the direction from the increment's sign, the fan's centre into the yaw of a
  // CPose3D (which wraps it to (-pi, pi]); fromMrptScan: the increment recovered from the aperture, the beams
  // symmetric about the laser's x axis, the yaw of a pure-yaw pose read back as it was stored.
  const double span = static_cast<double>(n - 1) * scan.angle_increment;
  const float aperture = static_cast<float>(std::abs(span));
  const bool right_to_left = scan.angle_increment > 0.0;
  const double centre = scan.start_angle + 0.5 * span;
  const double inc = incrementOfMrptAperture(aperture, n);
  const double half = 0.5 * static_cast<double>(n - 1) * inc;
  scan.timestamp = fromMrptTime(toMrptTime(scan.timestamp));
  scan.max_range = static_cast<double>(static_cast<float>(scan.max_range));
  scan.sensor_pose.phi = mrpt::math::wrapToPi(scan.sensor_pose.phi + centre);
  scan.start_angle = right_to_left ? -half : half;
  scan.angle_increment = right_to_left ? inc : -inc;
}

}  // namespace gridtopo::io
