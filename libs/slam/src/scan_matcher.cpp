#include "gridtopo/slam/scan_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gridtopo::slam {

namespace {

/// The squared distance from end point (px, py) to hit mean (mx, my) along the beam's surface normal (nx, ny) in the
/// robot frame, turned by the pose's heading (c, s = cos, sin): MatchResidual::Plane. One function for scoreScan
/// and the cached scorer, so that both give the same bits.
inline double planeDistance2(double px, double py, double mx, double my, double c, double s, double nx, double ny) {
  const double r = (px - mx) * (c * nx - s * ny) + (py - my) * (s * nx + c * ny);
  return r * r;
}

/// Calls fn(beam, px, py, found, d2, mx, my) for every matching beam at pose x: its world end point, whether a
/// correspondence was found, the squared distance to it and the hit mean (mx, my).
template <class Fn>
void associate(const GridMap& map, const Pose2& x, const PreparedScan& scan, const ScanMatcherOptions& o, Fn&& fn) {
  using Tile = GridMap::Tile;
  const double c = std::cos(x.theta), s = std::sin(x.theta);
  const int k = o.kernel;
  const float occ = o.occupied_log_odds;
  const bool free_check = o.free_check;
  // One-entry tile cache: consecutive beams and the cells of a window mostly fall in the same tile.
  int ctx = 0x7fffffff, cty = 0x7fffffff;
  const Tile* tile = nullptr;
  auto lookup = [&](int cx, int cy) -> const Tile* {
    const int tx = cx >> GridMap::kTileBits, ty = cy >> GridMap::kTileBits;
    if (tx != ctx || ty != cty) {
      ctx = tx;
      cty = ty;
      tile = map.tileAt(cx, cy);
    }
    return tile;
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
    const HitMean* best_hit = nullptr;
    auto consider = [&](const Tile* t, int i) {
      if (t->log_odds[static_cast<std::size_t>(i)] <= occ) return;
      const HitMean* h = t->hit(static_cast<std::size_t>(i));
      if (!h || h->n == 0) return;
      const double ddx = px - h->x, ddy = py - h->y;
      const double d2 = ddx * ddx + ddy * ddy;
      if (d2 < best) {
        best = d2;
        best_hit = h;
      }
    };
    const int lx = ipx & GridMap::kTileMask, ly = ipy & GridMap::kTileMask;
    if (!free_check && lx >= k && ly >= k && lx < GridMap::kTileSize - k && ly < GridMap::kTileSize - k) {
      // Fast path: the whole window lies in one tile.
      if (const Tile* t = lookup(ipx, ipy)) {
        const int centre = GridMap::cellOffset(ipx, ipy);
        for (int dy = -k; dy <= k; ++dy)
          for (int dx = -k; dx <= k; ++dx) consider(t, centre + dy * GridMap::kTileSize + dx);
      }
    } else {
      for (int dy = -k; dy <= k; ++dy) {
        for (int dx = -k; dx <= k; ++dx) {
          const Tile* t = lookup(ipx + dx, ipy + dy);
          if (!t) continue;
          const int i = GridMap::cellOffset(ipx + dx, ipy + dy);
          const HitMean* hm = t->hit(static_cast<std::size_t>(i));
          if (free_check && t->log_odds[static_cast<std::size_t>(i)] > occ && hm && hm->n) {
            const Tile* ft = lookup(iqx + dx, iqy + dy);
            if (ft && ft->log_odds[static_cast<std::size_t>(GridMap::cellOffset(iqx + dx, iqy + dy))] > occ) continue;
            t = lookup(ipx + dx, ipy + dy);
          }
          consider(t, i);
        }
      }
    }
    if (best_hit) fn(b, px, py, true, best, static_cast<double>(best_hit->x), static_cast<double>(best_hit->y));
    else fn(b, px, py, false, best, 0.0, 0.0);
  }
}

}  // namespace

