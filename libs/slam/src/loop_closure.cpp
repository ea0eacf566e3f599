#include "gridtopo/slam/loop_closure.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <iomanip>
#include <limits>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_set>

#include "gridtopo/slam/proposal.h"

namespace gridtopo::slam {

namespace {

std::uint64_t cellKey(double x, double y, double size) {
  const auto ix = static_cast<std::int64_t>(std::floor(x / size));
  const auto iy = static_cast<std::int64_t>(std::floor(y / size));
  return (static_cast<std::uint64_t>(ix) << 32) ^ (static_cast<std::uint64_t>(iy) & 0xffffffffULL);
}

/// Keeps the first point of every voxel (input order: deterministic).
void thinInPlace(std::vector<Point2>& pts, double voxel) {
  std::unordered_set<std::uint64_t> seen;
  seen.reserve(pts.size() * 2);
  std::size_t k = 0;
  for (const Point2& p : pts)
    if (seen.insert(cellKey(p.x, p.y, voxel)).second) pts[k++] = p;
  pts.resize(k);
}

// Adds the calling thread's processor seconds between its construction and its destruction to `total`.
class ThreadCpuTimer {
 public:
  explicit ThreadCpuTimer(double& total) : total_(total), start_(now()) {}
  ~ThreadCpuTimer() { total_ += now() - start_; }
  ThreadCpuTimer(const ThreadCpuTimer&) = delete;
  ThreadCpuTimer& operator=(const ThreadCpuTimer&) = delete;

