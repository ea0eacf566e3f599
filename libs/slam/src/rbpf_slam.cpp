#include "gridtopo/slam/rbpf_slam.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <unordered_set>

#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/proposal.h"
#include "gridtopo/slam/resampling.h"
#include "gridtopo/slam/scan_matcher.h"

namespace gridtopo::slam {

namespace {
Pose2 toPose(const mrpt::math::TPose2D& p) { return {p.x, p.y, p.phi}; }
constexpr std::uint64_t kPurposeParticle = 1, kPurposeResample = 2, kPurposeStart = 3, kPurposeScale = 4;

/// The minimum sigmas on the proposal's diagonal (numerical safety).
void addFloor(GaussianProposal& g, const ProposalOptions& p) {
  g.cov(0, 0) += p.min_sigma_xy * p.min_sigma_xy;
  g.cov(1, 1) += p.min_sigma_xy * p.min_sigma_xy;
  g.cov(2, 2) += p.min_sigma_theta * p.min_sigma_theta;
}
}  // namespace

ProposalPlan planProposal(const GridMap& map, const Pose2& prev, const Pose2& u, bool has_odometry,
                          const PreparedScan& scan, const SlamOptions& o, const OdometryMotionModel& motion,
                          const Pose2* start) {
  ProposalPlan plan;
  plan.type = o.proposal.type;
  if (o.proposal.type == ProposalType::Odometry) return plan;
  if (o.proposal.type == ProposalType::ModeOnly) {
    plan.matched = true;  // matched per particle in drawFromProposal (from its own motion sample)
    return plan;
  }
  const double inv_gain = 1.0 / o.likelihood_gain;
  const Pose2 predicted = start ? *start : compose(prev, u);
  MatchPrior prior;
  prior.likelihood_scale = inv_gain;
  prior.log_prior = [&](const Pose2& x) { return motion.logDensity(x, prev, u, has_odometry); };
  ScanScorer scorer(map, scan, o.matcher);
  const MatchResult m = matchScan(scorer, predicted, o.matcher.use_motion_prior ? &prior : nullptr);
  plan.evaluations = m.evaluations;
  if (!m.ok) return plan;
  plan.matched = true;
  // Informed proposal: ln p(z|m,x_j) at K poses on a grid around the mode.
  const int n = o.proposal.points_per_axis;
  const double half = 0.5 * (n - 1);
  std::vector<Pose2> xs;
  std::vector<double> log_lik;
  xs.reserve(static_cast<std::size_t>(n) * n * n);
  log_lik.reserve(xs.capacity());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Pose2 x{m.pose.x + (i - half) * o.proposal.delta_xy, m.pose.y + (j - half) * o.proposal.delta_xy,
                      wrapAngle(m.pose.theta + (k - half) * o.proposal.delta_theta)};
        xs.push_back(x);
        log_lik.push_back((i == n / 2 && j == n / 2 && k == n / 2 && (n % 2) == 1) ? m.score.log_likelihood
                                                                                    : scorer.score(x).log_likelihood);
      }
  plan.evaluations += static_cast<int>(xs.size()) - (n % 2);
  if (o.proposal.fit == ProposalFit::Quadratic) {
    // Laplace's approximation of τ, centred on the mode the hill climb found (to a millimetre; the fit's own peak
    // is smoothed over the grid and biased by truncated beams), with the curvature fitted over the K poses.
    auto fitAtMode = [&](double min_curvature) {
      LocalQuadratic q =
          fitLocalQuadratic(xs, log_lik, m.pose, o.proposal.delta_xy, o.proposal.delta_theta, min_curvature);
      q.b.setZero();
      q.c = m.score.log_likelihood;
      return q;
    };
    // The shape keeps only the directions the scan clearly observes.
    const LocalQuadratic observed = fitAtMode(o.proposal.min_curvature);
    if (observed.ok) {
      const OdometryMotionModel::Sigmas sg = motion.sigmas(u, has_odometry);
      const Pose2 prediction = compose(prev, u);  // the motion prior's mean (the search may start elsewhere)
      // The weight: the softened likelihood at the mode, or the integral of the softened target with every concave
      // direction (the best local model of the integrand). The shape: the likelihood of beams that register to
      // beam_sigma, times the motion prior.
      plan.log_weight_increment =
          o.proposal.weight == ProposalWeight::Mode
              ? m.score.log_likelihood * inv_gain
              : informedGaussian(fitAtMode(0.0), inv_gain, m.pose, prediction, sg.xy, sg.theta).log_eta;
      const double shape_scale = std::pow(o.matcher.sigma / o.proposal.beam_sigma, 2);
      plan.gaussian = informedGaussian(observed, shape_scale, m.pose, prediction, sg.xy, sg.theta);
      addFloor(plan.gaussian, o.proposal);
      return plan;
    }
  }
  // The paper's moments: τ_j = p(z|m,x_j)^(1/gain)·p(x_j|x_{t-1},u).
  std::vector<double> log_tau(xs.size());
  for (std::size_t j = 0; j < xs.size(); ++j)
    log_tau[j] = log_lik[j] * inv_gain + motion.logDensity(xs[j], prev, u, has_odometry);
  plan.gaussian = fitProposal(xs, log_tau, m.pose);
  addFloor(plan.gaussian, o.proposal);
  // The weight factor approximates the integral ∫ p(z|m,x)^(1/gain) p(x|x_{t-1},u) dx, so that it is
  // commensurate with the weight of a particle whose matching failed (odometry proposal: p(z|m,x)^(1/gain) at a
  // motion sample, a one-sample Monte-Carlo estimate of the same integral). η = Σ τ_j alone lacks the grid
  // volume Δx·Δy·Δθ, and such particles would be discarded in every mixed step.
  plan.log_weight_increment =
      o.proposal.laplace_weight
          ? logIntegralOnGrid(xs, log_tau, m.pose, o.proposal.delta_xy, o.proposal.delta_theta)
          : logSumExp(log_tau) + 2.0 * std::log(o.proposal.delta_xy) + std::log(o.proposal.delta_theta);
  return plan;
}

