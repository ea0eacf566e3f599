#pragma once
// A small synthetic scan log for fast tests: a robot driving around a rectangular 12 m x 6 m room with an
// off-centre laser, ranges ray-cast exactly. It exercises the quirks of real logs: scans at -90..+89 deg
// (180 beams), interleaved start angles, a laser max range shorter than the room's diagonal (no-return
// readings), timestamps that step backwards once, and Unix timestamps with microseconds.
#include <cmath>
#include <limits>
#include <vector>

#include "gridtopo/core/scan_record.h"

namespace gridtopo::test {

struct SyntheticOptions {
  std::size_t scans = 40;
  std::size_t beams = 180;
  double start_deg = -90.0;
  double increment_deg = 1.0;
  bool interleave = true;  ///< odd scans start half an increment later
  double max_range = 7.0;
  mrpt::math::TPose2D mount{0.12, -0.03, 0.0};
};

/// Distance from (x, y) along angle a to the walls of the box [0, 12] x [0, 6].
inline double rayToBox(double x, double y, double a) {
  const double W = 12.0, H = 6.0;
  const double c = std::cos(a), s = std::sin(a);
  double t = std::numeric_limits<double>::infinity();
  if (c > 1e-12) t = std::min(t, (W - x) / c);
  if (c < -1e-12) t = std::min(t, -x / c);
  if (s > 1e-12) t = std::min(t, (H - y) / s);
  if (s < -1e-12) t = std::min(t, -y / s);
  return t;
}

inline std::vector<gridtopo::ScanRecord> syntheticRecords(const SyntheticOptions& o = {}) {
  std::vector<gridtopo::ScanRecord> out;
  const double deg = M_PI / 180.0;
  for (std::size_t i = 0; i < o.scans; ++i) {
    gridtopo::ScanRecord r;
    const double u = static_cast<double>(i) / static_cast<double>(o.scans);
    // An ellipse inside the room, heading along the tangent.
    const double ang = 2.0 * M_PI * u;
    r.odometry = {6.0 + 3.5 * std::cos(ang), 3.0 + 1.5 * std::sin(ang),
                  std::atan2(1.5 * std::cos(ang), -3.5 * std::sin(ang))};
    r.has_odometry = true;
    r.source_index = i;
    gridtopo::LaserScan& s = r.scan;
    // Microsecond Unix timestamps, 0.2 s apart; scan 7 is logged 0.05 s before scan 6.
    s.timestamp = 1002560357.218569 + 0.2 * static_cast<double>(i) - (i == 7 ? 0.25 : 0.0);
    s.timestamp = std::round(s.timestamp * 1e6) / 1e6;
    s.start_angle = (o.start_deg + (o.interleave && (i % 2) ? 0.5 * o.increment_deg : 0.0)) * deg;
    s.angle_increment = o.increment_deg * deg;
    s.max_range = o.max_range;
    s.sensor_pose = o.mount;
    // The laser's pose in the room.
    const auto& p = r.odometry;
    const double lx = p.x + std::cos(p.phi) * o.mount.x - std::sin(p.phi) * o.mount.y;
    const double ly = p.y + std::sin(p.phi) * o.mount.x + std::cos(p.phi) * o.mount.y;
    for (std::size_t k = 0; k < o.beams; ++k) {
      const double d = rayToBox(lx, ly, p.phi + o.mount.phi + s.beamAngle(k));
      // Centimetre resolution like CARMEN; beyond max range the laser reports max range + 1 m.
      float range =
          d >= o.max_range ? static_cast<float>(o.max_range + 1.0) : static_cast<float>(std::round(d * 100.0) / 100.0);
      s.ranges.push_back(range);
      s.valid.push_back(d < o.max_range ? 1 : 0);
    }
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace gridtopo::test
