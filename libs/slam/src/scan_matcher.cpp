#include "gridtopo/slam/scan_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gridtopo::slam {

namespace {

/// Calls fn(beam, px, py, found, d2, mx, my) for every matching beam at pose x: its world end point, whether a
/// correspondence was found, the squared distance to it and the hit mean (mx, my).
template <class Fn>
void associate(const GridMap& map, const Pose2& x, const PreparedScan& scan, const ScanMatcherOptions& o, Fn&& fn) {
  const double c = std::cos(x.theta), s = std::sin(x.theta);
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
    const Cell* best_cell = nullptr;
    auto consider = [&](const Cell* oc) {
      if (oc->log_odds <= occ || oc->hits == 0) return;
      const double ddx = px - oc->hit_x, ddy = py - oc->hit_y;
      const double d2 = ddx * ddx + ddy * ddy;
      if (d2 < best) {
        best = d2;
        best_cell = oc;
      }
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
    if (best_cell) fn(b, px, py, true, best, static_cast<double>(best_cell->hit_x), static_cast<double>(best_cell->hit_y));
    else fn(b, px, py, false, best, 0.0, 0.0);
  }
}

}  // namespace

ScanScore scoreScan(const GridMap& map, const Pose2& x, const PreparedScan& scan, const ScanMatcherOptions& o) {
  const double inv2s2 = 1.0 / (2.0 * o.sigma * o.sigma);
  ScanScore out;
  associate(map, x, scan, o, [&](std::size_t, double, double, bool found, double d2, double, double) {
    if (found) {
      ++out.matched;
      out.log_likelihood += std::max(-d2 * inv2s2, o.null_log_likelihood);
    } else {
      out.log_likelihood += o.null_log_likelihood;
    }
  });
  return out;
}

