#include "gridtopo/slam/prepared_scan.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace gridtopo::slam {

namespace {

/// Unit normal of a total-least-squares line through the hit end points of beams lo..hi, or (0, 0) when fewer
/// than three are hits or their RMS distance to the line exceeds kNormalMaxRms.
void surfaceNormal(const std::vector<double>& hx, const std::vector<double>& hy, const std::vector<char>& is_hit,
                   std::size_t lo, std::size_t hi, double& nx, double& ny) {
  nx = ny = 0.0;
  double sx = 0, sy = 0;
  int n = 0;
  for (std::size_t j = lo; j <= hi; ++j)
    if (is_hit[j]) {
      sx += hx[j];
      sy += hy[j];
      ++n;
    }
  if (n < 3) return;
  const double mx = sx / n, my = sy / n;
  double cxx = 0, cxy = 0, cyy = 0;
  for (std::size_t j = lo; j <= hi; ++j)
    if (is_hit[j]) {
      const double dx = hx[j] - mx, dy = hy[j] - my;
      cxx += dx * dx;
      cxy += dx * dy;
      cyy += dy * dy;
    }
  // The smaller eigenvalue of the scatter matrix is the sum of squared distances to the best line; its
  // eigenvector is the line's normal.
  const double tr = cxx + cyy, det = cxx * cyy - cxy * cxy;
  const double lmin = 0.5 * tr - std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
  if (!(lmin / n <= kNormalMaxRms * kNormalMaxRms)) return;
  double vx = cxy, vy = lmin - cxx;  // (C - lmin I) v = 0, first row
  if (std::abs(vx) + std::abs(vy) < 1e-15) {
    vx = lmin - cyy;  // second row
    vy = cxy;
  }
  const double len = std::hypot(vx, vy);
  if (!(len > 0.0)) return;
  nx = vx / len;
  ny = vy / len;
}

}  // namespace

PreparedScan prepareScan(const LaserScan& scan, const BeamOptions& o, double resolution) {
  PreparedScan p;
  p.sensor = {scan.sensor_pose.x, scan.sensor_pose.y, scan.sensor_pose.phi};
  const double usable =
      o.max_usable_range > 0.0 ? std::min(o.max_usable_range, scan.max_range > 0 ? scan.max_range : 1e9)
                               : scan.max_range;
  const double cs = std::cos(p.sensor.theta), ss = std::sin(p.sensor.theta);
  auto toRobot = [&](double lx, double ly, double& rx, double& ry) {
    rx = p.sensor.x + cs * lx - ss * ly;
    ry = p.sensor.y + ss * lx + cs * ly;
  };
  int step = o.matching_beam_step;
  if (step <= 0) {
    const double inc = std::abs(scan.angle_increment);
    step = inc > 0.0 ? static_cast<int>(std::lround(o.matching_beam_angle / inc)) : 1;
  }
  step = std::max(1, step);

  // Pass 1: the beams to insert, and every hit's end point (robot frame) for the normals.
  const std::size_t n = scan.size();
  std::vector<double> hx(n), hy(n), len_of(n);
  std::vector<char> is_hit(n, 0);
  std::vector<std::size_t> map_index(n, 0);
  p.map_beams.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double r = scan.ranges[k];
    const double a = scan.beamAngle(k);
    double len;
    bool hit;
    if (scan.valid[k] && std::isfinite(r) && r >= o.min_range) {
      hit = r < usable;
      len = hit ? r : usable;
    } else if (o.clear_no_return && !std::isnan(r) && (r >= scan.max_range || std::isinf(r)) && r > 0) {
      hit = false;
      len = std::min(o.no_return_range, usable);
    } else {
      continue;
    }
    MapBeam b{};
    toRobot(len * std::cos(a), len * std::sin(a), b.ex, b.ey);
    b.hit = hit;
    p.map_beams.push_back(b);
    if (hit) {
      map_index[k] = p.map_beams.size() - 1;
      hx[k] = b.ex;
      hy[k] = b.ey;
      len_of[k] = len;
      is_hit[k] = 1;
    }
  }

  // Pass 2: every step-th matchable hit is a matching end point, with its surface normal.
  const double match_below = usable - o.matching_range_margin;
  const double min_sin_incidence = std::sin(o.matching_min_incidence);
  int hit_count = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const bool matchable = is_hit[k] && len_of[k] < match_below;
    if (!matchable && !(is_hit[k] && o.surface_clearance > 0.0)) continue;
    // The window of beams: k ± w, widened until its outermost hits are kNormalSpan apart (a wall seen square on at
    // 1 m gives end points 2 cm apart per degree, too close for a normal at the range noise) or w reaches the cap.
    std::size_t lo = k, hi = k;
    for (int w = 1; w <= kNormalMaxNeighbours; ++w) {
      if (lo > 0) --lo;
      if (hi + 1 < n) ++hi;
      std::size_t a = lo, b = hi;
      while (a < k && !is_hit[a]) ++a;
      while (b > k && !is_hit[b]) --b;
      if (w >= 2 && std::hypot(hx[b] - hx[a], hy[b] - hy[a]) >= kNormalSpan) break;
    }
    double nx = 0.0, ny = 0.0;
    surfaceNormal(hx, hy, is_hit, lo, hi, nx, ny);
    // The angle between beam and surface: sin = |cos(beam, normal)|.
    const bool has_normal = nx != 0.0 || ny != 0.0;
    const double bx = hx[k] - p.sensor.x, by = hy[k] - p.sensor.y;
    const double sin_incidence = has_normal ? std::abs(bx * nx + by * ny) / std::hypot(bx, by) : 1.0;
    if (o.surface_clearance > 0.0 && has_normal) {
      const double keep = std::min(len_of[k], o.surface_clearance / std::max(sin_incidence, 1e-6));
      p.map_beams[map_index[k]].free_fraction = (len_of[k] - keep) / len_of[k];
    }
    if (!matchable) continue;
    if (o.matching_min_incidence > 0.0 && has_normal && sin_incidence < min_sin_incidence) continue;
    if ((hit_count++ % step) != 0) continue;
    const double a = scan.beamAngle(k), back = len_of[k] - resolution;
    double fxr, fyr;
    toRobot(back * std::cos(a), back * std::sin(a), fxr, fyr);
    p.ex.push_back(hx[k]);
    p.ey.push_back(hy[k]);
    p.fx.push_back(fxr);
    p.fy.push_back(fyr);
    p.nx.push_back(nx);
    p.ny.push_back(ny);
  }
  return p;
}

PreparedScan everyNthMatchingPoint(const PreparedScan& scan, std::size_t step) {
  PreparedScan sub;
  for (std::size_t b = 0; b < scan.size(); b += step) {
    sub.ex.push_back(scan.ex[b]);
    sub.ey.push_back(scan.ey[b]);
    sub.fx.push_back(scan.fx[b]);
    sub.fy.push_back(scan.fy[b]);
    sub.nx.push_back(scan.nx[b]);
    sub.ny.push_back(scan.ny[b]);
  }
  return sub;
}

}  // namespace gridtopo::slam
