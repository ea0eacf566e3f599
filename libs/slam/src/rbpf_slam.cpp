#include "gridtopo/slam/rbpf_slam.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_set>

#include "gridtopo/slam/kld_sampling.h"
#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/proposal.h"
#include "gridtopo/slam/resampling.h"

namespace gridtopo::slam {

namespace {
Pose2 toPose(const mrpt::math::TPose2D& p) { return {p.x, p.y, p.phi}; }
constexpr std::uint64_t kPurposeParticle = 1, kPurposeResample = 2, kPurposeStart = 3, kPurposeScale = 4;
}  // namespace

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

void RbpfSlam::insertKnownScan(const Pose2& robot_pose, const LaserScan& scan) {
  if (initialized_) throw std::logic_error("RbpfSlam::insertKnownScan: the filter has already started");
  const PreparedScan ps = prepareScan(scan, o_.beams, o_.resolution);
  prior_map_.insertScan(robot_pose, ps.sensor, ps.map_beams, o_.map);
}

bool RbpfSlam::shouldProcess(const ScanRecord& r) const {
  if (!initialized_) return true;
  const ScanInfo& last = scans_[last_processed_];
  if (!r.has_odometry || !last.has_odometry) {
    return r.scan.timestamp - last.timestamp >= o_.no_odometry_period;
  }
  if (acc_linear_ >= o_.linear_update || acc_angular_ >= o_.angular_update) return true;
  if (o_.temporal_update >= 0.0 && r.scan.timestamp - last.timestamp >= o_.temporal_update) return true;
  return false;
}

bool RbpfSlam::processScan(const ScanRecord& record) {
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
  last_scan_ = prepareScan(record.scan, o_.beams, o_.resolution);
  const PreparedScan& scan = last_scan_;
  StepStats st;
  st.step = stats_.size();
  st.scan_index = index;
  st.timestamp = record.scan.timestamp;
  if (!initialized_) {
    startParticles(record, scan, index);
    st.particles = static_cast<int>(particles_.size());
    st.neff = static_cast<double>(particles_.size());
  } else {
    // The count this step runs with (the adaptive set changes it only when it resamples).
    const std::size_t n = particles_.size();
    st.particles = static_cast<int>(n);
    // The paper's steps (Grisetti et al. 2007, Table I), in order.
    const Odometry odo = odometrySinceLastStep(record);
    const std::vector<Pose2> u = predictWithOdometry(record, odo);
    const ProposalGroups groups = groupParticles(odo.available);
    const std::vector<ProposalPlan> plans = matchAndFitProposals(groups, u, odo.available, scan);
    std::vector<Pose2> estimates;
    std::vector<char> matched;
    const std::vector<Pose2> poses =
        sampleFromProposals(groups, plans, u, odo.available, scan, st, estimates, matched);
    updateMaps(poses, estimates, matched, scan, index);
    const std::vector<double> w = normaliseWeights();
    st.neff = effectiveSampleSize(w);
    const std::size_t maximum = static_cast<std::size_t>(o_.particles);
    if (growOnFailedMatches(st.failed_matches, n, maximum, o_.kld)) {
      resample(w, maximum);
      st.resampled = true;
    } else if (st.neff < o_.resample_threshold * static_cast<double>(n)) {
      resample(w);
      st.resampled = true;
    }
  }
  acc_linear_ = acc_angular_ = 0.0;
  last_processed_ = index;
  recordStep(st, t0);
  return true;
}

void RbpfSlam::startParticles(const ScanRecord& record, const PreparedScan& scan, std::size_t index) {
  const std::size_t n = static_cast<std::size_t>(o_.particles);
  // The map frame starts at the first odometry pose (identity without odometry).
  const Pose2 start = has_initial_pose_ ? initial_pose_ : (record.has_odometry ? toPose(record.odometry) : Pose2{});
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
}

RbpfSlam::Odometry RbpfSlam::odometrySinceLastStep(const ScanRecord& record) const {
  const ScanInfo& last = scans_[last_processed_];
  Odometry odo;
  odo.available = record.has_odometry && last.has_odometry;
  if (odo.available) odo.u = relative(last.odometry, toPose(record.odometry));
  return odo;
}

std::vector<Pose2> RbpfSlam::predictWithOdometry(const ScanRecord& record, const Odometry& odo) {
  const std::size_t n = particles_.size();
  const std::size_t step = stats_.size();
  if (odo.available && o_.motion.scale_walk_sigma > 0.0) {
    // The scale's random walk: variance scale_walk_sigma² per metre of odometry translation.
    const double sd = o_.motion.scale_walk_sigma * std::sqrt(std::hypot(odo.u.x, odo.u.y));
    for (std::size_t i = 0; i < n; ++i) {
      Rng rng(o_.seed, step, i, kPurposeScale);
      particles_[i].odometry_scale += rng.gaussian(sd);
    }
  }
  // With odometry: the measured increment, its translation scaled by the particle's odometry scale. Without: a
  // constant-velocity prediction from the particle's last two poses, scaled by time.
  std::vector<Pose2> u(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Particle& p = particles_[i];
    if (odo.available) {
      u[i] = {p.odometry_scale * odo.u.x, p.odometry_scale * odo.u.y, odo.u.theta};
      continue;
    }
    u[i] = odo.u;
    if (!p.node || !p.node->parent) continue;
    const TrajectoryNode& a = *p.node->parent;
    const TrajectoryNode& b = *p.node;
    const double dt_prev = scans_[b.scan_index].timestamp - scans_[a.scan_index].timestamp;
    const double dt_now = record.scan.timestamp - scans_[b.scan_index].timestamp;
    if (!(dt_prev > 1e-6) || !(dt_now >= 0.0)) {
      u[i] = Pose2{};
      continue;
    }
    const double k = std::min(3.0, dt_now / dt_prev);
    const Pose2 d = relative(a.pose, b.pose);
    u[i] = {k * d.x, k * d.y, k * d.theta};
  }
  return u;
}

RbpfSlam::ProposalGroups RbpfSlam::groupParticles(bool has_odometry) const {
  const std::size_t n = particles_.size();
  ProposalGroups g;
  // Particles duplicated by resampling (same trajectory node, hence same map and pose, and same odometry scale)
  // share one plan, unless each particle starts its search from its own motion sample (proposal_start_spread; not
  // without odometry: the wide no-odometry prior is not a noise model around a measured increment).
  g.own_start = o_.proposal.type == ProposalType::Informed && o_.proposal.start_spread > 0.0 && has_odometry;
  g.group_of.resize(n);
  if (g.own_start) {
    for (std::size_t i = 0; i < n; ++i) {
      g.group_of[i] = i;
      g.leaders.push_back(i);
    }
    return g;
  }
  std::map<std::pair<const TrajectoryNode*, double>, std::size_t> first;
  for (std::size_t i = 0; i < n; ++i) {
    auto it = first.emplace(std::make_pair(particles_[i].node.get(), particles_[i].odometry_scale), g.leaders.size());
    if (it.second) g.leaders.push_back(i);
    g.group_of[i] = it.first->second;
  }
  return g;
}

std::vector<ProposalPlan> RbpfSlam::matchAndFitProposals(const ProposalGroups& groups, const std::vector<Pose2>& u,
                                                         bool has_odometry, const PreparedScan& scan) {
  const std::size_t step = stats_.size();
  std::vector<ProposalPlan> plans(groups.leaders.size());
  pool_->parallelFor(groups.leaders.size(), [&](std::size_t g) {
    const std::size_t i = groups.leaders[g];
    const Particle& p = particles_[i];
    if (groups.own_start) {
      Rng rng(o_.seed, step, i, kPurposeStart);
      const OdometryMotionModel::Sigmas sg = motion_.sigmas(u[i], has_odometry);
      const double k = o_.proposal.start_spread;
      const Pose2 start = compose(p.pose, {u[i].x + k * rng.gaussian(sg.xy), u[i].y + k * rng.gaussian(sg.xy),
                                           u[i].theta + k * rng.gaussian(sg.theta)});
      plans[g] = planProposal(p.map, p.pose, u[i], has_odometry, scan, o_, motion_, &start);
    } else {
      plans[g] = planProposal(p.map, p.pose, u[i], has_odometry, scan, o_, motion_);
    }
  });
  return plans;
}

std::vector<Pose2> RbpfSlam::sampleFromProposals(const ProposalGroups& groups, const std::vector<ProposalPlan>& plans,
                                                 const std::vector<Pose2>& u, bool has_odometry,
                                                 const PreparedScan& scan, StepStats& st,
                                                 std::vector<Pose2>& estimates, std::vector<char>& matched) {
  const std::size_t n = particles_.size();
  const std::size_t step = stats_.size();
  std::vector<Pose2> poses(n);
  estimates.assign(n, Pose2{});
  std::vector<int> extra_evals(n, 0);
  pool_->parallelFor(n, [&](std::size_t i) {
    Particle& p = particles_[i];
    const ProposalPlan& plan = plans[groups.group_of[i]];
    Rng rng(o_.seed, step, i, kPurposeParticle);
    const double dw = drawFromProposal(plan, p.map, p.pose, u[i], has_odometry, scan, o_, motion_, rng, poses[i]);
    // The reported pose: the informed proposal's mean (the sample without its own noise), else the sample.
    const bool report_mean = o_.proposal.report_mean && plan.type == ProposalType::Informed && plan.matched;
    estimates[i] = report_mean ? plan.gaussian.mean : poses[i];
    extra_evals[i] = plan.matched ? 0 : 1;
    p.log_weight += dw;
    p.log_weight_total += dw;
  });
  matched.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    matched[i] = plans[groups.group_of[i]].matched;
    st.failed_matches += !matched[i];
    st.evaluations += extra_evals[i];
  }
  for (const auto& pl : plans) st.evaluations += pl.evaluations;
  st.evaluations /= static_cast<double>(n);
  return poses;
}

