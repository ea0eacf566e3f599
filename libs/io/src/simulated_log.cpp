#include "gridtopo/io/simulated_log.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace gridtopo::io {
namespace {

mrpt::math::TPose2D compose(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b) {
  const double c = std::cos(a.phi), s = std::sin(a.phi);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, std::remainder(a.phi + b.phi, 2.0 * M_PI)};
}

mrpt::math::TPose2D between(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b) {
  const double c = std::cos(a.phi), s = std::sin(a.phi);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, std::remainder(b.phi - a.phi, 2.0 * M_PI)};
}

}  // namespace

const std::vector<std::array<double, 4>>& simulatedWorld() {
  static const std::vector<std::array<double, 4>> walls = [] {
    std::vector<std::array<double, 4>> w = {
        {0, 0, 12, 0},        {12, 0, 12, 6},       {12, 6, 0, 6}, {0, 6, 0, 0},  // the room
        {5.0, 6.0, 5.0, 5.4}, {7.0, 0.0, 7.0, 0.5},                               // two short wall stubs
    };
    for (const double cx : {3.0, 9.0}) {  // two 0.6 m square pillars at (3, 3) and (9, 3)
      const double a = cx - 0.3, b = cx + 0.3, lo = 2.7, hi = 3.3;
      w.push_back({a, lo, b, lo});
      w.push_back({b, lo, b, hi});
      w.push_back({b, hi, a, hi});
      w.push_back({a, hi, a, lo});
    }
    return w;
  }();
  return walls;
}

double castRay(double x, double y, double angle) {
  const double dx = std::cos(angle), dy = std::sin(angle);
  double best = std::numeric_limits<double>::infinity();
  for (const auto& w : simulatedWorld()) {
    // Solve (x, y) + t (dx, dy) = (x1, y1) + u (x2 - x1, y2 - y1), t >= 0, u in [0, 1].
    const double ex = w[2] - w[0], ey = w[3] - w[1];
    const double den = dx * ey - dy * ex;
    if (std::abs(den) < 1e-15) continue;
    const double qx = w[0] - x, qy = w[1] - y;
    const double t = (qx * ey - qy * ex) / den;
    const double u = (qx * dy - qy * dx) / den;
    if (t >= 0.0 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
  }
  return best;
}

SimulatedLog simulateLog(const SimulationOptions& o) {
  if (o.scans < 2 || o.beams < 2) throw std::invalid_argument("simulation: need at least 2 scans and 2 beams");
  if (!(o.max_range > 0) || !(o.period > 0) || !(o.increment_deg != 0))
    throw std::invalid_argument("simulation: max range, period and increment must be positive / non-zero");
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double deg = M_PI / 180.0;

  SimulatedLog log;
  mrpt::math::TPose2D odo{0, 0, 0};
  for (std::size_t i = 0; i < o.scans; ++i) {
    // Ground truth: a counter-clockwise ellipse around both pillars, centre (6, 3), radii 4.5 m and 2 m,
    // starting at its bottom point heading +x; the last scan stops one step short of closing the loop.
    const double u = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(o.scans) - M_PI / 2.0;
    const mrpt::math::TPose2D gt{6.0 + 4.5 * std::cos(u), 3.0 + 2.0 * std::sin(u),
                                 std::atan2(2.0 * std::cos(u), -4.5 * std::sin(u))};
    const double t = o.start_time + o.period * static_cast<double>(i);
    log.ground_truth.push_back({t, gt});

    // Odometry: the true increment with noise proportional to the motion.
    if (i == 0) {
      odo = gt;
    } else {
      const auto inc = between(log.ground_truth[i - 1].pose, gt);
      const double dist = std::hypot(inc.x, inc.y);
      const mrpt::math::TPose2D noisy{
          inc.x + gauss(rng) * o.odometry_noise_xy * dist, inc.y + gauss(rng) * o.odometry_noise_xy * dist,
          inc.phi + gauss(rng) * (o.odometry_noise_phi * std::abs(inc.phi) + o.odometry_noise_drift * dist)};
      odo = compose(odo, noisy);
    }

    ScanRecord rec;
    rec.has_odometry = true;
    rec.odometry = odo;
    rec.source_index = i;
    LaserScan& s = rec.scan;
    s.timestamp = t;
    s.start_angle = (o.start_deg + (o.interleave && (i % 2) ? 0.5 * o.increment_deg : 0.0)) * deg;
    s.angle_increment = o.increment_deg * deg;
    s.max_range = o.max_range;
    s.sensor_pose = o.mount;
    const auto laser = compose(gt, o.mount);
    s.ranges.reserve(o.beams);
    s.valid.reserve(o.beams);
    for (std::size_t k = 0; k < o.beams; ++k) {
      const double d = castRay(laser.x, laser.y, laser.phi + s.beamAngle(k));
      const double noisy = d + gauss(rng) * o.range_noise;
      if (!(noisy < o.max_range)) {
        s.ranges.push_back(static_cast<float>(o.max_range + 1.0));
        s.valid.push_back(0);
      } else {
        s.ranges.push_back(static_cast<float>(std::round(std::max(noisy, 0.01) * 100.0) / 100.0));
        s.valid.push_back(1);
      }
    }
    log.scans.push_back(std::move(rec));
  }
  return log;
}

}  // namespace gridtopo::io
