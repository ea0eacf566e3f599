#include "gridtopo/slam/trajectory_render.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

#include "gridtopo/core/distance_transform.h"

namespace gridtopo::slam {

std::optional<LoopClosure> firstLoopClosure(const std::vector<TimedPose>& trajectory, double radius,
                                            double min_travel) {
  const std::size_t n = trajectory.size();
  std::vector<double> travelled(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
    travelled[i] = travelled[i - 1] + std::hypot(trajectory[i].pose.x - trajectory[i - 1].pose.x,
                                                 trajectory[i].pose.y - trajectory[i - 1].pose.y);
  const double r2 = radius * radius;
  for (std::size_t later = 1; later < n; ++later) {
    const auto& b = trajectory[later].pose;
    std::optional<LoopClosure> best;
    // Every pose at least min_travel metres back along the path; the nearest of them is the closure.
    for (std::size_t i = 0; i < later && travelled[later] - travelled[i] >= min_travel; ++i) {
      const double dx = trajectory[i].pose.x - b.x, dy = trajectory[i].pose.y - b.y;
      const double d2 = dx * dx + dy * dy;
      if (d2 <= r2 && (!best || d2 < best->distance * best->distance))
        best = LoopClosure{i, later, std::sqrt(d2), travelled[later] - travelled[i]};
    }
    if (best) return best;
  }
  return std::nullopt;
}

namespace {

/// Liang-Barsky: the parameters [t0, t1] of the segment p + t·d, t in [0, 1], inside the window; false if none.
bool clipToWindow(double px, double py, double dx, double dy, const MapWindow& w, double& t0, double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {px - w.x0, w.x1 - px, py - w.y0, w.y1 - py};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return false;
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0.0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  return true;
}

/// Distance from (x, y) to the window (0 inside).
double distanceToWindow(const MapWindow& w, double x, double y) {
  const double dx = std::max({w.x0 - x, 0.0, x - w.x1});
  const double dy = std::max({w.y0 - y, 0.0, y - w.y1});
  return std::hypot(dx, dy);
}

/// The beams of `scan` at `robot` cut at the window's border: a beam that ends outside becomes free-only up to the
/// border; one that never enters it is dropped.
std::vector<MapBeam> beamsInWindow(const PreparedScan& scan, const Pose2& robot, const MapWindow& w) {
  const Pose2 sensor = compose(robot, scan.sensor);
  const double c = std::cos(robot.theta), s = std::sin(robot.theta);
  std::vector<MapBeam> out;
  out.reserve(scan.map_beams.size());
  for (const MapBeam& b : scan.map_beams) {
    const double ex = robot.x + c * b.ex - s * b.ey, ey = robot.y + s * b.ex + c * b.ey;
    double t0, t1;
    if (!clipToWindow(sensor.x, sensor.y, ex - sensor.x, ey - sensor.y, w, t0, t1)) continue;
    if (t1 >= 1.0) {
      out.push_back(b);
      continue;
    }
    const double wx = sensor.x + t1 * (ex - sensor.x), wy = sensor.y + t1 * (ey - sensor.y);
    // Back to the robot frame.
    out.push_back({c * (wx - robot.x) + s * (wy - robot.y), -s * (wx - robot.x) + c * (wy - robot.y), false, 1.0});
  }
  return out;
}

}  // namespace

GridMap mapFromTrajectory(const std::vector<ScanRecord>& scans, const std::vector<TimedPose>& trajectory,
                          const TrajectoryRenderOptions& o, std::size_t* inserted) {
  if (trajectory.size() > scans.size()) {
    TrajectoryMismatch e("the trajectory has " + std::to_string(trajectory.size()) + " poses but the log only " +
                         std::to_string(scans.size()) + " scans");
    e.pose_index = scans.size();
    throw e;
  }
  GridMap map(o.resolution);
  std::size_t count = 0;
  for (std::size_t k = 0; k < trajectory.size(); ++k) {
    if (k < o.first_pose || k >= o.end_pose) continue;
    if (trajectory[k].timestamp != scans[k].scan.timestamp) {
      TrajectoryMismatch e("pose " + std::to_string(k + 1) + " has timestamp " + io::formatDouble(trajectory[k].timestamp) +
                           " but scan " + std::to_string(k + 1) + " of the log " +
                           io::formatDouble(scans[k].scan.timestamp) + ": not this log's trajectory");
      e.pose_index = k;
      throw e;
    }
    const auto& p = trajectory[k].pose;
    const Pose2 robot{p.x, p.y, p.phi};
    const PreparedScan ps = prepareScan(scans[k].scan, o.beams, o.resolution);
    if (o.window) {
      const Pose2 sensor = compose(robot, ps.sensor);
      if (distanceToWindow(*o.window, sensor.x, sensor.y) > o.reach) continue;
      const auto beams = beamsInWindow(ps, robot, *o.window);
      if (beams.empty()) continue;
      map.insertScan(robot, ps.sensor, beams, o.map);
    } else {
      map.insertScan(robot, ps.sensor, ps.map_beams, o.map);
    }
    ++count;
  }
  if (inserted) *inserted = count;
  return map;
}

MapWindow boundsOf(const GridMap& map) {
  int x0, y0, x1, y1;
  map.cellBounds(x0, y0, x1, y1);
  const double r = map.resolution();
  return {x0 * r, y0 * r, x1 * r - 1e-9, y1 * r - 1e-9};
}

cv::Mat renderWindow(const GridMap& map, const MapWindow& w) {
  const int cx0 = map.cellIndex(w.x0), cy0 = map.cellIndex(w.y0);
  const int cols = std::max(1, map.cellIndex(w.x1) - cx0 + 1), rows = std::max(1, map.cellIndex(w.y1) - cy0 + 1);
  cv::Mat img(rows, cols, CV_8UC1);
  for (int row = 0; row < rows; ++row) {
    const int cy = cy0 + (rows - 1 - row);
    auto* out = img.ptr<unsigned char>(row);
    for (int col = 0; col < cols; ++col)
      out[col] = static_cast<unsigned char>(std::lround(255.0 * (1.0 - map.probability(cx0 + col, cy))));
  }
  return img;
}

WallAgreement wallAgreement(const GridMap& a, const GridMap& b, const MapWindow& w, double occupied) {
  const cv::Mat ia = renderWindow(a, w), ib = renderWindow(b, w);
  // Grey g = 255 (1 - p): occupied means g <= 255 (1 - occupied); known means g != 128.
  const double g_occ = 255.0 * (1.0 - occupied);
  cv::Mat not_wall_a(ia.size(), CV_8UC1);
  for (int r = 0; r < ia.rows; ++r)
    for (int c = 0; c < ia.cols; ++c) not_wall_a.at<unsigned char>(r, c) = ia.at<unsigned char>(r, c) <= g_occ ? 0 : 255;
  const cv::Mat dist = preciseDistance(not_wall_a);
  std::vector<double> d;
  for (int r = 0; r < ib.rows; ++r)
    for (int c = 0; c < ib.cols; ++c)
      if (ib.at<unsigned char>(r, c) <= g_occ && ia.at<unsigned char>(r, c) != 128)
        d.push_back(static_cast<double>(dist.at<float>(r, c)) * a.resolution());
  WallAgreement out;
  out.cells = d.size();
  if (d.empty()) return out;
  std::sort(d.begin(), d.end());
  out.median = d[d.size() / 2];
  out.p90 = d[std::min(d.size() - 1, d.size() * 9 / 10)];
  out.within_2cells = static_cast<double>(std::upper_bound(d.begin(), d.end(), 2.0 * a.resolution() + 1e-9) - d.begin()) /
                      static_cast<double>(d.size());
  return out;
}

std::optional<LoopClosureRendering> renderLoopClosure(const std::vector<ScanRecord>& scans,
                                                      const std::vector<TimedPose>& trajectory,
                                                      const TrajectoryRenderOptions& options, double size,
                                                      double radius, double min_travel) {
  const auto lc = firstLoopClosure(trajectory, radius, min_travel);
  if (!lc) return std::nullopt;
  const auto& p = trajectory[lc->later].pose;
  TrajectoryRenderOptions o = options;
  o.window = MapWindow::around(p.x, p.y, size, size);
  TrajectoryRenderOptions before = o, after = o;
  before.end_pose = after.first_pose = lc->later;
  const auto agreement =
      wallAgreement(mapFromTrajectory(scans, trajectory, before), mapFromTrajectory(scans, trajectory, after), *o.window);
  return LoopClosureRendering{*lc, *o.window, agreement, mapFromTrajectory(scans, trajectory, o)};
}

}  // namespace gridtopo::slam