void RbpfSlam::updateMaps(const std::vector<Pose2>& poses, const std::vector<Pose2>& estimates,
                          const std::vector<char>& matched, const PreparedScan& scan, std::size_t index) {
  pool_->parallelFor(particles_.size(), [&](std::size_t i) {
    Particle& p = particles_[i];
    p.pose = poses[i];
    p.map.insertScan(p.pose, scan.sensor, scan.map_beams, o_.map);
    auto node = std::make_shared<TrajectoryNode>(p.pose, estimates[i], index, p.node);
    node->matched = matched[i] != 0;
    p.node = std::move(node);
  });
}

std::vector<double> RbpfSlam::normaliseWeights() {
  std::vector<double> lw(particles_.size());
  for (std::size_t i = 0; i < particles_.size(); ++i) lw[i] = particles_[i].log_weight;
  const std::vector<double> w = normalizedWeights(lw);
  // Keep the relative weights bounded: subtract the maximum (a common factor).
  const double mx = *std::max_element(lw.begin(), lw.end());
  for (auto& p : particles_) p.log_weight -= mx;
  return w;
}

void RbpfSlam::recordStep(StepStats& st, std::chrono::steady_clock::time_point t0) {
  // Counting distinct tiles hashes every tile pointer of every particle: done every 20 steps only.
  if (stats_.empty() || stats_.size() % 20 == 0) {
    last_unique_tiles_ = uniqueTiles(&last_map_bytes_);
  }
  st.unique_tiles = last_unique_tiles_;
  st.map_bytes = last_map_bytes_;
  {
    // Each particle's ancestor kLineageLag nodes up its path (a path shorter than that: its root).
    std::vector<const TrajectoryNode*> ancestors;
    ancestors.reserve(particles_.size());
    for (const Particle& p : particles_) {
      const TrajectoryNode* a = p.node.get();
      for (std::size_t k = 0; a && a->parent && k < kLineageLag; ++k) a = a->parent.get();
      ancestors.push_back(a);
    }
    std::sort(ancestors.begin(), ancestors.end());
    st.lineages = static_cast<int>(std::unique(ancestors.begin(), ancestors.end()) - ancestors.begin());
  }
  st.coalescence = coalescenceDepth();
  st.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  stats_.push_back(st);
}

