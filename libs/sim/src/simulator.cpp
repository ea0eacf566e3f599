#include "gridtopo/sim/simulator.h"

#include <cmath>
#include <limits>
#include <random>

namespace gridtopo::sim {

void FloorPlan::addRectangle(double x0, double y0, double x1, double y1) {
  walls.push_back({x0, y0, x1, y0});
  walls.push_back({x1, y0, x1, y1});
  walls.push_back({x1, y1, x0, y1});
  walls.push_back({x0, y1, x0, y0});
}

FloorPlan FloorPlan::officeLoop() {
  FloorPlan p;
  p.addRectangle(0, 0, 20, 12);  // outer walls
  // Central block 4..16 x 4..8 split into three rooms with doors opening onto the corridor.
  const double dw = 0.9;  // door width
  // south wall of the block with a door in each room
  p.walls.push_back({4, 4, 5.5, 4});
  p.walls.push_back({5.5 + dw, 4, 9.5, 4});
  p.walls.push_back({9.5 + dw, 4, 13.5, 4});
  p.walls.push_back({13.5 + dw, 4, 16, 4});
  p.walls.push_back({16, 4, 16, 8});
  p.walls.push_back({16, 8, 4, 8});
  p.walls.push_back({4, 8, 4, 4});
  p.walls.push_back({8, 4, 8, 8});    // room dividers
  p.walls.push_back({12, 4, 12, 8});
  // Furniture / pillars along the corridor give features in the long straight parts.
  auto box = [&](double cx, double cy, double h) { p.addRectangle(cx - h, cy - h, cx + h, cy + h); };
  box(2, 2, 0.3);
  box(10, 1.2, 0.25);
  box(18, 10, 0.3);
  box(7, 10.8, 0.25);
  box(13, 10.9, 0.2);
  box(18.8, 3, 0.2);
  box(1.2, 9, 0.25);
  // Alcoves in the outer wall.
  p.walls.push_back({6, 12, 6, 11.5});
  p.walls.push_back({14, 0, 14, 0.6});
  return p;
}

double FloorPlan::rayCast(double x, double y, double a) const {
  const double dx = std::cos(a), dy = std::sin(a);
  double best = std::numeric_limits<double>::infinity();
  for (const auto& w : walls) {
    const double ex = w.x1 - w.x0, ey = w.y1 - w.y0;
    const double den = dx * ey - dy * ex;
    if (std::abs(den) < 1e-12) continue;
    const double wx = w.x0 - x, wy = w.y0 - y;
    const double t = (wx * ey - wy * ex) / den;  // along the ray
    const double s = (wx * dy - wy * dx) / den;  // along the wall
    if (t > 1e-9 && s >= 0.0 && s <= 1.0 && t < best) best = t;
  }
  return best;
}

std::vector<mrpt::math::TPose2D> officeLoopWaypoints(int laps) {
  std::vector<mrpt::math::TPose2D> w;
  w.push_back({2, 6, -M_PI / 2});
  for (int l = 0; l < laps; ++l) {
    w.push_back({2, 2.8, 0});
    w.push_back({17.5, 2.8, 0});
    w.push_back({17.5, 10, 0});
    w.push_back({2.5, 10, 0});
    w.push_back({2.5, 5.5, 0});
  }
  w.push_back({2.5, 2.8, 0});
  w.push_back({10, 2.8, 0});
  return w;
}

SimLog simulate(const FloorPlan& plan, const std::vector<mrpt::math::TPose2D>& waypoints, const SimOptions& o) {
  SimLog log;
  if (waypoints.empty()) return log;
  std::mt19937_64 gen(o.seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  mrpt::math::TPose2D truth = waypoints[0];
  mrpt::math::TPose2D odo = truth;
  double t = 1000.0;
  auto wrap = [](double a) { return std::atan2(std::sin(a), std::cos(a)); };
  auto record = [&] {
    io::ScanRecord r;
    r.has_odometry = true;
    r.odometry = odo;
    r.source_index = log.records.size();
    auto& s = r.scan;
    s.timestamp = t;
    s.start_angle = -o.fov / 2;
    s.angle_increment = o.fov / (o.beams - 1);
    s.max_range = o.max_range;
    s.sensor_pose = o.sensor_pose;
    const double c = std::cos(truth.phi), sn = std::sin(truth.phi);
    const double lx = truth.x + c * o.sensor_pose.x - sn * o.sensor_pose.y;
    const double ly = truth.y + sn * o.sensor_pose.x + c * o.sensor_pose.y;
    for (int k = 0; k < o.beams; ++k) {
      const double a = truth.phi + o.sensor_pose.phi + s.beamAngle(k);
      double r0 = plan.rayCast(lx, ly, a);
      if (r0 < o.max_range) {
        r0 += o.range_sigma * n01(gen);
        s.ranges.push_back(static_cast<float>(r0));
        s.valid.push_back(1);
      } else {
        s.ranges.push_back(static_cast<float>(o.max_range));
        s.valid.push_back(0);
      }
    }
    log.records.push_back(std::move(r));
    log.truth.push_back(truth);
  };
  // Applies a true increment (forward d, rotation dth) and the corresponding noisy odometry.
  auto move = [&](double d, double dth) {
    truth.x += d * std::cos(truth.phi);
    truth.y += d * std::sin(truth.phi);
    truth.phi = wrap(truth.phi + dth);
    const double nd = d + o.odo_sigma_xy * std::abs(d) * n01(gen);
    const double ny = o.odo_sigma_xy * std::abs(d) * n01(gen);
    const double nth = dth + o.odo_drift_theta * std::abs(d) +
                       o.odo_sigma_theta * (std::abs(d) + std::abs(dth)) * n01(gen);
    odo.x += nd * std::cos(odo.phi) - ny * std::sin(odo.phi);
    odo.y += nd * std::sin(odo.phi) + ny * std::cos(odo.phi);
    odo.phi = wrap(odo.phi + nth);
    t += (std::abs(d) + 0.5 * std::abs(dth)) / o.speed;
  };
  record();
  for (std::size_t w = 1; w < waypoints.size(); ++w) {
    const double gx = waypoints[w].x, gy = waypoints[w].y;
    const double dist = std::hypot(gx - truth.x, gy - truth.y);
    if (dist < 1e-9) continue;
    const double heading = std::atan2(gy - truth.y, gx - truth.x);
    double turn = wrap(heading - truth.phi);
    const int nturn = static_cast<int>(std::ceil(std::abs(turn) / o.scan_spacing));
    for (int i = 0; i < nturn; ++i) {
      move(0.0, turn / nturn);
      record();
    }
    const int nmove = static_cast<int>(std::ceil(dist / o.scan_spacing));
    for (int i = 0; i < nmove; ++i) {
      move(dist / nmove, 0.0);
      record();
    }
  }
  return log;
}

}  // namespace gridtopo::sim