double drawFromProposal(const ProposalPlan& plan, const GridMap& map, const Pose2& prev, const Pose2& u,
                        bool has_odometry, const PreparedScan& scan, const SlamOptions& o,
                        const OdometryMotionModel& motion, Rng& rng, Pose2& out_pose) {
  if (plan.type == ProposalType::ModeOnly) {
    // GMapping: draw from the motion model, climb to the likelihood mode from there, weight p(z|m,x̂).
    const Pose2 start = motion.sample(prev, u, rng, has_odometry);
    const MatchResult m = matchScan(map, start, scan, o.matcher);
    if (m.ok) {
      out_pose = m.pose;
      return m.score.log_likelihood / o.likelihood_gain;
    }
    out_pose = start;
    return scoreScan(map, start, scan, o.matcher).log_likelihood / o.likelihood_gain;
  }
  if (!plan.matched) {
    // Odometry proposal (also the fallback when matching failed): sample the motion model, weight by p(z|m,x).
    out_pose = motion.sample(prev, u, rng, has_odometry);
    return scoreScan(map, out_pose, scan, o.matcher).log_likelihood / o.likelihood_gain;
  }
  out_pose = plan.type == ProposalType::Informed ? sampleGaussian(plan.gaussian, rng) : plan.gaussian.mean;
  return plan.log_weight_increment;
}

RbpfSlam::RbpfSlam(const SlamOptions& options)
    : o_(options), motion_(options.motion), prior_map_(options.resolution) {
  o_.validate();
  pool_ = std::make_unique<ThreadPool>(o_.threads);
}

void RbpfSlam::setInitialPose(const Pose2& pose) {
  if (initialized_) throw std::logic_error("RbpfSlam::setInitialPose: the filter has already started");
  initial_pose_ = pose;
  has_initial_pose_ = true;
}

void RbpfSlam::insertKnownScan(const Pose2& robot_pose, const io::LaserScan& scan) {
  if (initialized_) throw std::logic_error("RbpfSlam::insertKnownScan: the filter has already started");
  const PreparedScan ps = prepareScan(scan, o_.beams, o_.resolution);
  prior_map_.insertScan(robot_pose, ps.sensor, ps.map_beams, o_.map);
}

