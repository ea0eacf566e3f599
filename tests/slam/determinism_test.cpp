#include <gtest/gtest.h>

#include <cstring>

#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/rbpf_slam.h"

using namespace gridtopo;

namespace {
struct RunResult {
  std::vector<TimedPose> traj;
  std::vector<double> neff;
  std::vector<std::vector<float>> maps;  // log-odds of every particle map over a fixed window
};
RunResult run(const sim::SimLog& log, int threads, std::uint64_t seed, slam::ProposalType type,
              double start_spread = 0.0, double scale_sigma = 0.0) {
  slam::SlamOptions o;
  o.proposal.start_spread = start_spread;
  o.motion.scale_sigma = scale_sigma;
  o.motion.scale_walk_sigma = 0.5 * scale_sigma;
  o.particles = 12;
  o.threads = threads;
  o.seed = seed;
  o.proposal.type = type;
  o.linear_update = 0.3;
  slam::RbpfSlam f(o);
  for (const auto& r : log.records) f.processScan(r);
  RunResult out;
  out.traj = f.trajectory();
  for (const auto& s : f.stats()) out.neff.push_back(s.neff);
  for (const auto& p : f.particles()) {
    std::vector<float> v;
    for (int y = -20; y < 260; y += 3)
      for (int x = -20; x < 420; x += 3) {
        const auto c = p.map.cell(x, y);
        v.push_back(c ? c->log_odds : -99.0f);
      }
    out.maps.push_back(std::move(v));
  }
  return out;
}
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
}  // namespace

TEST(Determinism, BitIdenticalWhateverTheThreadCount) {
  const auto plan = sim::FloorPlan::officeLoop();
  sim::SimOptions so;
  auto wp = sim::officeLoopWaypoints(1);
  wp.resize(4);
  const auto log = sim::simulate(plan, wp, so);
  struct Case {
    slam::ProposalType type;
    double start_spread;
    double scale_sigma;
  };
  for (const Case k : {Case{slam::ProposalType::Informed, 0.0, 0.0}, Case{slam::ProposalType::Informed, 1.0, 0.0},
                       Case{slam::ProposalType::Informed, 0.0, 0.02},
                       Case{slam::ProposalType::Odometry, 0.0, 0.0}}) {
    const auto type = k.type;
    const RunResult a = run(log, 1, 5, type, k.start_spread, k.scale_sigma),
                    b = run(log, 2, 5, type, k.start_spread, k.scale_sigma),
                    c = run(log, 4, 5, type, k.start_spread, k.scale_sigma);
    ASSERT_EQ(a.traj.size(), b.traj.size());
    for (std::size_t i = 0; i < a.traj.size(); ++i) {
      for (const RunResult* r : {&b, &c}) {
        ASSERT_TRUE(sameBits(a.traj[i].pose.x, r->traj[i].pose.x)) << i;
        ASSERT_TRUE(sameBits(a.traj[i].pose.y, r->traj[i].pose.y)) << i;
        ASSERT_TRUE(sameBits(a.traj[i].pose.phi, r->traj[i].pose.phi)) << i;
      }
    }
    ASSERT_EQ(a.neff.size(), c.neff.size());
    for (std::size_t i = 0; i < a.neff.size(); ++i) EXPECT_TRUE(sameBits(a.neff[i], c.neff[i]));
    EXPECT_EQ(a.maps, b.maps);
    EXPECT_EQ(a.maps, c.maps);
    // A different seed gives a different result (the seed is really used).
    const RunResult d = run(log, 2, 6, type, k.start_spread, k.scale_sigma);
    bool differs = false;
    for (std::size_t i = 0; i < a.traj.size(); ++i) differs |= a.traj[i].pose.x != d.traj[i].pose.x;
    EXPECT_TRUE(differs);
  }
}
