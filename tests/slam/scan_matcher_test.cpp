#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/scan_matcher.h"

using namespace gridtopo;
using namespace gridtopo::slam;

namespace {
// A map built from noise-free scans of the office floor plan taken at known poses.
struct Fixture {
  GridMap map{0.05};
  sim::FloorPlan plan = sim::FloorPlan::officeLoop();
  sim::SimOptions so;
  BeamOptions bo;
  Fixture() {
    bo.matching_beam_step = 1;  // all beams: the matcher's own accuracy, not the subsampling's
    so.range_sigma = 0.0;
    const std::vector<mrpt::math::TPose2D> wp = {{2, 6, -M_PI / 2}, {2, 2.8, 0}, {9, 2.8, 0}};
    const auto log = sim::simulate(plan, wp, so);
    for (std::size_t i = 0; i < log.records.size(); ++i) {
      const auto ps = prepareScan(log.records[i].scan, bo, map.resolution());
      const auto& t = log.truth[i];
      map.insertScan({t.x, t.y, t.phi}, ps.sensor, ps.map_beams, MapUpdateOptions{});
    }
  }
  PreparedScan scanAt(const Pose2& p) {
    sim::SimOptions o = so;
    o.range_sigma = 0.005;
    const auto log = sim::simulate(plan, {{p.x, p.y, p.theta}}, o);
    return prepareScan(log.records.at(0).scan, bo, map.resolution());
  }
};
}  // namespace

TEST(ScanMatcher, LikelihoodPeaksAtTheTruePose) {
  Fixture f;
  const Pose2 truth{6.3, 2.8, 0.05};
  const auto scan = f.scanAt(truth);
  ScanMatcherOptions o;
  const ScanScore at = scoreScan(f.map, truth, scan, o);
  EXPECT_GT(at.matched, 0.9 * scan.size());
  for (const Pose2 d : {Pose2{0.05, 0, 0}, Pose2{0, -0.05, 0}, Pose2{0, 0, 0.03}})
    EXPECT_LT(scoreScan(f.map, {truth.x + d.x, truth.y + d.y, truth.theta + d.theta}, scan, o).log_likelihood,
              at.log_likelihood - 5.0);
}

TEST(ScanMatcher, CachedScorerEqualsScoreScanBitForBit) {
  Fixture f;
  const auto scan = f.scanAt({6.3, 2.8, 0.05});
  for (int variant = 0; variant < 3; ++variant) {
    const int kernel = variant == 1 ? 2 : 1;
    ScanMatcherOptions o;
    o.kernel = kernel;
    if (variant == 2) o.residual = MatchResidual::Plane;
    ScanScorer scorer(f.map, scan, o);
    // A walk of poses that revisits cells (as a search does), crosses tile borders and leaves the map.
    std::uint64_t state = 12345;
    auto uniform = [&] {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(state >> 11) * 0x1.0p-53;
    };
    int differing_windows = 0;
    for (int i = 0; i < 600; ++i) {
      const double r = i < 500 ? 0.15 : 30.0;  // the last poses far outside the map: no correspondences
      const Pose2 x{6.3 + r * (uniform() - 0.5), 2.8 + r * (uniform() - 0.5), 0.05 + 0.2 * (uniform() - 0.5)};
      const ScanScore a = scoreScan(f.map, x, scan, o), b = scorer.score(x);
      ASSERT_EQ(a.matched, b.matched) << i;
      ASSERT_EQ(a.log_likelihood, b.log_likelihood) << i;  // exactly, not approximately
      differing_windows += a.matched != static_cast<int>(scan.size());
    }
    EXPECT_GT(differing_windows, 100);  // the walk really changes the correspondences
    // The search with the cached scorer is the search with scoreScan.
    const MatchResult m1 = matchScan(f.map, {6.35, 2.75, 0.0}, scan, o);
    ScanScorer fresh(f.map, scan, o);
    const MatchResult m2 = matchScan(fresh, {6.35, 2.75, 0.0});
    EXPECT_EQ(m1.pose.x, m2.pose.x);
    EXPECT_EQ(m1.pose.theta, m2.pose.theta);
    EXPECT_EQ(m1.evaluations, m2.evaluations);
  }
}