 private:
  static double now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
  double& total_;
  double start_;
};

// How many of the values (travels, m) lie at least `gap` apart, taken greedily from the smallest.
int spacedCount(std::vector<double> values, double gap) {
  std::sort(values.begin(), values.end());
  int n = 0;
  double last = -1e300;
  for (double v : values)
    if (v - last >= gap) {
      ++n;
      last = v;
    }
  return n;
}

}  // namespace

LoopCloser::LoopCloser(const LoopClosureOptions& options, const MotionModelOptions& motion)
    : o_(options), motion_(motion) {
  o_.validate();
}

LoopClosureStep LoopCloser::addScan(std::size_t scan_index, double timestamp, const Pose2& filter_pose,
                                    const Pose2& motion, const Pose2* odometry, const PreparedScan& scan,
                                    bool matched) {
  LoopClosureStep step;
  addFilterMotion(scan_index, timestamp, filter_pose, motion, odometry, scan, matched);
  const std::size_t i = nodes_.size() - 1;
  step.newest_before = step.newest_after = graph_.pose(i);
  {
    const ThreadCpuTimer timer(cpu_windowed_);
    if (backfill_from_ < i) backfillClosures(step, i);
    if (i % static_cast<std::size_t>(o_.search_every) == 0) searchForClosures(step, i);
  }
  if (o_.global_search) {
    std::vector<Pose2> geometry;  // the filter's path, read once per step and only when needed
    const auto geo = [&]() -> const std::vector<Pose2>& {
      if (geometry.empty()) geometry = localGeometry();
      return geometry;
    };
    if (next_to_sign_ < nodes_.size() && nodes_[i].travelled - nodes_[next_to_sign_].travelled >= o_.global_query_m) {
      const ThreadCpuTimer timer(cpu_global_sign_);
      signOlderPlaces(geo());
    }
    if (nodes_[i].travelled - last_global_travel_ >= o_.global_every_m) {
      const ThreadCpuTimer timer(cpu_global_query_);
      last_global_travel_ = nodes_[i].travelled;
      proposeGlobalClosures(geo());
    }
    if (!pending_.empty()) {
      const ThreadCpuTimer timer(cpu_global_verify_);
      verifyGlobalClosures(step, geo());
    }
  }
  const bool pending = pending_from_ < closures_.size();
  // Optimise every optimize_every scans while closures are pending, and at once after a closure that moves the
  // estimate by more than ten loop_sigma_xy (the first closure after a long excursion) or after verified global
  // closures.
  const bool large = optimize_now_ || (step.accepted > 0 && closures_.back().offset_xy > 10.0 * o_.loop_sigma_xy);
  optimize_now_ = false;
  if (pending && (i - last_optimized_node_ >= static_cast<std::size_t>(o_.optimize_every) || large)) {
    const ThreadCpuTimer timer(cpu_optimize_);
    optimizePoseGraph(step);
  }
  return step;
}

std::vector<Pose2> LoopCloser::finalPoses() const {
  PoseGraph g = graph_;
  if (filter_path_) {
    const std::vector<FilterStep> path = filter_path_();
    if (path.size() == nodes_.size()) {
      if (closures_.empty()) return posesOf(path);
      setMotionEdges(path, g);
    }
  }
  if (!closures_.empty()) g.optimize(solveOptions());
  std::vector<Pose2> p(g.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = g.pose(i);
  return p;
}

PoseGraphSolveOptions LoopCloser::solveOptions() const {
  PoseGraphSolveOptions so;
  so.huber_scale = o_.huber_scale;
  so.max_iterations = o_.max_iterations;
  return so;
}

void LoopCloser::setMotionEdges(const std::vector<FilterStep>& path, PoseGraph& g) const {
  for (std::size_t k = 1; k < path.size(); ++k) {
    const auto change = frame_changes_.find(k);
    const Pose2& before = path[k - 1].estimate;
    const Pose2 from = change == frame_changes_.end() ? before : compose(change->second, before);
    const Pose2* odometry = nodes_[k].odometry ? &*nodes_[k].odometry : nullptr;
    g.replaceEdge(nodes_[k].motion_edge,
                  motionEdge(k - 1, relative(from, path[k].estimate), odometry, path[k].matched));
  }
}

std::vector<Pose2> LoopCloser::posesOf(const std::vector<FilterStep>& path) {
  std::vector<Pose2> poses;
  poses.reserve(path.size());
  for (const FilterStep& s : path) poses.push_back(s.estimate);
  return poses;
}

std::vector<Pose2> LoopCloser::poses() const {
  std::vector<Pose2> p(graph_.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = graph_.pose(i);
  return p;
}

void LoopCloser::addFilterMotion(std::size_t scan_index, double timestamp, const Pose2& filter_pose,
                                 const Pose2& motion, const Pose2* odometry, const PreparedScan& scan, bool matched) {
  Node n;
  if (odometry) n.odometry = *odometry;
  n.scan_index = scan_index;
  n.timestamp = timestamp;
  n.travelled = nodes_.empty() ? 0.0 : nodes_.back().travelled + std::hypot(motion.x, motion.y);
  if (!nodes_.empty()) {
    n.suspect_xy = nodes_.back().suspect_xy;
    n.suspect_theta = nodes_.back().suspect_theta;
    if (const auto d = suspectDisagreement(motion, odometry)) {
      n.suspect_xy += d->xy;
      n.suspect_theta += d->theta;
      ++suspect_;
    }
  }
  const double r2 = o_.point_range * o_.point_range;
  for (const MapBeam& b : scan.map_beams) {
    if (!b.hit) continue;
    const double dx = b.ex - scan.sensor.x, dy = b.ey - scan.sensor.y;
    if (dx * dx + dy * dy > r2) continue;
    n.points.push_back({b.ex, b.ey});
  }
  thinInPlace(n.points, o_.resolution);
  n.points.shrink_to_fit();
  n.sensor = {scan.sensor.x, scan.sensor.y};
  if (nodes_.empty()) {
    graph_.addNode(filter_pose);
  } else {
    const std::size_t prev = nodes_.size() - 1;
    graph_.addNode(compose(graph_.pose(prev), motion));
    const PoseGraphEdge e = motionEdge(prev, motion, odometry, matched);
    n.motion_edge = graph_.addEdge(e);
  }
  nodes_.push_back(std::move(n));
  // Submaps: runs of submap_nodes consecutive nodes.
  const std::size_t i = nodes_.size() - 1;
  if (submaps_.empty() || submaps_.back().last + 1 - submaps_.back().first >= static_cast<std::size_t>(o_.submap_nodes))
    submaps_.push_back({i, i, {}, false});
  else
    submaps_.back().last = i;
}

std::optional<LoopCloser::Disagreement> LoopCloser::suspectDisagreement(const Pose2& motion,
                                                                          const Pose2* odometry) const {
  if (!odometry) return std::nullopt;
  if (motion_.squaredDeviations(motion, *odometry) <= o_.disagreement_sigmas * o_.disagreement_sigmas)
    return std::nullopt;
  return Disagreement{std::hypot(motion.x - odometry->x, motion.y - odometry->y),
                      std::abs(wrapAngle(motion.theta - odometry->theta))};
}

PoseGraphEdge LoopCloser::motionEdge(std::size_t prev, const Pose2& motion, const Pose2* odometry,
                                     bool matched) const {
  // A step where the filter and the odometry disagree beyond the motion model's noise is suspect: one of them is
  // wrong (a filter that followed something moving with the robot, or an odometry that slipped). Its edge is
  // weakened by the difference, so that a closure can bend it (and the search windows of paths through it widen).
  const Disagreement d = suspectDisagreement(motion, odometry).value_or(Disagreement{0.0, 0.0});
  PoseGraphEdge e;
  e.a = prev;
  e.b = prev + 1;
  e.z = motion;
  double sxy = o_.odometry_sigma_xy + o_.odometry_sigma_xy_per_m * std::hypot(motion.x, motion.y) + d.xy;
  double st = o_.odometry_sigma_theta + o_.odometry_sigma_theta_per_rad * std::abs(motion.theta) + d.theta;
  if (!matched && o_.unmatched_steps_as_odometry) {
    // The match failed: the pose is a draw from the motion model around the odometry (or around no motion without
    // odometry), as uncertain as the model says, not a match good to millimetres.
    const OdometryMotionModel::Sigmas m = motion_.sigmas(odometry ? *odometry : motion, odometry != nullptr);
    sxy = std::hypot(sxy, m.xy);
    st = std::hypot(st, m.theta);
  }
  e.sqrt_information = sqrtInformationOfSigmas(sxy, sxy, st);
  return e;
}

void LoopCloser::adoptFilterPath() {
  if (!filter_path_) return;
  const std::vector<FilterStep> path = filter_path_();
  if (path.size() != nodes_.size()) return;
  setMotionEdges(path, graph_);
  // Without a closure the graph is the filter's path itself.
  if (closures_.empty())
    for (std::size_t k = 0; k < path.size(); ++k) graph_.setPose(k, path[k].estimate);
}

Eigen::Matrix3d LoopCloser::closureSqrtInformation(const CorrelationGrid& grid, const std::vector<Point2>& query,
                                                   const Pose2& x, double dtheta) const {
  // The match's log-likelihood: the query's points each count as ln p = refined value (a Gaussian of width
  // refine_sigma around the submap's points, ≈ 1 − d²/2σ² near them), divided by the information gain for the
  // correlation between neighbouring points. Its curvature at the match, fitted over a 3 × 3 × 3 grid of poses one
  // cell and two angular steps apart, is the information (Olson 2009: the covariance of a correlative match from
  // the shape of its score); flat directions (a corridor's axis) carry none.
  const double dxy = grid.resolution(), dth = std::max(2.0 * dtheta, 1e-3);
  std::vector<Pose2> poses;
  std::vector<double> ll;
  const double k = static_cast<double>(query.size()) / o_.information_gain;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int t = -1; t <= 1; ++t) {
        const Pose2 p{x.x + i * dxy, x.y + j * dxy, wrapAngle(x.theta + t * dth)};
        poses.push_back(p);
        ll.push_back(k * refinementScore(grid, query, p));
      }
  const LocalQuadratic q = fitLocalQuadratic(poses, ll, x, dxy, dth, 2.0);
  if (!q.ok) return sqrtInformationOfSigmas(o_.loop_sigma_xy, o_.loop_sigma_xy, o_.loop_sigma_theta);
  // The deviations floored at loop_sigma_* along every direction, in coordinates where the heading is scaled by
  // lever = loop_sigma_xy / loop_sigma_theta (so that one floor serves both).
  const double lever = o_.loop_sigma_xy / o_.loop_sigma_theta;
  const Eigen::Vector3d s(1.0, 1.0, 1.0 / lever);  // P in scaled coordinates: S⁻¹ P S⁻¹ with S = diag(1, 1, lever)
  const Eigen::Matrix3d Pu = s.asDiagonal() * q.P * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(0.5 * (Pu + Pu.transpose()));
  Eigen::Vector3d root;
  for (int i = 0; i < 3; ++i) {
    const double lambda = es.eigenvalues()(i);
    const double variance = (lambda > 1e-12 ? 1.0 / lambda : 1e12) + o_.loop_sigma_xy * o_.loop_sigma_xy;
    root(i) = 1.0 / std::sqrt(variance);
  }
  // residual = root ⊙ Eᵀ (S e): ‖·‖² = eᵀ S E diag(1/v) Eᵀ S e.
  const Eigen::Vector3d S(1.0, 1.0, lever);
  return root.asDiagonal() * es.eigenvectors().transpose() * S.asDiagonal();
}

std::vector<Pose2> LoopCloser::localGeometry() const {
  // With feedback the filter's path changes frame at the corrected nodes: the graph's poses then.
  if (filter_path_ && frame_changes_.empty()) {
    std::vector<Pose2> path = posesOf(filter_path_());
    if (path.size() == nodes_.size()) return path;
  }
  return poses();
}

std::vector<Point2> LoopCloser::queryOf(std::size_t node, const std::vector<Pose2>& geometry) const {
  std::vector<Point2> q;
  const std::size_t n = std::min(nodes_.size(), static_cast<std::size_t>(o_.query_nodes));
  const Pose2& ref = geometry[node];
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t j = node - k;  // newest first, so the thinning keeps the newest scan's points
    const Pose2 rel = relative(ref, geometry[j]);
    for (const Point2& p : nodes_[j].points) q.push_back(transform(rel, p));
  }
  thinInPlace(q, o_.query_voxel);
  return q;
}

const CorrelationGrid& LoopCloser::gridOf(std::size_t s, const std::vector<Pose2>& geometry) {
  for (auto it = cache_.begin(); it != cache_.end(); ++it)
    if (it->first == s) {
      cache_.splice(cache_.end(), cache_, it);
      return *cache_.back().second;
    }
  // The submap's points in the frame of its first node, placed by the filter's path as it is when the submap is
  // first searched (then kept rigid): the submap is at least min_travel old, so the particles share that part of
  // their history.
  Submap& sm = submaps_[s];
  if (!sm.frozen) {
    const Pose2& anchor = geometry[sm.first];
    for (std::size_t j = sm.first; j <= sm.last; ++j) {
      const Pose2 rel = relative(anchor, geometry[j]);
      for (const Point2& p : nodes_[j].points) sm.points.push_back(transform(rel, p));
    }
    thinInPlace(sm.points, o_.resolution);
    sm.points.shrink_to_fit();
    sm.frozen = true;
  }
  const std::vector<Point2>& pts = sm.points;
  cache_.emplace_back(s, std::make_unique<CorrelationGrid>(pts, o_.resolution, o_.field_sigma, o_.depth, o_.refine_sigma));
  while (cache_.size() > static_cast<std::size_t>(o_.grid_cache)) cache_.pop_front();
  return *cache_.back().second;
}

std::vector<LoopCloser::PathDrift> LoopCloser::driftToSubmaps(std::size_t from) const {
  // The graph reduced to its key nodes (the ends of every submap, the ends of every accepted closure and `from`):
  // consecutive key nodes are joined by the chain of motion edges between them, a closure's ends by nothing (it
  // ties them to a few centimetres). Each measure of drift is minimised over the paths on its own (Dijkstra):
  // the least the motion edges can have drifted by between the two ends. A closed loop makes its far side near.
  std::vector<std::size_t> keys;
  keys.reserve(2 * submaps_.size() + 2 * closures_.size() + 1);
  keys.push_back(from);
  for (const Submap& sm : submaps_) {
    keys.push_back(sm.first);
    keys.push_back(sm.last);
  }
  for (const LoopClosureRecord& c : closures_)
    if (!c.rejected) {
      keys.push_back(c.node);
      keys.push_back(c.submap_node);
    }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  const auto indexOf = [&](std::size_t node) {
    return static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), node) - keys.begin());
  };
  std::vector<std::vector<std::size_t>> links(keys.size());
  for (const LoopClosureRecord& c : closures_)
    if (!c.rejected) {
      const std::size_t a = indexOf(c.node), b = indexOf(c.submap_node);
      links[a].push_back(b);
      links[b].push_back(a);
    }
  const auto shortest = [&](auto cumulative) {
    std::vector<double> dist(keys.size(), std::numeric_limits<double>::infinity());
    using Item = std::pair<double, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    dist[indexOf(from)] = 0.0;
    open.emplace(0.0, indexOf(from));
    while (!open.empty()) {
      const auto [d, k] = open.top();
      open.pop();
      if (d > dist[k]) continue;
      const auto relax = [&, d = d](std::size_t j, double w) {
        if (d + w < dist[j]) {
          dist[j] = d + w;
          open.emplace(dist[j], j);
        }
      };
      if (k > 0) relax(k - 1, cumulative(nodes_[keys[k]]) - cumulative(nodes_[keys[k - 1]]));
      if (k + 1 < keys.size()) relax(k + 1, cumulative(nodes_[keys[k + 1]]) - cumulative(nodes_[keys[k]]));
      for (std::size_t j : links[k]) relax(j, 0.0);
    }
    return dist;
  };
  const std::vector<double> travel = shortest([](const Node& n) { return n.travelled; });
  const std::vector<double> sxy = shortest([](const Node& n) { return n.suspect_xy; });
  const std::vector<double> sth = shortest([](const Node& n) { return n.suspect_theta; });
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<PathDrift> per_submap(submaps_.size(), PathDrift{inf, inf, inf});
  for (std::size_t s = 0; s < submaps_.size(); ++s)
    for (std::size_t k = indexOf(submaps_[s].first); k < keys.size() && keys[k] <= submaps_[s].last; ++k) {
      PathDrift& d = per_submap[s];
      d.travel = std::min(d.travel, travel[k]);
      d.suspect_xy = std::min(d.suspect_xy, sxy[k]);
      d.suspect_theta = std::min(d.suspect_theta, sth[k]);
    }
  return per_submap;
}