std::size_t RbpfSlam::coalescenceDepth() const {
  // Every processed scan adds one node to every particle's path, so the particles' paths step back in lockstep:
  // climb them together, one node each, until they meet (or the oldest reaches its root).
  std::vector<const TrajectoryNode*> front;
  front.reserve(particles_.size());
  for (const Particle& p : particles_) front.push_back(p.node.get());
  std::size_t depth = 0;
  for (;;) {
    std::sort(front.begin(), front.end());
    front.erase(std::unique(front.begin(), front.end()), front.end());
    if (front.size() <= 1) return depth;
    bool moved = false;
    for (const TrajectoryNode*& n : front) {
      if (n && n->parent) {
        n = n->parent.get();
        moved = true;
      }
    }
    if (!moved) return depth;
    ++depth;
  }
}

void RbpfSlam::resample(const std::vector<double>& w, std::size_t count) {
  Rng rng(o_.seed, stats_.size(), 0, kPurposeResample);
  if (count == 0 && o_.kld.adaptive()) {
    // KLD-sampling (Fox 2003): the bins of the particles the full (maximum) count would keep give the new count;
    // the same comb offset draws it.
    const std::size_t maximum = static_cast<std::size_t>(o_.particles);
    Rng probe = rng;
    const std::vector<std::size_t> full = lowVarianceResample(w, probe, maximum);
    std::vector<Pose2> poses(particles_.size());
    for (std::size_t i = 0; i < particles_.size(); ++i) poses[i] = particles_[i].pose;
    count = kldParticleCount(poses, full, o_.kld, maximum);
  }
  if (count == 0) count = particles_.size();  // the fixed set
  const std::vector<std::size_t> keep = lowVarianceResample(w, rng, count);
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
          if (t->hits && seen_hits.insert(t->hits.get()).second) b += t->hits->bytes();
        }
    }
  }
  if (bytes) *bytes = b;
  return seen.size();
}

