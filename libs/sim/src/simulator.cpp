#include "gridtopo/sim/simulator.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

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

FloorPlan FloorPlan::straightCorridor(double length, double width) {
  FloorPlan p;
  p.walls.push_back({0, 0, length, 0});
  p.walls.push_back({0, width, length, width});
  return p;
}

FloorPlan FloorPlan::pillarRoom() {
  FloorPlan p;
  p.addRectangle(0, 0, 12, 6);
  p.walls.push_back({5.0, 6.0, 5.0, 5.4});  // two short wall stubs
  p.walls.push_back({7.0, 0.0, 7.0, 0.5});
  p.addRectangle(2.7, 2.7, 3.3, 3.3);  // two 0.6 m square pillars
  p.addRectangle(8.7, 2.7, 9.3, 3.3);
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

namespace {

double wrap(double a) { return std::remainder(a, 2.0 * M_PI); }

mrpt::math::TPose2D compose(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b) {
  const double c = std::cos(a.phi), s = std::sin(a.phi);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, wrap(a.phi + b.phi)};
}

/// b expressed in the frame of a.
mrpt::math::TPose2D between(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b) {
  const double c = std::cos(a.phi), s = std::sin(a.phi);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, wrap(b.phi - a.phi)};
}

}  // namespace

std::vector<TimedPose> SimLog::timedTruth() const {
  std::vector<TimedPose> out;
  out.reserve(truth.size());
  for (std::size_t i = 0; i < truth.size() && i < records.size(); ++i)
    out.push_back({records[i].scan.timestamp, truth[i]});
  return out;
}

SimLog simulatePath(const FloorPlan& plan, const std::vector<mrpt::math::TPose2D>& truth,
                    const std::vector<double>& times, const SimOptions& o) {
  return simulatePath([&plan](double x, double y, double a) { return plan.rayCast(x, y, a); }, truth, times, o);
}

SimLog simulatePath(const RayCaster& world, const std::vector<mrpt::math::TPose2D>& truth,
                    const std::vector<double>& times, const SimOptions& o) {
  if (truth.size() != times.size()) throw std::invalid_argument("simulation: one timestamp per pose is needed");
  if (o.beams < 2) throw std::invalid_argument("simulation: need at least 2 beams");
  if (!(o.max_range > 0) || !(o.fov > 0) || !(o.range_sigma >= 0) || !(o.range_quantum >= 0))
    throw std::invalid_argument("simulation: max range and field of view must be positive, noise not negative");
  if (!(o.dropout_probability >= 0 && o.dropout_probability < 1))
    throw std::invalid_argument("simulation: dropout probability must be in [0, 1)");
  std::mt19937_64 gen(o.seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const double increment = o.fov / (o.beams - 1);
  const float no_return = static_cast<float>(o.no_return_range > 0 ? o.no_return_range : o.max_range);

  SimLog log;
  log.records.reserve(truth.size());
  mrpt::math::TPose2D odo{};
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const auto& gt = truth[i];
    // Odometry: the true increment with noise proportional to the motion, plus the heading bias.
    if (i == 0) {
      odo = gt;
    } else {
      const auto inc = between(truth[i - 1], gt);
      const double d = std::hypot(inc.x, inc.y);
      const double nx = o.odo_sigma_xy * d * n01(gen);
      const double ny = o.odo_sigma_xy * d * n01(gen);
      const double nth = o.odo_drift_theta * d +
                         (o.odo_sigma_theta * std::abs(inc.phi) + o.odo_sigma_theta_per_m * d) * n01(gen);
      odo = compose(odo, {inc.x + nx, inc.y + ny, inc.phi + nth});
    }

    ScanRecord r;
    r.has_odometry = true;
    r.odometry = odo;
    r.source_index = i;
    auto& s = r.scan;
    s.timestamp = times[i];
    s.start_angle = -o.fov / 2 + (o.interleave && (i % 2) ? 0.5 * increment : 0.0);
    s.angle_increment = increment;
    s.max_range = o.max_range;
    s.sensor_pose = o.sensor_pose;
    s.ranges.reserve(o.beams);
    s.valid.reserve(o.beams);
    const auto laser = compose(gt, o.sensor_pose);
    for (int k = 0; k < o.beams; ++k) {
      const double noisy = world(laser.x, laser.y, laser.phi + s.beamAngle(k)) + o.range_sigma * n01(gen);
      const bool dropped = o.dropout_probability > 0 && u01(gen) < o.dropout_probability;
      if (!(noisy < o.max_range) || dropped) {
        s.ranges.push_back(no_return);
        s.valid.push_back(0);
        continue;
      }
      double v = std::max(noisy, 0.01);
      if (o.range_quantum > 0) v = std::round(v / o.range_quantum) * o.range_quantum;
      s.ranges.push_back(static_cast<float>(v));
      s.valid.push_back(1);
    }
    log.records.push_back(std::move(r));
    log.truth.push_back(gt);
  }
  return log;
}