namespace {

double objective(const ScanScore& s, const Pose2& x, const MatchPrior* prior) {
  return prior ? s.log_likelihood * prior->likelihood_scale + prior->log_prior(x) : s.log_likelihood;
}

MatchResult hillClimb(const GridMap& map, const MatchResult& from, const PreparedScan& scan,
                      const ScanMatcherOptions& o, double sxy, double sth, int refinements, const MatchPrior* prior) {
  MatchResult r = from;
  double current = objective(r.score, r.pose, prior);
  int refinement = 0, iterations = 0;
  int came_from = -1;  // the move that leads back to the previous pose (known to be worse): not re-evaluated
  while (refinement <= refinements && iterations < o.max_iterations) {
    ++iterations;
    Pose2 best_pose = r.pose;
    ScanScore best = r.score;
    double best_obj = current;
    int best_move = -1;
    const Pose2 moves[6] = {{sxy, 0, 0}, {-sxy, 0, 0}, {0, sxy, 0}, {0, -sxy, 0}, {0, 0, sth}, {0, 0, -sth}};
    for (int mi = 0; mi < 6; ++mi) {
      if (mi == came_from) continue;
      const Pose2& m = moves[mi];
      const Pose2 cand{r.pose.x + m.x, r.pose.y + m.y, wrapAngle(r.pose.theta + m.theta)};
      const ScanScore sc = scoreScan(map, cand, scan, o);
      ++r.evaluations;
      const double obj = objective(sc, cand, prior);
      if (obj > best_obj) {
        best = sc;
        best_pose = cand;
        best_obj = obj;
        best_move = mi;
      }
    }
    if (best_obj > current) {
      r.pose = best_pose;
      r.score = best;
      current = best_obj;
      came_from = best_move ^ 1;  // moves come in ± pairs
    } else {
      sxy *= 0.5;
      sth *= 0.5;
      ++refinement;
      came_from = -1;
    }
  }
  return r;
}

/// Gauss-Newton on Σ_k |R(θ) e_k + t − m_k|² over the beams whose correspondence m_k (nearest hit mean) lies
/// within the likelihood's cut-off, re-associating at every iteration: a gradient method on the same
/// objective as the hill climber, converging in a few evaluations instead of ~100.
MatchResult gaussNewton(const GridMap& map, const Pose2& start, const PreparedScan& scan, const ScanMatcherOptions& o) {
  MatchResult r;
  r.pose = start;
  const double reach = (std::max(o.kernel, o.gn_kernel) + 0.5) * map.resolution();
  const double cutoff2 = std::max(-2.0 * o.sigma * o.sigma * o.null_log_likelihood, reach * reach);
  Pose2 x = start;
  ScanMatcherOptions wide = o;  // a wider correspondence window for the Gauss-Newton association
  wide.kernel = std::max(o.kernel, o.gn_kernel);
  for (int it = 0; it < o.gn_iterations; ++it) {
    const double c = std::cos(x.theta), s = std::sin(x.theta);
    double H[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, g[3] = {0, 0, 0};
    int used = 0;
    associate(map, x, scan, wide, [&](std::size_t b, double px, double py, bool found, double d2, double mx, double my) {
      if (!found || d2 >= cutoff2) return;
      const double rx = px - mx, ry = py - my;
      // d p / d θ
      const double jx = -s * scan.ex[b] - c * scan.ey[b], jy = c * scan.ex[b] - s * scan.ey[b];
      H[0][0] += 1;
      H[1][1] += 1;
      H[0][2] += jx;
      H[1][2] += jy;
      H[2][2] += jx * jx + jy * jy;
      g[0] += rx;
      g[1] += ry;
      g[2] += jx * rx + jy * ry;
      ++used;
    });
    ++r.evaluations;
    if (used < 3) break;
    H[2][0] = H[0][2];
    H[2][1] = H[1][2];
    // Solve H δ = −g (3×3, Cramer's rule; H is positive definite when beams are spread).
    const double det = H[0][0] * (H[1][1] * H[2][2] - H[1][2] * H[2][1]) -
                       H[0][1] * (H[1][0] * H[2][2] - H[1][2] * H[2][0]) +
                       H[0][2] * (H[1][0] * H[2][1] - H[1][1] * H[2][0]);
    if (!(std::abs(det) > 1e-12)) break;
    auto solve = [&](int col) {
      double M[3][3];
      for (int a = 0; a < 3; ++a)
        for (int b2 = 0; b2 < 3; ++b2) M[a][b2] = b2 == col ? -g[a] : H[a][b2];
      return (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
              M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) /
             det;
    };
    double dx = solve(0), dy = solve(1), dth = solve(2);
    // Trust region: never jump further than the hill climber's first step per iteration.
    const double n = std::hypot(dx, dy);
    if (n > o.step_xy) {
      dx *= o.step_xy / n;
      dy *= o.step_xy / n;
    }
    dth = std::clamp(dth, -o.step_theta, o.step_theta);
    x = {x.x + dx, x.y + dy, wrapAngle(x.theta + dth)};
    if (n < 1e-4 && std::abs(dth) < 1e-4) break;
  }
  r.pose = x;
  r.score = scoreScan(map, x, scan, o);
  ++r.evaluations;
  return r;
}

}  // namespace

MatchResult matchScan(const GridMap& map, const Pose2& start, const PreparedScan& scan,
                      const ScanMatcherOptions& o, const MatchPrior* prior) {
  MatchResult r;
  if (o.method == MatchMethod::GaussNewton) {
    r = gaussNewton(map, start, scan, o);
    // Polish on the true (truncated) objective with small steps; also guards against a bad GN step.
    MatchResult s0;
    s0.pose = start;
    s0.score = scoreScan(map, start, scan, o);
    if (objective(s0.score, s0.pose, prior) > objective(r.score, r.pose, prior)) {
      s0.evaluations = r.evaluations + 1;
      r = s0;
    } else {
      ++r.evaluations;
    }
    r = hillClimb(map, r, scan, o, o.polish_step_xy, o.polish_step_theta, o.polish_refinements, prior);
  } else {
    r.pose = start;
    double sxy = o.step_xy, sth = o.step_theta;
    int refinements = o.refinements;
    const int coarse = std::min(o.coarse_levels, o.refinements);
    if (coarse > 0 && o.coarse_beam_step > 1) {
      // Coarse-to-fine: the large steps only need to find the basin; every n-th matching beam does.
      PreparedScan sub;
      for (std::size_t b = 0; b < scan.size(); b += static_cast<std::size_t>(o.coarse_beam_step)) {
        sub.ex.push_back(scan.ex[b]);
        sub.ey.push_back(scan.ey[b]);
        sub.fx.push_back(scan.fx[b]);
        sub.fy.push_back(scan.fy[b]);
      }
      MatchResult c;
      c.pose = start;
      c.score = scoreScan(map, start, sub, o);
      c = hillClimb(map, c, sub, o, sxy, sth, coarse - 1, prior);
      r.pose = c.pose;
      r.evaluations = c.evaluations + 1;  // counted as full evaluations (an upper bound on the work)
      for (int i = 0; i < coarse; ++i) {
        sxy *= 0.5;
        sth *= 0.5;
      }
      refinements -= coarse;
    }
    r.score = scoreScan(map, r.pose, scan, o);
    r.evaluations += 1;
    r = hillClimb(map, r, scan, o, sxy, sth, refinements, prior);
  }
  r.ok = scan.size() > 0 && r.score.matched >= o.min_match_fraction * static_cast<double>(scan.size());
  return r;
}

}  // namespace gridtopo::slam
