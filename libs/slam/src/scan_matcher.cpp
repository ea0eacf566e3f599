#include "gridtopo/slam/scan_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gridtopo::slam {

ScanScore scoreScan(const GridMap& map, const Pose2& x, const PreparedScan& scan, const ScanMatcherOptions& o) {
  const double c = std::cos(x.theta), s = std::sin(x.theta);
  const double inv2s2 = 1.0 / (2.0 * o.sigma * o.sigma);
  const int k = o.kernel;
  const float occ = o.occupied_log_odds;
  ScanScore out;
  const std::size_t n = scan.size();
  for (std::size_t b = 0; b < n; ++b) {
    const double px = x.x + c * scan.ex[b] - s * scan.ey[b];
    const double py = x.y + s * scan.ex[b] + c * scan.ey[b];
    const double qx = x.x + c * scan.fx[b] - s * scan.fy[b];
    const double qy = x.y + s * scan.fx[b] + c * scan.fy[b];
    const int ipx = map.cellIndex(px), ipy = map.cellIndex(py);
    const int iqx = map.cellIndex(qx), iqy = map.cellIndex(qy);
    double best = std::numeric_limits<double>::infinity();
    for (int dy = -k; dy <= k; ++dy) {
      for (int dx = -k; dx <= k; ++dx) {
        const Cell* oc = map.cell(ipx + dx, ipy + dy);
        if (!oc || oc->hits == 0 || oc->log_odds <= occ) continue;
        const Cell* fc = map.cell(iqx + dx, iqy + dy);
        if (fc && fc->log_odds > occ) continue;
        const double inv = 1.0 / oc->hits;
        const double ddx = px - oc->hit_x * inv, ddy = py - oc->hit_y * inv;
        best = std::min(best, ddx * ddx + ddy * ddy);
      }
    }
    if (best < std::numeric_limits<double>::infinity()) {
      ++out.matched;
      out.log_likelihood += std::max(-best * inv2s2, o.null_log_likelihood);
    } else {
      out.log_likelihood += o.null_log_likelihood;
    }
  }
  return out;
}

MatchResult matchScan(const GridMap& map, const Pose2& start, const PreparedScan& scan,
                      const ScanMatcherOptions& o) {
  MatchResult r;
  r.pose = start;
  r.score = scoreScan(map, start, scan, o);
  r.evaluations = 1;
  double sxy = o.step_xy, sth = o.step_theta;
  int refinement = 0, iterations = 0;
  while (refinement <= o.refinements && iterations < o.max_iterations) {
    ++iterations;
    Pose2 best_pose = r.pose;
    ScanScore best = r.score;
    const Pose2 moves[6] = {{sxy, 0, 0}, {-sxy, 0, 0}, {0, sxy, 0}, {0, -sxy, 0}, {0, 0, sth}, {0, 0, -sth}};
    for (const auto& m : moves) {
      const Pose2 cand{r.pose.x + m.x, r.pose.y + m.y, wrapAngle(r.pose.theta + m.theta)};
      const ScanScore sc = scoreScan(map, cand, scan, o);
      ++r.evaluations;
      if (sc.log_likelihood > best.log_likelihood) {
        best = sc;
        best_pose = cand;
      }
    }
    if (best.log_likelihood > r.score.log_likelihood) {
      r.pose = best_pose;
      r.score = best;
    } else {
      sxy *= 0.5;
      sth *= 0.5;
      ++refinement;
    }
  }
  r.ok = scan.size() > 0 && r.score.matched >= o.min_match_fraction * static_cast<double>(scan.size());
  return r;
}

}  // namespace gridtopo::slam