bool RbpfSlam::shouldProcess(const io::ScanRecord& r) const {
  if (!initialized_) return true;
  const ScanInfo& last = scans_[last_processed_];
  if (!r.has_odometry || !last.has_odometry) {
    return r.scan.timestamp - last.timestamp >= o_.no_odometry_period;
  }
  if (acc_linear_ >= o_.linear_update || acc_angular_ >= o_.angular_update) return true;
  if (o_.temporal_update >= 0.0 && r.scan.timestamp - last.timestamp >= o_.temporal_update) return true;
  return false;
}

bool RbpfSlam::processScan(const io::ScanRecord& record) {
  const std::size_t index = scans_.size();
  if (index > 0 && record.has_odometry && scans_.back().has_odometry) {
    const Pose2 d = relative(scans_.back().odometry, toPose(record.odometry));
    acc_linear_ += std::hypot(d.x, d.y);
    acc_angular_ += std::abs(d.theta);
  }
  const bool process = shouldProcess(record);
  scans_.push_back({record.scan.timestamp, record.has_odometry, toPose(record.odometry)});
  if (!process) return false;

  const auto t0 = std::chrono::steady_clock::now();
  const PreparedScan scan = prepareScan(record.scan, o_.beams, o_.resolution);
  StepStats st;
  st.step = stats_.size();
  st.scan_index = index;
  st.timestamp = record.scan.timestamp;
  const std::size_t n = static_cast<std::size_t>(o_.particles);

  if (!initialized_) {
    // The map frame starts at the first odometry pose (identity without odometry).
    const Pose2 start =
        has_initial_pose_ ? initial_pose_ : (record.has_odometry ? toPose(record.odometry) : Pose2{});
    GridMap map = prior_map_;
    map.insertScan(start, scan.sensor, scan.map_beams, o_.map);
    auto node = std::make_shared<const TrajectoryNode>(start, index, nullptr);
    particles_.assign(n, Particle{start, 0.0, 0.0, node, map});
    // Odometry calibration in the state: every particle draws its own scale of the odometry translation.
    if (o_.motion.scale_sigma > 0.0) {
      for (std::size_t i = 0; i < n; ++i) {
        Rng rng(o_.seed, 0, i, kPurposeScale);
        particles_[i].odometry_scale = 1.0 + rng.gaussian(o_.motion.scale_sigma);
      }
    }
    initialized_ = true;
    st.neff = static_cast<double>(n);
  } else {
    const ScanInfo& last = scans_[last_processed_];
    const bool has_odo = record.has_odometry && last.has_odometry;
    const Pose2 u_odo = has_odo ? relative(last.odometry, toPose(record.odometry)) : Pose2{};
    // Without odometry: a constant-velocity prediction from each particle's last two poses, scaled by time.
    const std::size_t step = stats_.size();
    if (has_odo && o_.motion.scale_walk_sigma > 0.0) {
      // The scale's random walk: variance scale_walk_sigma² per metre of odometry translation.
      const double sd = o_.motion.scale_walk_sigma * std::sqrt(std::hypot(u_odo.x, u_odo.y));
      for (std::size_t i = 0; i < n; ++i) {
        Rng rng(o_.seed, step, i, kPurposeScale);
        particles_[i].odometry_scale += rng.gaussian(sd);
      }
    }
    auto incrementFor = [&](const Particle& p) -> Pose2 {
      if (has_odo) return {p.odometry_scale * u_odo.x, p.odometry_scale * u_odo.y, u_odo.theta};
      if (!p.node || !p.node->parent) return u_odo;
      const TrajectoryNode& a = *p.node->parent;
      const TrajectoryNode& b = *p.node;
      const double dt_prev = scans_[b.scan_index].timestamp - scans_[a.scan_index].timestamp;
      const double dt_now = record.scan.timestamp - scans_[b.scan_index].timestamp;
      if (!(dt_prev > 1e-6) || !(dt_now >= 0.0)) return Pose2{};
      const double k = std::min(3.0, dt_now / dt_prev);
      const Pose2 d = relative(a.pose, b.pose);
      return {k * d.x, k * d.y, k * d.theta};
    };
    // Particles duplicated by resampling (same trajectory node, hence same map and pose, and same odometry
    // scale) share one plan, unless each particle starts its search from its own motion sample
    // (proposal_start_spread; not without odometry: the wide no-odometry prior is not a noise model around a
    // measured increment).
    const bool own_start = o_.proposal.type == ProposalType::Informed && o_.proposal.start_spread > 0.0 && has_odo;
    std::vector<std::size_t> group_of(n), leaders;
    if (own_start) {
      for (std::size_t i = 0; i < n; ++i) {
        group_of[i] = i;
        leaders.push_back(i);
      }
    } else {
      std::map<std::pair<const TrajectoryNode*, double>, std::size_t> first;
      for (std::size_t i = 0; i < n; ++i) {
        auto it = first.emplace(std::make_pair(particles_[i].node.get(), particles_[i].odometry_scale), leaders.size());
        if (it.second) leaders.push_back(i);
        group_of[i] = it.first->second;
      }
    }
    std::vector<ProposalPlan> plans(leaders.size());
    pool_->parallelFor(leaders.size(), [&](std::size_t g) {
      const Particle& p = particles_[leaders[g]];
      const Pose2 u = incrementFor(p);
      if (own_start) {
        Rng rng(o_.seed, step, leaders[g], kPurposeStart);
        const OdometryMotionModel::Sigmas sg = motion_.sigmas(u, has_odo);
        const double k = o_.proposal.start_spread;
        const Pose2 start = compose(p.pose, {u.x + k * rng.gaussian(sg.xy), u.y + k * rng.gaussian(sg.xy),
                                             u.theta + k * rng.gaussian(sg.theta)});
        plans[g] = planProposal(p.map, p.pose, u, has_odo, scan, o_, motion_, &start);
      } else {
        plans[g] = planProposal(p.map, p.pose, u, has_odo, scan, o_, motion_);
      }
    });
    std::vector<int> extra_evals(n, 0);
    pool_->parallelFor(n, [&](std::size_t i) {
      Particle& p = particles_[i];
      const ProposalPlan& plan = plans[group_of[i]];
      Rng rng(o_.seed, step, i, kPurposeParticle);
      Pose2 x;
      const double dw = drawFromProposal(plan, p.map, p.pose, incrementFor(p), has_odo, scan, o_, motion_, rng, x);
      extra_evals[i] = plan.matched ? 0 : 1;
      p.log_weight += dw;
      p.log_weight_total += dw;
      p.pose = x;
      p.map.insertScan(x, scan.sensor, scan.map_beams, o_.map);
      // The reported pose: the informed proposal's mean (the sample minus its own noise), else the sample.
      const bool report_mean = o_.proposal.report_mean && plan.type == ProposalType::Informed && plan.matched;
      p.node = std::make_shared<const TrajectoryNode>(x, report_mean ? plan.gaussian.mean : x, index, p.node);
    });
    for (std::size_t i = 0; i < n; ++i) {
      st.failed_matches += !plans[group_of[i]].matched;
      st.evaluations += extra_evals[i];
    }
    for (const auto& pl : plans) st.evaluations += pl.evaluations;
    st.evaluations /= static_cast<double>(n);
    std::vector<double> lw(n);
    for (std::size_t i = 0; i < n; ++i) lw[i] = particles_[i].log_weight;
    const std::vector<double> w = normalizedWeights(lw);
    st.neff = effectiveSampleSize(w);
    // Keep the relative weights bounded: subtract the maximum (a common factor).
    const double mx = *std::max_element(lw.begin(), lw.end());
    for (auto& p : particles_) p.log_weight -= mx;
    if (st.neff < o_.resample_threshold * static_cast<double>(n)) {
      resample(w);
      st.resampled = true;
    }
  }
  acc_linear_ = acc_angular_ = 0.0;
  last_processed_ = index;
  st.particles = static_cast<int>(n);
  // Counting distinct tiles hashes every tile pointer of every particle: done every 20 steps only.
  if (stats_.empty() || stats_.size() % 20 == 0) {
    last_unique_tiles_ = uniqueTiles(&last_map_bytes_);
  }
  st.unique_tiles = last_unique_tiles_;
  st.map_bytes = last_map_bytes_;
  st.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  stats_.push_back(st);
  return true;
}