ScanScore scoreScan(const GridMap& map, const Pose2& x, const PreparedScan& scan, const ScanMatcherOptions& o) {
  const double inv2s2 = 1.0 / (2.0 * o.sigma * o.sigma);
  ScanScore out;
  const bool plane = o.residual == MatchResidual::Plane;
  const double c = std::cos(x.theta), s = std::sin(x.theta);
  associate(map, x, scan, o, [&](std::size_t b, double px, double py, bool found, double d2, double mx, double my) {
    if (found && plane && (scan.nx[b] != 0.0 || scan.ny[b] != 0.0))
      d2 = planeDistance2(px, py, mx, my, c, s, scan.nx[b], scan.ny[b]);
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
inline std::uint64_t cellKey(int cx, int cy) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(cx)) << 32) | static_cast<std::uint32_t>(cy);
}
}  // namespace

struct ScanScorer::Tables {
  std::vector<Slot> table;
  std::vector<std::uint32_t> filled;
  std::vector<double> hits;
  std::vector<Slot> near;
};

namespace {
constexpr std::size_t kInitialTableBits = 12;
}  // namespace

// Each thread's unused tables: a scorer takes one (or makes one) and gives it back emptied. Scorers can nest (the
// coarse-to-fine search's coarse scorer lives inside the fine one): a thread then holds two.
std::vector<std::unique_ptr<ScanScorer::Tables>>& ScanScorer::threadPool() {
  thread_local std::vector<std::unique_ptr<Tables>> pool;
  return pool;
}

std::unique_ptr<ScanScorer::Tables> ScanScorer::takeTables() {
  auto& pool = threadPool();
  if (pool.empty()) return std::make_unique<Tables>();
  std::unique_ptr<Tables> t = std::move(pool.back());
  pool.pop_back();
  return t;
}

ScanScorer::ScanScorer(const GridMap& map, const PreparedScan& scan, const ScanMatcherOptions& o)
    : map_(map), scan_(scan), o_(o), tables_(takeTables()), table_(tables_->table), filled_(tables_->filled),
      hits_(tables_->hits), near_(tables_->near) {
  // A table given back keeps its size (every slot empty): a power of two, at least 2^12.
  if (table_.empty()) table_.assign(std::size_t{1} << kInitialTableBits, Slot{kEmpty, 0, 0});
  shift_ = 64 - __builtin_ctzll(table_.size());
  hits_.reserve(4096);
  near_.assign(scan.size() * kNearSlots, Slot{kEmpty, 0, 0});
}

ScanScorer::~ScanScorer() {
  for (const std::uint32_t i : filled_) table_[i].key = kEmpty;
  filled_.clear();
  hits_.clear();
  threadPool().push_back(std::move(tables_));
}

void ScanScorer::grow() {
  std::vector<Slot> old(table_.size() * 2, Slot{kEmpty, 0, 0});
  old.swap(table_);
  --shift_;
  const std::size_t mask = table_.size() - 1;
  filled_.clear();
  for (const Slot& s : old) {
    if (s.key == kEmpty) continue;
    std::size_t i = static_cast<std::size_t>((s.key * 0x9E3779B97F4A7C15ULL) >> shift_);
    while (table_[i].key != kEmpty) i = (i + 1) & mask;
    table_[i] = s;
    filled_.push_back(static_cast<std::uint32_t>(i));
  }
}