std::vector<TimedPose> RbpfSlam::trajectory() const {
  if (scans_.empty() || particles_.empty()) return std::vector<TimedPose>(scans_.size());
  std::vector<Pose2> processed;
  for (const TrajectoryNode* n : pathOf(bestParticle().node)) processed.push_back(n->estimate);
  return trajectoryThrough(processed);
}

void RbpfSlam::applyCorrection(const Pose2& correction, const GridMap& map) {
  for (Particle& p : particles_) {
    p.pose = compose(correction, p.pose);
    p.map = map;
    if (p.node) {
      auto node = std::make_shared<TrajectoryNode>(p.pose, compose(correction, p.node->estimate),
                                                   p.node->scan_index, p.node->parent);
      node->matched = p.node->matched;
      p.node = std::move(node);
    }
  }
}

std::vector<TimedPose> RbpfSlam::trajectoryThrough(const std::vector<Pose2>& processed) const {
  std::vector<TimedPose> out(scans_.size());
  if (scans_.empty() || particles_.empty()) return out;
  struct Anchor {
    std::size_t scan_index;
    Pose2 estimate;
  };
  std::vector<Anchor> anchors(std::min(processed.size(), stats_.size()));
  for (std::size_t k = 0; k < anchors.size(); ++k) anchors[k] = {stats_[k].scan_index, processed[k]};
  const std::vector<Anchor>& path = anchors;
  if (path.empty()) return out;
  // The odometry between processed scans, scaled by the best particle's (current) odometry scale.
  const double scale = bestParticle().odometry_scale;
  // processed scan index -> pose
  std::vector<long> proc_at(scans_.size(), -1);
  for (std::size_t k = 0; k < path.size(); ++k) proc_at[path[k].scan_index] = static_cast<long>(k);
  auto fromAnchor = [&](std::size_t k, std::size_t i) {
    const ScanInfo& a = scans_[path[k].scan_index];
    const ScanInfo& b = scans_[i];
    if (a.has_odometry && b.has_odometry) {
      const Pose2 d = relative(a.odometry, b.odometry);
      return compose(path[k].estimate, {scale * d.x, scale * d.y, d.theta});
    }
    return path[k].estimate;
  };
  std::size_t prev = 0;  // index into path
  for (std::size_t i = 0; i < scans_.size(); ++i) {
    out[i].timestamp = scans_[i].timestamp;
    Pose2 p;
    if (proc_at[i] >= 0) {
      prev = static_cast<std::size_t>(proc_at[i]);
      p = path[prev].estimate;
    } else if (prev + 1 < path.size()) {
      // Blend the odometry extrapolations from the previous and the next processed scan.
      const std::size_t i0 = path[prev].scan_index, i1 = path[prev + 1].scan_index;
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