void RbpfSlam::resample(const std::vector<double>& w) {
  Rng rng(o_.seed, stats_.size(), 0, kPurposeResample);
  const std::vector<std::size_t> keep = lowVarianceResample(w, rng);
  // The last copy of a particle takes its state over (moved, not copied): copying every survivor while the old
  // set still lives would hold two sets of tile-pointer arrays (the hospital's map spans 10^5 tile slots per
  // particle) at once. Copies share the map tiles and the trajectory.
  std::vector<std::size_t> last_use(particles_.size(), keep.size());
  for (std::size_t k = 0; k < keep.size(); ++k) last_use[keep[k]] = k;
  std::vector<Particle> next;
  next.reserve(keep.size());
  for (std::size_t k = 0; k < keep.size(); ++k) {
    const std::size_t i = keep[k];
    if (last_use[i] == k) {
      next.push_back(std::move(particles_[i]));
    } else {
      next.push_back(particles_[i]);
    }
    next.back().log_weight = 0.0;
  }
  particles_ = std::move(next);
}

std::size_t RbpfSlam::bestParticleIndex() const {
  std::size_t best = 0;
  for (std::size_t i = 1; i < particles_.size(); ++i)
    if (particles_[i].log_weight_total > particles_[best].log_weight_total) best = i;
  return best;
}