SimLog simulate(const FloorPlan& plan, const std::vector<mrpt::math::TPose2D>& waypoints, const SimOptions& o) {
  return simulate([&plan](double x, double y, double a) { return plan.rayCast(x, y, a); }, waypoints, o);
}

SimLog simulate(const RayCaster& world, const std::vector<mrpt::math::TPose2D>& waypoints, const SimOptions& o) {
  if (waypoints.empty()) return {};
  std::vector<mrpt::math::TPose2D> path{waypoints[0]};
  std::vector<double> times{o.start_time};
  // Applies a true increment: forward d, then rotation dth.
  auto move = [&](double d, double dth) {
    auto p = path.back();
    p.x += d * std::cos(p.phi);
    p.y += d * std::sin(p.phi);
    p.phi = wrap(p.phi + dth);
    path.push_back(p);
    times.push_back(times.back() + (std::abs(d) + 0.5 * std::abs(dth)) / o.speed);
  };
  for (std::size_t w = 1; w < waypoints.size(); ++w) {
    const double gx = waypoints[w].x, gy = waypoints[w].y;
    const double dist = std::hypot(gx - path.back().x, gy - path.back().y);
    if (dist < 1e-9) continue;
    const double turn = wrap(std::atan2(gy - path.back().y, gx - path.back().x) - path.back().phi);
    const int nturn = static_cast<int>(std::ceil(std::abs(turn) / o.scan_spacing));
    for (int i = 0; i < nturn; ++i) move(0.0, turn / nturn);
    const int nmove = static_cast<int>(std::ceil(dist / o.scan_spacing));
    for (int i = 0; i < nmove; ++i) move(dist / nmove, 0.0);
  }
  return simulatePath(world, path, times, o);
}

SimOptions pillarRoomOptions() {
  SimOptions o;
  o.beams = 180;
  o.fov = 179.0 * M_PI / 180.0;  // 1° between beams
  o.max_range = 8.0;
  o.no_return_range = 9.0;
  o.range_sigma = 0.01;
  o.range_quantum = 0.01;
  o.odo_sigma_xy = 0.05;
  o.odo_sigma_theta = 0.05;
  o.odo_sigma_theta_per_m = 0.01;
  o.odo_drift_theta = 0.0;
  o.seed = 42;
  return o;
}

SimLog simulatePillarRoom(std::size_t scans, const SimOptions& o) {
  if (scans < 2) throw std::invalid_argument("simulation: need at least 2 scans");
  std::vector<mrpt::math::TPose2D> path;
  std::vector<double> times;
  for (std::size_t i = 0; i < scans; ++i) {
    const double u = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(scans) - M_PI / 2.0;
    path.push_back({6.0 + 4.5 * std::cos(u), 3.0 + 2.0 * std::sin(u), std::atan2(2.0 * std::cos(u), -4.5 * std::sin(u))});
    times.push_back(o.start_time + 0.2 * static_cast<double>(i));
  }
  return simulatePath(FloorPlan::pillarRoom(), path, times, o);
}

}  // namespace gridtopo::sim