double LoopCloser::driftWindowXy(const PathDrift& p) const {
  return o_.window_xy_min + o_.window_xy_per_m * p.travel + p.suspect_xy + p.suspect_theta * p.travel;
}

void LoopCloser::searchForClosures(LoopClosureStep& step, std::size_t i) {
  if (i + 1 < static_cast<std::size_t>(o_.query_nodes)) return;
  const Node& cur = nodes_[i];
  const Pose2& x = graph_.pose(i);
  // The window around the estimate, per submap: how far the graph's least-drift path to the submap can have
  // drifted. It grows with the path's travel, and with the filter's disagreement with the odometry on its suspect
  // steps (where one of the two went wrong), in translation directly and through the heading, whose error moves
  // every later pose by at most the heading times the travel after it (bounded by the path's travel).
  const std::vector<PathDrift> drift = driftToSubmaps(i);
  const auto windowXy = [&](std::size_t s) { return std::min(o_.window_xy_max, driftWindowXy(drift[s])); };
  // Candidates: complete submaps left at least min_travel ago, one of whose poses lies within the window (plus
  // the reach of a view) of the current estimate; nearest first, in units of that reach (a submap far along the
  // graph, whose window is wide, ranks with a near one whose window is narrow).
  std::vector<std::pair<double, std::size_t>> cand;
  for (std::size_t s = 0; s < submaps_.size(); ++s) {
    const Submap& sm = submaps_[s];
    if (sm.last + 1 - sm.first < static_cast<std::size_t>(o_.submap_nodes)) continue;
    if (cur.travelled - nodes_[sm.last].travelled < o_.min_travel) continue;
    const double reach = windowXy(s) + 0.5 * o_.point_range;
    double best = reach;
    for (std::size_t j = sm.first; j <= sm.last; ++j) {
      const Pose2& p = graph_.pose(j);
      best = std::min(best, std::hypot(p.x - x.x, p.y - x.y));
    }
    if (best < reach) cand.emplace_back(best / reach, s);
  }
  std::sort(cand.begin(), cand.end());
  if (cand.size() > static_cast<std::size_t>(o_.max_candidates)) cand.resize(static_cast<std::size_t>(o_.max_candidates));
  if (cand.empty()) return;
  const std::vector<Pose2> geometry = localGeometry();
  const std::vector<Point2> query = queryOf(i, geometry);
  if (query.size() < 20) return;
  double d_max = o_.resolution;
  for (const Point2& q : query) d_max = std::max(d_max, std::hypot(q.x, q.y));
  const double dtheta = std::acos(std::max(-1.0, 1.0 - o_.resolution * o_.resolution / (2.0 * d_max * d_max)));
  for (const auto& [dist, s] : cand) {
    (void)dist;
    const Submap& sm = submaps_[s];
    const CorrelationGrid& grid = gridOf(s, geometry);
    SearchWindow w;
    w.center = relative(graph_.pose(sm.first), x);
    // The window for this submap: the drift the graph's shortest path to it can have gathered.
    const double d = drift[s].travel;
    w.xy = windowXy(s);
    // The suspect steps' heading disagreement widens the window beyond its largest growth: after a stretch where
    // the filter turned and the odometry did not (FR079: a crowd walking with the robot), the truth can lie 40
    // degrees away, and only a closure brings the estimate back to it.
    w.theta = std::min(0.5 * M_PI, std::min(o_.window_theta_max, o_.window_theta_min + o_.window_theta_per_m * d) +
                                       drift[s].suspect_theta);
    ++searches_;
    const auto found = branchAndBoundSearch(grid, query, w, o_.min_score);
    if (!found) continue;
    // A best pose near the window's border may only be the foot of a better one outside it (a corridor that goes
    // on past the submap's end): no closure. The margin is four cells and four angular steps.
    const double margin_xy = 4.0 * grid.resolution(), margin_th = 4.0 * dtheta;
    if (std::abs(found->pose.x - w.center.x) > w.xy - margin_xy ||
        std::abs(found->pose.y - w.center.y) > w.xy - margin_xy ||
        (w.theta > margin_th && std::abs(wrapAngle(found->pose.theta - w.center.theta)) > w.theta - margin_th)) {
      ++border_;
      continue;
    }
    // The refinement climbs the sharp value from the search's best cell and from the estimate itself; the higher
    // sharp score wins (the wide search value can favour a pose a few cells off when structures blur together).
    CorrelativeMatch m = refineMatch(grid, query, found->pose, dtheta);
    const CorrelativeMatch from_estimate = refineMatch(grid, query, w.center, dtheta);
    if (refinementScore(grid, query, from_estimate.pose) > refinementScore(grid, query, m.pose)) m = from_estimate;
    if (m.score < o_.min_score) continue;
    // Refuse look-alikes: a distinct pose of the window that scores nearly as well.
    const Point2 at{m.pose.x, m.pose.y};
    if (o_.ambiguity_ratio < 1.0) {
      const auto other = branchAndBoundSearch(grid, query, w, std::max(o_.min_score, o_.ambiguity_ratio * m.score), &at,
                                              o_.ambiguity_distance);
      if (other) {
        ++ambiguous_;
        continue;
      }
    }
    addClosure(sm.first, i, m.pose, closureSqrtInformation(grid, query, m.pose, dtheta), m.score, w.xy,
               std::hypot(m.pose.x - w.center.x, m.pose.y - w.center.y),
               std::abs(wrapAngle(m.pose.theta - w.center.theta)), false);
    ++step.accepted;
  }
}