std::size_t RbpfSlam::uniqueTiles(std::size_t* bytes) const {
  std::unordered_set<const void*> seen_blocks, seen, seen_hits;
  std::size_t b = 0;
  for (const auto& p : particles_) {
    b += p.map.blocks().size() * sizeof(CowPtr<GridMap::Block>);
    for (const auto& blk : p.map.blocks()) {
      if (!blk || !seen_blocks.insert(blk.get()).second) continue;
      b += sizeof(GridMap::Block);
      for (const auto& t : blk->tiles)
        if (t && seen.insert(t.get()).second) {
          b += sizeof(GridMap::Tile);
          if (t->hits && seen_hits.insert(t->hits.get()).second) b += sizeof(GridMap::HitMeans);
        }
    }
  }
  if (bytes) *bytes = b;
  return seen.size();
}

std::vector<io::TimedPose> RbpfSlam::trajectory() const {
  std::vector<io::TimedPose> out(scans_.size());
  if (scans_.empty() || particles_.empty()) return out;
  const auto path = pathOf(bestParticle().node);
  // The odometry between processed scans, scaled by the best particle's (current) odometry scale.
  const double scale = bestParticle().odometry_scale;
  // processed scan index -> pose
  std::vector<long> proc_at(scans_.size(), -1);
  for (std::size_t k = 0; k < path.size(); ++k) proc_at[path[k]->scan_index] = static_cast<long>(k);
  auto fromAnchor = [&](std::size_t k, std::size_t i) {
    const ScanInfo& a = scans_[path[k]->scan_index];
    const ScanInfo& b = scans_[i];
    if (a.has_odometry && b.has_odometry) {
      const Pose2 d = relative(a.odometry, b.odometry);
      return compose(path[k]->estimate, {scale * d.x, scale * d.y, d.theta});
    }
    return path[k]->estimate;
  };
  std::size_t prev = 0;  // index into path
  for (std::size_t i = 0; i < scans_.size(); ++i) {
    out[i].timestamp = scans_[i].timestamp;
    Pose2 p;
    if (proc_at[i] >= 0) {
      prev = static_cast<std::size_t>(proc_at[i]);
      p = path[prev]->estimate;
    } else if (prev + 1 < path.size()) {
      // Blend the odometry extrapolations from the previous and the next processed scan.
      const std::size_t i0 = path[prev]->scan_index, i1 = path[prev + 1]->scan_index;
      const double f = static_cast<double>(i - i0) / static_cast<double>(i1 - i0);
      const Pose2 a = fromAnchor(prev, i), b = fromAnchor(prev + 1, i);
      p = {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), wrapAngle(a.theta + f * wrapAngle(b.theta - a.theta))};
    } else {
      p = fromAnchor(prev, i);
    }
    out[i].pose = {p.x, p.y, p.theta};
  }
  return out;
}

}  // namespace gridtopo::slam