TEST(ScanMatcher, ScorersReuseTheirThreadsTablesWithoutCarryingAnythingOver) {
  // A scorer takes its tables from the thread's pool and gives them back emptied: the next scorer, on another map
  // and a scan of another size, nested in a third or after a scorer whose table grew, scores exactly as scoreScan.
  Fixture f;
  const auto scan = f.scanAt({6.3, 2.8, 0.05});
  const PreparedScan few = everyNthMatchingPoint(scan, 7);
  GridMap shifted(0.05);  // the same walls 0.4 m further east: every window differs from f.map's
  {
    sim::SimOptions so = f.so;
    const auto log = sim::simulate(f.plan, {{2, 2.8, 0}, {9, 2.8, 0}}, so);
    for (std::size_t i = 0; i < log.records.size(); ++i) {
      const auto ps = prepareScan(log.records[i].scan, f.bo, shifted.resolution());
      const auto& t = log.truth[i];
      shifted.insertScan({t.x + 0.4, t.y, t.phi}, ps.sensor, ps.map_beams, MapUpdateOptions{});
    }
  }
  ScanMatcherOptions o;
  std::uint64_t state = 7;
  auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  // Scores `n` poses spread by `r` around (x, y) with a scorer and with scoreScan; returns how many poses differ.
  auto check = [&](ScanScorer& scorer, const GridMap& map, const PreparedScan& s, double r, int n) {
    int differing = 0;
    for (int i = 0; i < n; ++i) {
      const Pose2 x{6.3 + r * (uniform() - 0.5), 2.8 + r * (uniform() - 0.5), 0.05 + 0.3 * (uniform() - 0.5)};
      const ScanScore a = scoreScan(map, x, s, o), b = scorer.score(x);
      differing += a.matched != b.matched || a.log_likelihood != b.log_likelihood;
    }
    return differing;
  };
  {
    ScanScorer wide(f.map, scan, o);  // poses over 6 m: thousands of windows, the table grows
    EXPECT_EQ(check(wide, f.map, scan, 6.0, 3000), 0);
  }
  for (int round = 0; round < 3; ++round) {
    // Round 1 swaps the two scorers' scans: each gets back tables last used with the other scan.
    const PreparedScan& outer_scan = round == 1 ? few : scan;
    const PreparedScan& inner_scan = round == 1 ? scan : few;
    ScanScorer outer(shifted, outer_scan, o);
    EXPECT_EQ(check(outer, shifted, outer_scan, 0.3, 200), 0) << round;
    {
      ScanScorer inner(f.map, inner_scan, o);
      EXPECT_EQ(check(inner, f.map, inner_scan, 0.3, 200), 0) << round;
    }
    EXPECT_EQ(check(outer, shifted, outer_scan, 0.3, 200), 0) << round;
  }
}

TEST(ScanMatcher, ScoreAboveGivesUpOnlyBelowItsBound) {
  // scoreAbove (the hill climb's early exit) returns nothing exactly when the full score is <= the bound, and
  // otherwise exactly score(x): the climb's decisions are those of the full evaluation.
  Fixture f;
  const auto scan = f.scanAt({6.3, 2.8, 0.05});
  ScanMatcherOptions o;
  ScanScorer scorer(f.map, scan, o), reference(f.map, scan, o);
  std::uint64_t state = 99;
  auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  int stopped = 0, kept = 0;
  for (int i = 0; i < 400; ++i) {
    const Pose2 x{6.3 + 0.2 * (uniform() - 0.5), 2.8 + 0.2 * (uniform() - 0.5), 0.05 + 0.1 * (uniform() - 0.5)};
    const ScanScore full = reference.score(x);
    // Bounds below, at and above the full score (at: a tie cannot win the climb's strict comparison).
    const double bound = i % 3 == 0 ? full.log_likelihood : full.log_likelihood + 4.0 * (uniform() - 0.5);
    const std::optional<ScanScore> s = scorer.scoreAbove(x, bound);
    if (full.log_likelihood <= bound) {
      EXPECT_FALSE(s.has_value()) << i;
      ++stopped;
    } else {
      ASSERT_TRUE(s.has_value()) << i;
      EXPECT_EQ(s->log_likelihood, full.log_likelihood) << i;  // exactly
      EXPECT_EQ(s->matched, full.matched) << i;
      ++kept;
    }
  }
  EXPECT_GT(stopped, 100);
  EXPECT_GT(kept, 100);
}