void LoopCloser::backfillClosures(LoopClosureStep& step, std::size_t i) {
  // The nodes that went by while the global matches of a new loop waited for agreement: the windowed search could
  // not reach their places then (the estimate was tens of metres off); now that the loop is closed it can, and its
  // precise closures of the return's first metres tie the loop tight (the simulated 1 km ring: 0.107 -> 0.067 m).
  const auto accepted_before = step.accepted;
  for (std::size_t k = backfill_from_; k < i; ++k)
    if (k % static_cast<std::size_t>(o_.search_every) == 0) searchForClosures(step, k);
  backfill_from_ = std::numeric_limits<std::size_t>::max();
  if (step.accepted > accepted_before) optimize_now_ = true;
}

void LoopCloser::addClosure(std::size_t from, std::size_t node, const Pose2& z, const Eigen::Matrix3d& sqrt_information,
                            double score, double window_xy, double offset_xy, double offset_theta, bool global) {
  // Windowed closures carry the Huber loss; verified global ones do not (the stiff motion edges would otherwise hold
  // a large correction back).
  PoseGraphEdge e;
  e.a = from;
  e.b = node;
  e.z = z;
  e.sqrt_information = sqrt_information;
  e.robust = !global;
  LoopClosureRecord rec;
  rec.edge = graph_.addEdge(e);
  rec.node = node;
  rec.scan_index = nodes_[node].scan_index;
  rec.timestamp = nodes_[node].timestamp;
  rec.submap_node = from;
  rec.score = score;
  rec.window_xy = window_xy;
  rec.offset_xy = offset_xy;
  rec.offset_theta = offset_theta;
  rec.global = global;
  closures_.push_back(rec);
}

void LoopCloser::addExternalClosure(std::size_t from, const Pose2& z, double sigma_xy, double sigma_theta) {
  if (nodes_.empty() || from + 1 >= nodes_.size())
    throw std::invalid_argument("LoopCloser::addExternalClosure: node " + std::to_string(from) +
                                " is not older than the newest node (" + std::to_string(nodes_.size()) + " nodes)");
  if (!(sigma_xy > 0.0) || !(sigma_theta > 0.0))
    throw std::invalid_argument("LoopCloser::addExternalClosure: the deviations must be > 0");
  const std::size_t i = nodes_.size() - 1;
  const Pose2 estimate = relative(graph_.pose(from), graph_.pose(i));
  addClosure(from, i, z, sqrtInformationOfSigmas(sigma_xy, sigma_xy, sigma_theta), 0.0, 0.0,
             std::hypot(z.x - estimate.x, z.y - estimate.y),
             std::abs(wrapAngle(z.theta - estimate.theta)), false);
}

void LoopCloser::optimizePoseGraph(LoopClosureStep& step) {
  const std::size_t i = nodes_.size() - 1;
  const Pose2 before = graph_.pose(i);
  adoptFilterPath();
  // Where the filter's motions since the last optimisation put the newest node (adoptFilterPath may have changed
  // them: a new best particle): the closures' correction is measured from there, not from the poses chained from
  // an older best particle (the hospital: 122 m "corrections" that were a change of best particle, not a closure).
  Pose2 chained = graph_.pose(last_optimized_node_);
  for (std::size_t k = last_optimized_node_ + 1; k <= i; ++k)
    chained = compose(chained, graph_.edges()[nodes_[k].motion_edge].z);
  PoseGraphSolveOptions so = solveOptions();
  // A new global closure can bend the graph far from where it stands: more iterations for that optimisation.
  bool global = false;
  for (std::size_t k = pending_from_; k < closures_.size(); ++k) global = global || closures_[k].global;
  if (global) so.max_iterations = std::max(so.max_iterations, 4 * o_.max_iterations);
  graph_.optimize(so);
  ++optimizations_;
  // The new closures that still disagree with everything else are look-alikes: out, and optimise again.
  bool rejected = false;
  for (std::size_t k = pending_from_; k < closures_.size(); ++k) {
    LoopClosureRecord& c = closures_[k];
    c.residual = graph_.residual(graph_.edges()[c.edge]).norm();
    // Global closures were verified by their agreement (a large correction leaves them far from the stiff motion
    // edges' first compromise): they stay.
    if (!c.global && o_.outlier_sigmas > 0.0 && c.residual > o_.outlier_sigmas) {
      c.rejected = true;
      graph_.deactivateEdge(c.edge);
      rejected = true;
    }
  }
  if (rejected) {
    graph_.optimize(so);
    ++optimizations_;
  }
  const Pose2 after = graph_.pose(i);
  const Pose2 d = relative(before, after);
  for (std::size_t k = pending_from_; k < closures_.size(); ++k) {
    closures_[k].correction_xy = std::hypot(after.x - chained.x, after.y - chained.y);
    closures_[k].correction_theta = std::abs(wrapAngle(after.theta - chained.theta));
  }
  pending_from_ = closures_.size();
  last_optimized_node_ = i;
  step.optimized = true;
  step.newest_before = before;
  step.newest_after = after;
  step.feedback = o_.feedback && (std::hypot(after.x - before.x, after.y - before.y) > o_.feedback_min_correction ||
                                  std::abs(d.theta) > o_.feedback_min_rotation);
}