const ScanScorer::Slot& ScanScorer::window(int cx, int cy) {
  const std::uint64_t key = cellKey(cx, cy);
  const std::size_t mask = table_.size() - 1;
  std::size_t i = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> shift_);
  while (table_[i].key != kEmpty) {
    if (table_[i].key == key) return table_[i];
    i = (i + 1) & mask;
  }
  // Not seen yet: the occupied cells of the window, in scoreScan's order.
  const int k = o_.kernel;
  const float occ = o_.occupied_log_odds;
  const std::size_t offset = hits_.size() / 2;
  auto take = [&](const GridMap::Tile* t, int i) {
    if (t->log_odds[static_cast<std::size_t>(i)] <= occ) return;
    const HitMean* h = t->hit(static_cast<std::size_t>(i));
    if (!h || h->n == 0) return;
    hits_.push_back(h->x);
    hits_.push_back(h->y);
  };
  const int lx = cx & GridMap::kTileMask, ly = cy & GridMap::kTileMask;
  if (lx >= k && ly >= k && lx < GridMap::kTileSize - k && ly < GridMap::kTileSize - k) {
    if (const GridMap::Tile* t = map_.tileAt(cx, cy)) {
      const int centre = GridMap::cellOffset(cx, cy);
      for (int dy = -k; dy <= k; ++dy)
        for (int dx = -k; dx <= k; ++dx) take(t, centre + dy * GridMap::kTileSize + dx);
    }
  } else {
    for (int dy = -k; dy <= k; ++dy)
      for (int dx = -k; dx <= k; ++dx)
        if (const GridMap::Tile* t = map_.tileAt(cx + dx, cy + dy)) take(t, GridMap::cellOffset(cx + dx, cy + dy));
  }
  table_[i] = Slot{key, static_cast<std::uint32_t>(offset), static_cast<std::uint32_t>(hits_.size() / 2 - offset)};
  filled_.push_back(static_cast<std::uint32_t>(i));
  const Slot& filled = table_[i];
  if (++used_ * 2 > table_.size()) {
    grow();
    return window(cx, cy);
  }
  return filled;
}

ScanScore ScanScorer::score(const Pose2& x) {
  if (o_.free_check) return scoreScan(map_, x, scan_, o_);  // the window also depends on the cell in front
  ScanScore out;
  scoreImpl<false>(x, 0.0, out);
  return out;
}

std::optional<ScanScore> ScanScorer::scoreAbove(const Pose2& x, double stop_at) {
  ScanScore out;
  if (o_.free_check) {
    out = scoreScan(map_, x, scan_, o_);
  } else if (!scoreImpl<true>(x, stop_at, out)) {
    return std::nullopt;
  }
  if (out.log_likelihood <= stop_at) return std::nullopt;
  return out;
}

template <bool kStop>
bool ScanScorer::scoreImpl(const Pose2& x, double stop_at, ScanScore& out) {
  const double inv2s2 = 1.0 / (2.0 * o_.sigma * o_.sigma);
  const double c = std::cos(x.theta), s = std::sin(x.theta);
  const std::size_t n = scan_.size();
  const double* ex = scan_.ex.data();
  const double* ey = scan_.ey.data();
  const double null_ll = o_.null_log_likelihood;
  const bool plane = o_.residual == MatchResidual::Plane;
  const double* nx = scan_.nx.data();
  const double* ny = scan_.ny.data();
  const double inv_res = 1.0 / map_.resolution();
  auto cellIndex = [inv_res](double w) {  // GridMap::cellIndex with the scale hoisted out of the loop
    const double v = w * inv_res;
    const int i = static_cast<int>(v);
    return i - (v < static_cast<double>(i));
  };
  for (std::size_t b = 0; b < n; ++b) {
    // Same arithmetic as scoreScan, so the result is bit-identical.
    const double px = x.x + c * ex[b] - s * ey[b];
    const double py = x.y + s * ex[b] + c * ey[b];
    const int ipx = cellIndex(px), ipy = cellIndex(py);
    const std::uint64_t key = cellKey(ipx, ipy);
    Slot& w = near_[b * kNearSlots + static_cast<std::size_t>(((ipy & kNearMask) << kNearBits) | (ipx & kNearMask))];
    if (key != w.key) w = window(ipx, ipy);
    if (w.count == 0) {
      out.log_likelihood += null_ll;
      if (kStop && out.log_likelihood <= stop_at) return false;
      continue;
    }
    const double* h = hits_.data() + 2 * static_cast<std::size_t>(w.offset);
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t best_j = 0;
    for (std::uint32_t j = 0; j < w.count; ++j) {
      const double ddx = px - h[2 * j], ddy = py - h[2 * j + 1];
      const double d2 = ddx * ddx + ddy * ddy;
      if (d2 < best) {
        best = d2;
        best_j = j;
      }
    }
    if (plane && (nx[b] != 0.0 || ny[b] != 0.0))
      best = planeDistance2(px, py, h[2 * best_j], h[2 * best_j + 1], c, s, nx[b], ny[b]);
    ++out.matched;
    out.log_likelihood += std::max(-best * inv2s2, null_ll);
    if (kStop && out.log_likelihood <= stop_at) return false;
  }
  return true;
}