TEST(ScanMatcher, CachedScorerAroundTheOrigin) {
  // End points in the cells around (0, 0), including (-1, -1), whose packed key has all bits set.
  GridMap map(0.05);
  std::vector<MapBeam> beams;
  for (double ex : {-0.075, -0.025, 0.025})
    for (double ey : {-0.075, -0.025, 0.025}) beams.push_back({ex - 0.6, ey - 0.6, true});
  for (int i = 0; i < 3; ++i) map.insertScan({0.6, 0.6, 0.0}, {}, beams, MapUpdateOptions{});
  ASSERT_GT(map.cell(-1, -1)->hits, 0u);
  PreparedScan scan;
  for (double e : {-0.03, -0.01, 0.02}) {
    scan.ex.push_back(e);
    scan.ey.push_back(-0.02);
    scan.fx.push_back(e);
    scan.fy.push_back(-0.02);
  }
  ScanMatcherOptions o;
  ScanScorer scorer(map, scan, o);
  for (const Pose2 x : {Pose2{0, 0, 0}, Pose2{-0.01, 0.005, 0.01}, Pose2{0, 0, 0}}) {
    const ScanScore a = scoreScan(map, x, scan, o), b = scorer.score(x);
    EXPECT_EQ(a.matched, 3);
    EXPECT_EQ(a.matched, b.matched);
    EXPECT_EQ(a.log_likelihood, b.log_likelihood);
  }
}

TEST(ScanMatcher, RecoversKnownOffsetsWithSubCellAccuracy) {
  Fixture f;
  ScanMatcherOptions o;
  const Pose2 truths[] = {{6.3, 2.8, 0.0}, {4.1, 2.9, 0.1}, {8.2, 2.7, -0.08}, {2.1, 4.5, -1.4}};
  const Pose2 offsets[] = {{0.12, -0.07, 0.04}, {-0.1, 0.1, -0.05}, {0.05, 0.13, 0.06}, {-0.13, -0.02, -0.03}};
  double sum_xy = 0, sum_th = 0, evals = 0;
  int n = 0;
  for (const auto& t : truths)
    for (const auto& d : offsets) {
      const auto scan = f.scanAt(t);
      const MatchResult r = matchScan(f.map, {t.x + d.x, t.y + d.y, t.theta + d.theta}, scan, o);
      ASSERT_TRUE(r.ok);
      const double exy = std::hypot(r.pose.x - t.x, r.pose.y - t.y), eth = std::abs(wrapAngle(r.pose.theta - t.theta));
      evals += r.evaluations;
      EXPECT_LT(exy, 0.02) << t.x << "," << t.y << " offset " << d.x << "," << d.y;
      EXPECT_LT(eth, 0.01);
      sum_xy += exy;
      sum_th += eth;
      ++n;
    }
  // Sub-cell on average: well under a quarter of the 5 cm cell.
  EXPECT_LT(sum_xy / n, 0.01);
  EXPECT_LT(sum_th / n, 0.004);
  std::printf("mean error %.4f m %.4f rad over %d matches, %.1f evaluations\n", sum_xy / n, sum_th / n, n, evals / n);
}