std::pair<std::size_t, std::size_t> LoopCloser::stretchOf(std::size_t centre, double back, double ahead) const {
  const double t = nodes_[centre].travelled;
  std::size_t first = centre, last = centre;
  while (first > 0 && t - nodes_[first - 1].travelled <= back) --first;
  while (last + 1 < nodes_.size() && nodes_[last + 1].travelled - t <= ahead) ++last;
  return {first, last};
}

std::vector<Point2> LoopCloser::stretchPoints(std::size_t centre, std::size_t first, std::size_t last,
                                              const std::vector<Pose2>& geometry, double voxel) const {
  // Nearest to the centre first, so that the thinning keeps the points of the scans closest to it.
  std::vector<std::size_t> order;
  for (std::size_t j = first; j <= last; ++j) order.push_back(j);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const auto d = [&](std::size_t j) { return j > centre ? j - centre : centre - j; };
    return d(a) < d(b);
  });
  std::vector<Point2> pts;
  const Pose2& ref = geometry[centre];
  for (std::size_t j : order) {
    const Pose2 rel = relative(ref, geometry[j]);
    for (const Point2& p : nodes_[j].points) pts.push_back(transform(rel, p));
  }
  thinInPlace(pts, voxel);
  return pts;
}

PlaceSignatureShape LoopCloser::signatureShape() const {
  PlaceSignatureShape shape;
  shape.rings = o_.signature_rings;
  shape.sectors = o_.signature_sectors;
  shape.radius = o_.point_range;
  return shape;
}

void LoopCloser::signOlderPlaces(const std::vector<Pose2>& geometry) {
  // A node is signed once the trajectory has gone half global_query_m past it (its stretch is complete), every
  // global_signature_every_m of travel: the points of the trajectory within half global_query_m either side of it,
  // so that the way there and the way back give the same signature.
  const std::size_t i = nodes_.size() - 1;
  const double half = 0.5 * o_.global_query_m;
  const PlaceSignatureShape shape = signatureShape();
  for (; next_to_sign_ < nodes_.size() && nodes_[i].travelled - nodes_[next_to_sign_].travelled >= half;
       ++next_to_sign_) {
    const std::size_t j = next_to_sign_;
    if (nodes_[j].travelled - last_signed_travel_ < o_.global_signature_every_m) continue;
    last_signed_travel_ = nodes_[j].travelled;
    const auto [first, last] = stretchOf(j, half, half);
    places_.push_back({j, PlaceSignature(stretchPoints(j, first, last, geometry, o_.query_voxel), shape)});
  }
}

CorrelationGrid LoopCloser::placeGrid(std::size_t j, const std::vector<Pose2>& geometry) const {
  const auto [t0, t1] = stretchOf(j, o_.global_query_m, o_.global_query_m);
  return CorrelationGrid(stretchPoints(j, t0, t1, geometry, o_.resolution), o_.resolution, o_.field_sigma, o_.depth,
                         o_.refine_sigma);
}

ObservedArea LoopCloser::placeObservedArea(std::size_t j, const std::vector<Pose2>& geometry) const {
  const auto [t0, t1] = stretchOf(j, o_.global_query_m, o_.global_query_m);
  std::vector<ObservedScan> scans;
  scans.reserve(t1 + 1 - t0);
  for (std::size_t k = t0; k <= t1; ++k)
    scans.push_back({relative(geometry[j], geometry[k]), nodes_[k].sensor, &nodes_[k].points});
  // Cells of twice the grid's resolution; a beam's last 0.3 m and 0.2 m around every hit are not free: the field
  // of a hit reaches ~3 field_sigma, and a query point that close to a wall the place saw is a near miss, not a
  // contradiction.
  return ObservedArea(scans, 2.0 * o_.resolution, 0.3, 0.2);
}

bool LoopCloser::closedRecently(std::size_t submap, double since_travelled) const {
  for (auto c = closures_.rbegin(); c != closures_.rend(); ++c) {
    // (global and backfilled closures are appended after newer windowed ones: no early stop on the node's order)
    if (c->global || c->rejected || nodes_[c->node].travelled < since_travelled) continue;
    const std::size_t s = c->submap_node / static_cast<std::size_t>(o_.submap_nodes);
    if (s + 1 >= submap && s <= submap + 1) return true;
  }
  return false;
}

