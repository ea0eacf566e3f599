// The observation likelihood along a featureless corridor, in a map built from the true poses: the scans observe
// the lateral position and the heading, not the position along the axis, so ln p(z|m,x) must be flat along the
// axis. With GMapping's point-to-hit-mean distances and every hit matched it is not: it peaks where the scan
// repeats the previous scan's geometry (the previous pose: zero motion), which made the filter fall behind the truth
// in long corridors (corridor_loop_test). See doc/slam.md, "Long corridors".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/scan_matcher.h"
#include "gridtopo/slam/slam_options.h"

using namespace gridtopo;

namespace {

constexpr double kStep = 0.3;  // m between scans

struct Profile {
  std::vector<double> along;  // ln p at truth + (0.01 k, 0, 0), k = -60..60
  double lateral_drop = 0;    // ln p(truth) - max ln p(truth ± 0.1 m across)
};

// A 2 m wide, 60 m long corridor (walls only along it), a 12 m laser, scans every 0.3 m: the map is built from the
// true poses of the first 80 scans, scan 80 (24 m from the start, far from both ends) is scored around its true
// pose.
Profile corridorProfile(const slam::SlamOptions& o) {
  const sim::FloorPlan plan = sim::FloorPlan::straightCorridor(60, 2);
  sim::SimOptions so;
  so.max_range = 12;
  so.scan_spacing = kStep;
  so.seed = 1;
  const auto log = sim::simulate(plan, {{1, 1, 0}, {50, 1, 0}}, so);
  slam::GridMap map(o.resolution);
  const std::size_t at = 80;
  for (std::size_t i = 0; i < at; ++i) {
    const auto ps = slam::prepareScan(log.records[i].scan, o.beams, o.resolution);
    const auto& t = log.truth[i];
    map.insertScan({t.x, t.y, t.phi}, ps.sensor, ps.map_beams, o.map);
  }
  const auto ps = slam::prepareScan(log.records[at].scan, o.beams, o.resolution);
  const auto& t = log.truth[at];
  slam::ScanScorer scorer(map, ps, o.matcher);
  Profile p;
  for (int k = -60; k <= 60; ++k) p.along.push_back(scorer.score({t.x + 0.01 * k, t.y, t.phi}).log_likelihood);
  const double at_truth = scorer.score({t.x, t.y, t.phi}).log_likelihood;
  p.lateral_drop = at_truth - std::max(scorer.score({t.x, t.y + 0.1, t.phi}).log_likelihood,
                                       scorer.score({t.x, t.y - 0.1, t.phi}).log_likelihood);
  return p;
}

slam::SlamOptions pointResidual() {
  slam::SlamOptions o;
  o.matcher.residual = slam::MatchResidual::Point;
  o.beams.matching_min_incidence = 0;
  o.matcher.occupied_log_odds = 0;
  return o;
}

// Point-to-plane distances, grazing beams (< 20 degrees) not matched, cells with hits matchable down to log-odds -2.
slam::SlamOptions planeResidual() {
  slam::SlamOptions o;
  o.matcher.residual = slam::MatchResidual::Plane;
  o.beams.matching_min_incidence = 0.35;
  o.matcher.occupied_log_odds = -2;
  return o;
}

}  // namespace

// Values seen: the best offset along the axis is -0.30 m (one scan step back), 7.8 nats above the true pose's.
TEST(CorridorLikelihood, PointDistancesFavourThePreviousPose) {
  const Profile p = corridorProfile(pointResidual());
  const auto best = std::max_element(p.along.begin(), p.along.end()) - p.along.begin();
  const double offset = 0.01 * (static_cast<double>(best) - 60);
  EXPECT_TRUE(std::abs(offset + kStep) < 0.015 || std::abs(offset + 2 * kStep) < 0.015) << offset;
  EXPECT_GT(p.along[static_cast<std::size_t>(best)] - p.along[60], 5.0);
}

// Values seen: the profile spans 0.32 nats over +-0.6 m; 0.1 m across costs 40 nats.
TEST(CorridorLikelihood, PlaneDistancesWithoutGrazingBeamsAreFlatAlongTheAxis) {
  const Profile p = corridorProfile(planeResidual());
  const auto [lo, hi] = std::minmax_element(p.along.begin(), p.along.end());
  EXPECT_LT(*hi - *lo, 1.0);
  EXPECT_GT(p.lateral_drop, 20.0);
  // Without one of the three changes the profile spans (values seen) 1.68 nats (point distances), 6.25 (grazing
  // beams matched), 4.25 (cells with hits matchable only above log-odds 0).
  for (int drop = 0; drop < 3; ++drop) {
    slam::SlamOptions o = planeResidual();
    if (drop == 0) o.matcher.residual = slam::MatchResidual::Point;
    if (drop == 1) o.beams.matching_min_incidence = 0;
    if (drop == 2) o.matcher.occupied_log_odds = 0;
    const Profile q = corridorProfile(o);
    const auto [qlo, qhi] = std::minmax_element(q.along.begin(), q.along.end());
    std::printf("without change %d: %.2f nats\n", drop, *qhi - *qlo);
    EXPECT_GT(*qhi - *qlo, drop == 0 ? 1.3 : 3.0) << "without change " << drop;
  }
}
