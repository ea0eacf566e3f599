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
  const bool free_check = o.free_check;
  // One-entry tile cache: consecutive beams and the cells of a window mostly fall in the same tile.
  int ctx = 0x7fffffff, cty = 0x7fffffff;
  const Cell* tile = nullptr;
  auto lookup = [&](int cx, int cy) -> const Cell* {
    const int tx = cx >> GridMap::kTileBits, ty = cy >> GridMap::kTileBits;
    if (tx != ctx || ty != cty) {
      ctx = tx;
      cty = ty;
      const Cell* any = map.cell(cx, cy);
      tile = any ? any - (((cy & GridMap::kTileMask) << GridMap::kTileBits) | (cx & GridMap::kTileMask)) : nullptr;
    }
    return tile ? tile + (((cy & GridMap::kTileMask) << GridMap::kTileBits) | (cx & GridMap::kTileMask)) : nullptr;
  };
  ScanScore out;
  const std::size_t n = scan.size();
  const double* ex = scan.ex.data();
  const double* ey = scan.ey.data();
  const double* fx = scan.fx.data();
  const double* fy = scan.fy.data();
  for (std::size_t b = 0; b < n; ++b) {
    const double px = x.x + c * ex[b] - s * ey[b];
    const double py = x.y + s * ex[b] + c * ey[b];
    const int ipx = map.cellIndex(px), ipy = map.cellIndex(py);
    const int iqx = free_check ? map.cellIndex(x.x + c * fx[b] - s * fy[b]) : 0;
    const int iqy = free_check ? map.cellIndex(x.y + s * fx[b] + c * fy[b]) : 0;
    double best = std::numeric_limits<double>::infinity();
    auto consider = [&](const Cell* oc) {
      if (oc->log_odds <= occ || oc->hits == 0) return;
      const double ddx = px - oc->hit_x, ddy = py - oc->hit_y;
      best = std::min(best, ddx * ddx + ddy * ddy);
    };
    const int lx = ipx & GridMap::kTileMask, ly = ipy & GridMap::kTileMask;
    if (!free_check && lx >= k && ly >= k && lx < GridMap::kTileSize - k && ly < GridMap::kTileSize - k) {
      // Fast path: the whole window lies in one tile.
      const Cell* centre = lookup(ipx, ipy);
      if (centre) {
        for (int dy = -k; dy <= k; ++dy) {
          const Cell* row = centre + dy * GridMap::kTileSize;
          for (int dx = -k; dx <= k; ++dx) consider(row + dx);
        }
      }
    } else {
      for (int dy = -k; dy <= k; ++dy) {
        for (int dx = -k; dx <= k; ++dx) {
          const Cell* oc = lookup(ipx + dx, ipy + dy);
          if (!oc) continue;
          if (free_check && oc->log_odds > occ && oc->hits) {
            const Cell* fc = lookup(iqx + dx, iqy + dy);
            if (fc && fc->log_odds > occ) continue;
          }
          consider(oc);
        }
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