void LoopCloser::proposeGlobalClosures(const std::vector<Pose2>& geometry) {
  const std::size_t i = nodes_.size() - 1;
  const double half = 0.5 * o_.global_query_m;
  if (nodes_[i].travelled < o_.global_query_m) return;
  // The query: the newest global_query_m of trajectory, centred on its middle node (the stretch a place is signed
  // with).
  const std::size_t c = stretchOf(i, half, 0.0).first;
  const auto [q0, q1] = stretchOf(c, half, half);
  std::vector<Point2> query = stretchPoints(c, q0, q1, geometry, o_.query_voxel);
  if (query.size() < 50) return;
  const PlaceSignature signature(query, signatureShape());
  if (signature.empty()) return;
  ++global_searches_;
  // Candidates: places whose stretches ended at least global_min_travel before the query's began, ranked by the
  // signatures' distance.
  const double latest = nodes_[q0].travelled - o_.global_min_travel - half;
  struct Scored {
    double distance, yaw;
    std::size_t place;
  };
  // Scan Context's fast alignment (the sector keys' best shift) pre-ranks every place; the full distance, over every
  // shift, ranks the best of them. (The ring key, cheaper still, put the hospital's true places at rank 0-357 of
  // ~1 000 on its return, median 22: doc/slam.md, "Global search".)
  std::vector<std::pair<double, std::size_t>> ranked;
  for (std::size_t k = 0; k < places_.size() && nodes_[places_[k].node].travelled <= latest; ++k)
    ranked.emplace_back(places_[k].signature.alignedDistance(signature), k);
  const std::size_t pre = std::min<std::size_t>(ranked.size(), 10 * static_cast<std::size_t>(o_.global_candidates));
  std::partial_sort(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(pre), ranked.end());
  ranked.resize(pre);
  std::vector<Scored> scored;
  for (const auto& [key_distance, k] : ranked) {
    (void)key_distance;
    double yaw = 0.0;
    const double d = places_[k].signature.distance(signature, &yaw);
    if (d <= o_.global_max_distance) scored.push_back({d, yaw, k});
  }
  std::sort(scored.begin(), scored.end(), [](const Scored& a, const Scored& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.place < b.place;
  });
  const std::vector<PathDrift> drift = driftToSubmaps(c);
  // The branch and bound's points: a search at a bound as low as global_min_score prunes little, and its cost grows
  // with the points; a thinned query finds the same best cell (the refinement below then scores every point). Its
  // bound is a little lower than the full query's (the thinned mean is a sample of it).
  GlobalQuery q;
  q.node = c;
  q.search_points = query;
  q.points = std::move(query);
  q.thinned = o_.global_search_voxel > o_.query_voxel;
  if (q.thinned) thinInPlace(q.search_points, o_.global_search_voxel);
  double d_max = o_.resolution;
  for (const Point2& p : q.points) d_max = std::max(d_max, std::hypot(p.x, p.y));
  q.dtheta = std::acos(std::max(-1.0, 1.0 - o_.resolution * o_.resolution / (2.0 * d_max * d_max)));
  std::vector<std::size_t> tried;  // nodes of the places matched: distinct places only
  const auto distinct = [&](std::size_t j) {
    for (std::size_t t : tried)
      if (std::abs(nodes_[t].travelled - nodes_[j].travelled) < o_.global_independent_m) return false;
    return true;
  };
  // First where the newest match waiting for agreement puts the query: the signatures of a return's later queries
  // need not rank that place again (the hospital's return, doc/slam.md "Following a match").
  if (const auto predicted = predictedPlace(c, latest, geometry)) {
    const auto& [j, guess] = *predicted;
    if (!leftToWindowedSearch(j, c, drift)) {
      tried.push_back(j);
      // The prediction is as good as the trajectory since the match: the windowed search's smallest window. The
      // plain score's bar is lower (a return runs on past the places' stretches: the hospital's, past the log's
      // start, plain 0.24-0.44); what the place saw judges the match as it judges every other.
      SearchWindow w;
      w.center = guess;
      w.xy = o_.window_xy_min;
      w.theta = o_.window_theta_min;
      if (matchGlobally(q, j, w, o_.global_follow_min_score, drift, geometry)) ++global_followed_;
    }
  }
  const std::size_t followed = tried.size();
  for (const Scored& cand : scored) {
    if (tried.size() >= followed + static_cast<std::size_t>(o_.global_candidates)) break;
    const std::size_t j = places_[cand.place].node;
    if (leftToWindowedSearch(j, c, drift) || !distinct(j)) continue;
    tried.push_back(j);
    // The exact match: the query against the place's stretches both ways, around the signature's heading.
    SearchWindow w;
    w.center = {0.0, 0.0, cand.yaw};
    w.xy = o_.global_window_xy;
    w.theta = o_.global_window_theta;
    matchGlobally(q, j, w, o_.global_min_score, drift, geometry);
  }
}

bool LoopCloser::leftToWindowedSearch(std::size_t j, std::size_t c, const std::vector<PathDrift>& drift) const {
  // A place the windowed search reaches and has just closed is closed: its window holds the drift the graph's
  // least-drift path to the place can have gathered (not capped by window_xy_max), the estimate lies within that
  // window plus half a view, and one of the newest query's nodes is tied to the place's submap or a neighbour by
  // a windowed closure. The global search spends its exact matches elsewhere (on Intel it would otherwise re-close
  // ~100 places the windowed search closes anyway, at +40 % CPU); a place in reach that the windowed search did
  // not close (its match fell on the window's border, or on a look-alike) is still matched here.
  const std::size_t s = std::min(drift.size() - 1, j / static_cast<std::size_t>(o_.submap_nodes));
  const double window = driftWindowXy(drift[s]);
  const Pose2& pj = graph_.pose(j);
  const Pose2& pc = graph_.pose(c);
  return window <= o_.window_xy_max && std::hypot(pj.x - pc.x, pj.y - pc.y) < window + 0.5 * o_.point_range &&
         closedRecently(s, nodes_.back().travelled - o_.global_query_m);
}

std::optional<std::pair<std::size_t, Pose2>> LoopCloser::predictedPlace(std::size_t c, double latest,
                                                                        const std::vector<Pose2>& geometry) const {
  for (std::size_t k = pending_.size(); k-- > 0;) {
    const GlobalMatch& g = pending_[k];
    if (g.accepted || g.node == c) continue;
    // The query's node in the frame of the match's place, through the trajectory since the match's query.
    const Pose2 at = compose(g.z, relative(geometry[g.node], geometry[c]));
    // The node of the place's pass nearest to it (a pass: the trajectory global_consistency_max_m either side).
    const auto [p0, p1] = stretchOf(g.place, o_.global_consistency_max_m, o_.global_consistency_max_m);
    std::size_t best = p0;
    double best_d = 1e300;
    for (std::size_t j = p0; j <= p1 && nodes_[j].travelled <= latest; ++j) {
      const Pose2 pj = relative(geometry[g.place], geometry[j]);
      const double d = std::hypot(pj.x - at.x, pj.y - at.y);
      if (d < best_d) {
        best_d = d;
        best = j;
      }
    }
    // Beyond half a view from every pose of the pass, the query has left it.
    if (best_d > 0.5 * o_.point_range) return std::nullopt;
    return std::make_pair(best, relative(relative(geometry[g.place], geometry[best]), at));
  }
  return std::nullopt;
}

LoopCloser::DriftBound LoopCloser::driftBound(std::size_t j, const std::vector<PathDrift>& drift) const {
  // The filter's heading drifts by at most window_theta_per_m per metre of the graph's least-drift path (plus the
  // suspect steps' disagreement), and so the position by that heading times the path.
  const PathDrift& pd = drift[std::min(drift.size() - 1, j / static_cast<std::size_t>(o_.submap_nodes))];
  const double theta = o_.window_theta_min + o_.window_theta_per_m * pd.travel + pd.suspect_theta;
  return {o_.window_xy_min + o_.window_xy_per_m * pd.travel + pd.suspect_xy + theta * pd.travel, theta};
}

bool LoopCloser::beyondDriftBound(const GlobalQuery& q, std::size_t j, const SearchWindow& w,
                                  const DriftBound& bound) const {
  // matchGlobally's match: the search's best pose inside the window (it refuses one on the border), then
  // refineMatch's climb, less than kRefineStepsPerLevel cells (angular steps) in all.
  const Pose2 estimate = relative(graph_.pose(j), graph_.pose(q.node));
  const double reach_xy = w.xy + kRefineStepsPerLevel * o_.resolution;
  const double reach_theta = w.theta + kRefineStepsPerLevel * q.dtheta;
  const double gap_x = std::max(0.0, std::abs(estimate.x - w.center.x) - reach_xy);
  const double gap_y = std::max(0.0, std::abs(estimate.y - w.center.y) - reach_xy);
  const double gap_theta = std::abs(wrapAngle(estimate.theta - w.center.theta)) - reach_theta;
  return gap_theta > bound.theta || std::hypot(gap_x, gap_y) > bound.xy;
}