namespace {

double objective(const ScanScore& s, const Pose2& x, const MatchPrior* prior) {
  return prior ? s.log_likelihood * prior->likelihood_scale + prior->log_prior(x) : s.log_likelihood;
}

/// A log-likelihood at or below which a candidate's objective cannot exceed best_obj. The objective is
/// increasing in the log-likelihood (rounding included), so the bound is moved down until it provably holds.
double stopBelow(double best_obj, const Pose2& x, const MatchPrior* prior) {
  if (!prior) return best_obj;
  const double lp = prior->log_prior(x);
  double bound = (best_obj - lp) / prior->likelihood_scale;
  if (!std::isfinite(bound)) return -std::numeric_limits<double>::infinity();
  while (bound * prior->likelihood_scale + lp > best_obj)
    bound = std::nextafter(bound, -std::numeric_limits<double>::infinity());
  return bound;
}

MatchResult hillClimb(ScanScorer& scorer, const MatchResult& from, double sxy, double sth, int refinements,
                      const MatchPrior* prior) {
  const ScanMatcherOptions& o = scorer.options();
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
      ++r.evaluations;
      const std::optional<ScanScore> sc = scorer.scoreAbove(cand, stopBelow(best_obj, cand, prior));
      if (!sc) continue;  // cannot beat best_obj
      const double obj = objective(*sc, cand, prior);
      if (obj > best_obj) {
        best = *sc;
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
  ScanScorer scorer(map, scan, o);
  return matchScan(scorer, start, prior);
}

MatchResult matchScan(ScanScorer& scorer, const Pose2& start, const MatchPrior* prior) {
  const GridMap& map = scorer.map();
  const PreparedScan& scan = scorer.scan();
  const ScanMatcherOptions& o = scorer.options();
  MatchResult r;
  if (o.method == MatchMethod::GaussNewton) {
    r = gaussNewton(map, start, scan, o);
    // Polish on the true (truncated) objective with small steps; also guards against a bad GN step.
    MatchResult s0;
    s0.pose = start;
    s0.score = scorer.score(start);
    if (objective(s0.score, s0.pose, prior) > objective(r.score, r.pose, prior)) {
      s0.evaluations = r.evaluations + 1;
      r = s0;
    } else {
      ++r.evaluations;
    }
    r = hillClimb(scorer, r, o.polish_step_xy, o.polish_step_theta, o.polish_refinements, prior);
  } else {
    r.pose = start;
    double sxy = o.step_xy, sth = o.step_theta;
    int refinements = o.refinements;
    const int coarse = std::min(o.coarse_levels, o.refinements);
    if (coarse > 0 && o.coarse_beam_step > 1) {
      // Coarse-to-fine: the large steps only need to find the basin; every n-th matching beam does.
      const PreparedScan sub = everyNthMatchingPoint(scan, static_cast<std::size_t>(o.coarse_beam_step));
      ScanScorer sub_scorer(map, sub, o);
      MatchResult c;
      c.pose = start;
      c.score = sub_scorer.score(start);
      c = hillClimb(sub_scorer, c, sxy, sth, coarse - 1, prior);
      r.pose = c.pose;
      r.evaluations = c.evaluations + 1;  // counted as full evaluations (an upper bound on the work)
      for (int i = 0; i < coarse; ++i) {
        sxy *= 0.5;
        sth *= 0.5;
      }
      refinements -= coarse;
    }
    r.score = scorer.score(r.pose);
    r.evaluations += 1;
    r = hillClimb(scorer, r, sxy, sth, refinements, prior);
  }
  r.ok = scan.size() > 0 && r.score.matched >= o.min_match_fraction * static_cast<double>(scan.size());
  return r;
}

}  // namespace gridtopo::slam