TEST(ScanMatcher, CoarseToFineRecoversTheSameOffsets) {
  // The first levels on every 4th beam, the finer ones on all: same accuracy as the full-beam climb.
  Fixture f;
  ScanMatcherOptions full, c2f;
  c2f.coarse_levels = 3;
  c2f.coarse_beam_step = 4;
  const Pose2 truths[] = {{6.3, 2.8, 0.0}, {4.1, 2.9, 0.1}, {8.2, 2.7, -0.08}, {2.1, 4.5, -1.4}};
  const Pose2 offsets[] = {{0.12, -0.07, 0.04}, {-0.1, 0.1, -0.05}, {0.05, 0.13, 0.06}, {-0.13, -0.02, -0.03}};
  double sum_xy = 0, sum_th = 0, sum_full = 0;
  int n = 0;
  for (const auto& t : truths)
    for (const auto& d : offsets) {
      const auto scan = f.scanAt(t);
      const Pose2 start{t.x + d.x, t.y + d.y, t.theta + d.theta};
      const MatchResult r = matchScan(f.map, start, scan, c2f);
      const MatchResult rf = matchScan(f.map, start, scan, full);
      ASSERT_TRUE(r.ok);
      const double exy = std::hypot(r.pose.x - t.x, r.pose.y - t.y);
      EXPECT_LT(exy, 0.02) << t.x << "," << t.y << " offset " << d.x << "," << d.y;
      EXPECT_LT(std::abs(wrapAngle(r.pose.theta - t.theta)), 0.01);
      sum_xy += exy;
      sum_th += std::abs(wrapAngle(r.pose.theta - t.theta));
      sum_full += std::hypot(rf.pose.x - t.x, rf.pose.y - t.y);
      ++n;
    }
  EXPECT_LT(sum_xy / n, 0.01);
  EXPECT_LT(sum_th / n, 0.004);
  EXPECT_LT(sum_xy / n, sum_full / n + 0.003);
}

TEST(ScanMatcher, FailsOnAnEmptyMap) {
  Fixture f;
  GridMap empty(0.05);
  const auto scan = f.scanAt({6.3, 2.8, 0});
  const MatchResult r = matchScan(empty, {6.3, 2.8, 0}, scan, ScanMatcherOptions{});
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.score.matched, 0);
}

TEST(PreparedScan, ClassifiesReturnsNoReturnsAndNaN) {
  LaserScan s;
  s.start_angle = 0;
  s.angle_increment = 0.1;
  s.max_range = 80;
  s.ranges = {2.0f, 81.8f, std::nanf(""), 50.0f, 0.0f, std::numeric_limits<float>::infinity()};
  s.valid = {1, 0, 0, 1, 0, 0};
  BeamOptions o;
  o.max_usable_range = 30;
  o.no_return_range = 5;
  PreparedScan p = prepareScan(s, o, 0.05);
  ASSERT_EQ(p.map_beams.size(), 4u);  // NaN and 0 carry no information
  EXPECT_TRUE(p.map_beams[0].hit);
  EXPECT_FALSE(p.map_beams[1].hit);  // no return: free up to 5 m
  EXPECT_NEAR(std::hypot(p.map_beams[1].ex, p.map_beams[1].ey), 5.0, 1e-9);
  EXPECT_FALSE(p.map_beams[2].hit);  // 50 m return beyond the usable range: free up to 30 m
  EXPECT_NEAR(std::hypot(p.map_beams[2].ex, p.map_beams[2].ey), 30.0, 1e-9);
  EXPECT_FALSE(p.map_beams[3].hit);  // +inf
  EXPECT_EQ(p.size(), 1u);           // only the hit is matched
  o.clear_no_return = false;
  EXPECT_EQ(prepareScan(s, o, 0.05).map_beams.size(), 2u);
}

TEST(ScanMatcher, ExperimentalGaussNewtonRecoversSmallOffsets) {
  Fixture f;
  ScanMatcherOptions o;
  o.method = MatchMethod::GaussNewton;
  const Pose2 t{6.3, 2.8, 0.0};
  const auto scan = f.scanAt(t);
  for (const Pose2 d : {Pose2{0.03, -0.02, 0.01}, Pose2{-0.02, 0.03, -0.015}, Pose2{0.0, 0.04, 0.02}}) {
    const MatchResult r = matchScan(f.map, {t.x + d.x, t.y + d.y, t.theta + d.theta}, scan, o);
    ASSERT_TRUE(r.ok);
    EXPECT_LT(std::hypot(r.pose.x - t.x, r.pose.y - t.y), 0.01);
    EXPECT_LT(std::abs(wrapAngle(r.pose.theta - t.theta)), 0.005);
  }
}