bool LoopCloser::matchGlobally(const GlobalQuery& q, std::size_t j, const SearchWindow& w, double min_score,
                               const std::vector<PathDrift>& drift, const std::vector<Pose2>& geometry) {
  const DriftBound bound = driftBound(j, drift);
  if (o_.global_prejudge && beyondDriftBound(q, j, w, bound)) {
    ++global_beyond_bound_;
    return false;
  }
  const CorrelationGrid grid = placeGrid(j, geometry);
  const double search_bound = q.thinned ? 0.9 * min_score : min_score;
  const auto found = branchAndBoundSearch(grid, q.search_points, w, search_bound);
  if (!found) return false;
  const double margin_xy = 4.0 * grid.resolution(), margin_th = 4.0 * q.dtheta;
  if (std::abs(found->pose.x - w.center.x) > w.xy - margin_xy ||
      std::abs(found->pose.y - w.center.y) > w.xy - margin_xy ||
      std::abs(wrapAngle(found->pose.theta - w.center.theta)) > w.theta - margin_th)
    return false;
  const CorrelativeMatch m = refineMatch(grid, q.points, found->pose, q.dtheta);
  if (m.score < min_score) return false;
  // Judged where the place looked: the query's points inside what its scans saw must score global_min_observed,
  // and few may fall where its beams passed freely (a look-alike's walls cross the true place's free space).
  const MatchEvidence evidence = matchEvidence(grid, placeObservedArea(j, geometry), q.points, m.pose);
  if (evidence.observed_score < o_.global_min_observed || evidence.contradiction > o_.global_max_contradiction) {
    ++global_refuted_;
    return false;
  }
  if (o_.ambiguity_ratio < 1.0) {
    // Another pose that scores nearly as well on the search's (thinned) points as the best one does.
    const Point2 at{m.pose.x, m.pose.y};
    const double own = q.thinned ? found->score : m.score;
    if (branchAndBoundSearch(grid, q.search_points, w, std::max(search_bound, o_.ambiguity_ratio * own), &at,
                             o_.ambiguity_distance))
      return false;
  }
  ++global_proposed_;
  // No bound from the drift a long trajectory can have gathered: a building's odometry can drift by a third of
  // the travel (the outdoor campus log), and agreement decides (verifyGlobalClosures). But where the trajectory
  // between the place and the query is short enough to trust (global_consistency_max_m), the match must agree
  // with it as the windowed search's own window would (a look-alike corridor a few metres beside the place).
  const Pose2 estimate = relative(graph_.pose(j), graph_.pose(q.node));
  const double off_xy = std::hypot(m.pose.x - estimate.x, m.pose.y - estimate.y);
  const double off_theta = std::abs(wrapAngle(m.pose.theta - estimate.theta));
  // Beyond that, the drift bound (driftBound): a match that turns or moves the trajectory further is a look-alike
  // (the same corner elsewhere in the building).
  if (off_theta > bound.theta || off_xy > bound.xy) {
    ++global_contradicted_;
    return false;
  }
  const double chain = nodes_[q.node].travelled - nodes_[j].travelled;
  if (chain <= o_.global_consistency_max_m) {
    const Pose2 along = relative(geometry[j], geometry[q.node]);
    const Pose2 e = relative(along, m.pose);
    if (std::hypot(e.x, e.y) > o_.global_consistency_xy + o_.window_xy_per_m * chain ||
        std::abs(e.theta) > o_.window_theta_min + o_.window_theta_per_m * chain) {
      ++global_contradicted_;
      return false;
    }
  }
  GlobalMatch g;
  g.node = q.node;
  g.place = j;
  g.z = m.pose;
  g.sqrt_information = closureSqrtInformation(grid, q.points, m.pose, q.dtheta);
  g.score = m.score;
  g.offset_xy = off_xy;
  g.offset_theta = off_theta;
  pending_.push_back(g);
  return true;
}

void LoopCloser::distributeLoopError(std::size_t place, std::size_t node, const Pose2& z) {
  if (place >= node) return;
  const Pose2 target = compose(graph_.pose(place), z);
  const double span = nodes_[node].travelled - nodes_[place].travelled;
  if (span <= 0.0) return;
  const double dtheta = wrapAngle(target.theta - graph_.pose(node).theta);
  // The heading error spread evenly over the travel from the place to the node, the chain re-integrated from the
  // place; then the remaining translation error spread the same way; the nodes after `node` follow rigidly.
  std::vector<Pose2> p(nodes_.size());
  p[place] = graph_.pose(place);
  for (std::size_t k = place + 1; k < nodes_.size(); ++k) {
    Pose2 step = relative(graph_.pose(k - 1), graph_.pose(k));
    if (k <= node) step.theta = wrapAngle(step.theta + dtheta * (nodes_[k].travelled - nodes_[k - 1].travelled) / span);
    p[k] = compose(p[k - 1], step);
  }
  const double ex = target.x - p[node].x, ey = target.y - p[node].y;
  for (std::size_t k = place + 1; k < nodes_.size(); ++k) {
    const double f = k <= node ? (nodes_[k].travelled - nodes_[place].travelled) / span : 1.0;
    graph_.setPose(k, {p[k].x + f * ex, p[k].y + f * ey, p[k].theta});
  }
}

bool LoopCloser::globalMatchesAgree(const GlobalMatch& a, const GlobalMatch& b,
                                    const std::vector<Pose2>& geometry) const {
  const double travel_q = std::abs(nodes_[b.node].travelled - nodes_[a.node].travelled);
  double travel_p = std::abs(nodes_[b.place].travelled - nodes_[a.place].travelled);
  if (travel_q > o_.global_consistency_max_m) return false;
  // The places' relative pose: along the trajectory when they are near on it; when they belong to different visits
  // of the building, through the pose graph's accepted closures, if its least-drift path between them is as short
  // (the two visits already joined: the way back matched to both passes of a corridor is two independent pieces
  // of evidence, and they must agree).
  Pose2 places;
  if (travel_p <= o_.global_consistency_max_m) {
    places = relative(geometry[a.place], geometry[b.place]);
  } else {
    const std::vector<PathDrift> drift = driftToSubmaps(a.place);
    const std::size_t s = std::min(drift.size() - 1, b.place / static_cast<std::size_t>(o_.submap_nodes));
    const Submap& sm = submaps_[s];
    // The path reaches the submap's nearest node: add the travel within the submap to the place.
    const double within = std::max(std::abs(nodes_[b.place].travelled - nodes_[sm.first].travelled),
                                   std::abs(nodes_[sm.last].travelled - nodes_[b.place].travelled));
    travel_p = drift[s].travel + within;
    if (!(travel_p <= o_.global_consistency_max_m)) return false;
    places = relative(graph_.pose(a.place), graph_.pose(b.place));
  }
  // The queries' relative pose along the trajectory, against the one the two matches imply through the places'
  // relative pose: node_a⁻¹ ⊕ node_b = z_a⁻¹ ⊕ (place_a⁻¹ ⊕ place_b) ⊕ z_b.
  const Pose2 along = relative(geometry[a.node], geometry[b.node]);
  const Pose2 implied = compose(compose(relative(a.z, Pose2{}), places), b.z);
  const Pose2 e = relative(along, implied);
  const double length = travel_q + travel_p;
  return std::hypot(e.x, e.y) <= o_.global_consistency_xy + o_.global_consistency_per_m * length &&
         std::abs(e.theta) <= o_.global_consistency_theta + 0.1 * o_.global_consistency_per_m * length;
}

void LoopCloser::verifyGlobalClosures(LoopClosureStep& step, const std::vector<Pose2>& geometry) {
  const std::size_t i = nodes_.size() - 1;
  const double now = nodes_[i].travelled;
  // Matches that waited too long without agreement are dropped.
  std::vector<GlobalMatch> kept;
  for (GlobalMatch& g : pending_) {
    if (now - nodes_[g.node].travelled <= o_.global_pending_m) kept.push_back(g);
    else if (!g.accepted) ++global_dropped_;
  }
  pending_.swap(kept);
  // For each match not yet accepted, newest first: the largest set of mutually agreeing matches it belongs to
  // (greedy, newest first); accepted when it holds an accepted match or global_agree independent matches (queries
  // global_independent_m apart, counted per pass of the place; the other passes add one at most).
  for (std::size_t k = pending_.size(); k-- > 0;) {
    if (pending_[k].accepted) continue;
    std::vector<std::size_t> clique{k};
    for (std::size_t l = pending_.size(); l-- > 0;) {
      if (l == k) continue;
      bool agrees = true;
      for (std::size_t m : clique)
        if (!globalMatchesAgree(pending_[std::min(l, m)], pending_[std::max(l, m)], geometry)) {
          agrees = false;
          break;
        }
      if (agrees) clique.push_back(l);
    }
    bool anchored = false;
    for (std::size_t m : clique) anchored = anchored || pending_[m].accepted;
    // Independent matches: per visit of the place (places further apart on the trajectory than
    // global_consistency_max_m are different passes, each its own evidence), queries at least global_independent_m
    // apart.
    std::vector<std::pair<double, double>> by_place;  // (place's travel, query's travel)
    for (std::size_t m : clique)
      by_place.emplace_back(nodes_[pending_[m].place].travelled, nodes_[pending_[m].node].travelled);
    std::sort(by_place.begin(), by_place.end());
    int independent = 0;
    for (std::size_t v = 0; v < by_place.size();) {
      std::size_t e = v + 1;
      while (e < by_place.size() && by_place[e].first - by_place[e - 1].first <= o_.global_consistency_max_m) ++e;
      std::vector<double> queries;
      for (std::size_t m = v; m < e; ++m) queries.push_back(by_place[m].second);
      independent += spacedCount(std::move(queries), o_.global_independent_m);
      v = e;
    }
    // ... and the queries alone, whatever the places: a query like a look-alike corridor matches every pass of it,
    // so the passes add one piece of evidence at most.
    std::vector<double> all_queries;
    for (const auto& [place, query] : by_place) all_queries.push_back(query);
    const int independent_queries = spacedCount(std::move(all_queries), o_.global_independent_m);
    independent = std::min(independent, independent_queries + 1);
    if (!anchored && independent < o_.global_agree) continue;
    // A first global closure after a long excursion can correct hundreds of metres and most of a radian: the
    // optimisation starts from the trajectory with that error spread along the loop (distributeLoopError).
    if (!anchored) {
      const GlobalMatch& newest = pending_[*std::max_element(clique.begin(), clique.end(), [&](std::size_t a, std::size_t b) {
        return pending_[a].node < pending_[b].node;
      })];
      distributeLoopError(newest.place, newest.node, newest.z);
      std::size_t oldest = newest.node;
      for (std::size_t m : clique) oldest = std::min(oldest, pending_[m].node);
      backfill_from_ = std::min(backfill_from_, stretchOf(oldest, 0.5 * o_.global_query_m, 0.0).first);
    }
    for (std::size_t m : clique) {
      GlobalMatch& g = pending_[m];
      if (g.accepted) continue;
      g.accepted = true;
      addClosure(g.place, g.node, g.z, g.sqrt_information, g.score, o_.global_window_xy, g.offset_xy, g.offset_theta,
                 true);
      ++step.accepted;
      optimize_now_ = true;
    }
  }
}

LoopClosureCounts LoopCloser::counts() const {
  LoopClosureCounts c;
  c.nodes = nodes_.size();
  c.searches = searches_;
  c.ambiguous = ambiguous_;
  c.on_border = border_;
  c.suspect_steps = suspect_;
  c.optimizations = optimizations_;
  for (const LoopClosureRecord& r : closures_) {
    (r.rejected ? c.rejected : c.accepted) += 1;
    if (r.global) ++c.global_accepted;
    if (!r.rejected) {
      c.largest_correction_xy = std::max(c.largest_correction_xy, r.correction_xy);
      c.largest_correction_theta = std::max(c.largest_correction_theta, r.correction_theta);
    }
  }
  c.global_searches = global_searches_;
  c.global_proposed = global_proposed_;
  c.global_dropped = global_dropped_;
  c.global_contradicted = global_contradicted_;
  c.global_refuted = global_refuted_;
  c.global_followed = global_followed_;
  c.global_beyond_bound = global_beyond_bound_;
  c.cpu_windowed = cpu_windowed_;
  c.cpu_global_sign = cpu_global_sign_;
  c.cpu_global_query = cpu_global_query_;
  c.cpu_global_verify = cpu_global_verify_;
  c.cpu_optimize = cpu_optimize_;
  return c;
}

std::string closuresText(const std::vector<LoopClosureRecord>& closures, const LoopClosureCounts& n,
                         std::size_t feedbacks) {
  std::ostringstream out;
  out << "# closures: node scan_index timestamp submap_node score window_xy offset_xy offset_theta correction_xy "
         "correction_theta residual rejected global\n";
  out << std::setprecision(10);
  for (const LoopClosureRecord& c : closures)
    out << "# closure " << c.node << ' ' << c.scan_index << ' ' << c.timestamp << ' ' << c.submap_node << ' '
        << std::setprecision(4) << c.score << ' ' << c.window_xy << ' ' << c.offset_xy << ' ' << c.offset_theta
        << ' ' << c.correction_xy << ' ' << c.correction_theta << ' ' << c.residual << ' ' << (c.rejected ? 1 : 0)
        << ' ' << (c.global ? 1 : 0)
        << std::setprecision(10) << '\n';
  out << std::setprecision(4) << "# loop_closure: nodes " << n.nodes << " searches " << n.searches << " closures "
      << n.accepted << " rejected " << n.rejected << " ambiguous " << n.ambiguous << " on_border " << n.on_border
      << " suspect_steps " << n.suspect_steps << " optimisations " << n.optimizations << " feedbacks " << feedbacks
      << " global_searches " << n.global_searches << " global_refuted " << n.global_refuted
      << " global_proposed " << n.global_proposed << " global_followed " << n.global_followed
      << " global_accepted " << n.global_accepted
      << " global_contradicted " << n.global_contradicted << " global_dropped " << n.global_dropped
      << " global_beyond_bound " << n.global_beyond_bound
      << " largest_correction_xy " << n.largest_correction_xy << " largest_correction_theta "
      << n.largest_correction_theta << '\n';
  return out.str();
}

std::string loopClosureCpuText(const LoopClosureCounts& n) {
  std::ostringstream out;
  out << std::setprecision(4) << "# loop_closure_cpu_seconds: windowed " << n.cpu_windowed << " global_sign "
      << n.cpu_global_sign << " global_query " << n.cpu_global_query << " global_verify " << n.cpu_global_verify
      << " optimise " << n.cpu_optimize << '\n';
  return out.str();
}

}  // namespace gridtopo::slam
