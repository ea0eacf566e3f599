#include "gridtopo/slam/loop_closure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>
#include <unordered_set>

namespace gridtopo::slam {

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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

Point2 transform(const Pose2& t, const Point2& p) {
  const double c = std::cos(t.theta), s = std::sin(t.theta);
  return {t.x + c * p.x - s * p.y, t.y + s * p.x + c * p.y};
}

}  // namespace

LoopCloser::LoopCloser(const LoopClosureOptions& options) : o_(options) { o_.validate(); }

LoopClosureStep LoopCloser::addScan(std::size_t scan_index, double timestamp, const Pose2& filter_pose,
                                    const Pose2& motion, const Pose2* odometry, const PreparedScan& scan) {
  LoopClosureStep step;
  addFilterMotion(scan_index, timestamp, filter_pose, motion, odometry, scan);
  const std::size_t i = nodes_.size() - 1;
  step.newest_before = step.newest_after = graph_.pose(i);
  if (i % static_cast<std::size_t>(o_.search_every) == 0) searchForClosures(step);
  const bool pending = pending_from_ < closures_.size();
  // Optimise every optimize_every scans while closures are pending, and at once after a closure that moves the
  // estimate by more than a few deviations (the first closure after a long excursion).
  const bool large = step.accepted > 0 && closures_.back().offset_xy > 4.0 * o_.loop_sigma_xy;
  if (pending && (i - last_optimized_node_ >= static_cast<std::size_t>(o_.optimize_every) || large))
    optimizePoseGraph(step);
  return step;
}

void LoopCloser::finish() {
  LoopClosureStep step;
  if (pending_from_ < closures_.size()) optimizePoseGraph(step);
}

std::vector<Pose2> LoopCloser::poses() const {
  std::vector<Pose2> p(graph_.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = graph_.pose(i);
  return p;
}

void LoopCloser::addFilterMotion(std::size_t scan_index, double timestamp, const Pose2& filter_pose,
                                 const Pose2& motion, const Pose2* odometry, const PreparedScan& scan) {
  Node n;
  n.scan_index = scan_index;
  n.timestamp = timestamp;
  const double dist = std::hypot(motion.x, motion.y);
  n.travelled = nodes_.empty() ? 0.0 : nodes_.back().travelled + dist;
  const double r2 = o_.point_range * o_.point_range;
  for (const MapBeam& b : scan.map_beams) {
    if (!b.hit) continue;
    const double dx = b.ex - scan.sensor.x, dy = b.ey - scan.sensor.y;
    if (dx * dx + dy * dy > r2) continue;
    n.points.push_back({b.ex, b.ey});
  }
  thinInPlace(n.points, o_.resolution);
  n.points.shrink_to_fit();
  if (nodes_.empty()) {
    graph_.addNode(filter_pose);
    dead_reckoned_ = filter_pose;
  } else {
    const std::size_t prev = nodes_.size() - 1;
    graph_.addNode(compose(graph_.pose(prev), motion));
    dead_reckoned_ = compose(dead_reckoned_, odometry ? *odometry : motion);
    PoseGraphEdge e;
    e.a = prev;
    e.b = prev + 1;
    e.z = motion;
    // The disagreement with the odometry adds to the deviation: a filter that followed something moving with the
    // robot (or an odometry that slipped) leaves an edge a closure can bend.
    const double dxy = odometry ? std::hypot(motion.x - odometry->x, motion.y - odometry->y) : 0.0;
    const double dth = odometry ? std::abs(wrapAngle(motion.theta - odometry->theta)) : 0.0;
    const double sxy = o_.odometry_sigma_xy + o_.odometry_sigma_xy_per_m * dist + dxy;
    const double st = o_.odometry_sigma_theta + o_.odometry_sigma_theta_per_rad * std::abs(motion.theta) + dth;
    e.sqrt_information = sqrtInformationOfSigmas(sxy, sxy, st);
    graph_.addEdge(e);
  }
  nodes_.push_back(std::move(n));
  // Submaps: runs of submap_nodes consecutive nodes.
  const std::size_t i = nodes_.size() - 1;
  if (submaps_.empty() || submaps_.back().last + 1 - submaps_.back().first >= static_cast<std::size_t>(o_.submap_nodes))
    submaps_.push_back({i, i});
  else
    submaps_.back().last = i;
}

std::vector<Point2> LoopCloser::queryOf(std::size_t node) const {
  std::vector<Point2> q;
  const std::size_t n = std::min(nodes_.size(), static_cast<std::size_t>(o_.query_nodes));
  const Pose2& ref = graph_.pose(node);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t j = node - k;  // newest first, so the thinning keeps the newest scan's points
    const Pose2 rel = relative(ref, graph_.pose(j));
    for (const Point2& p : nodes_[j].points) q.push_back(transform(rel, p));
  }
  thinInPlace(q, o_.query_voxel);
  return q;
}

const CorrelationGrid& LoopCloser::gridOf(std::size_t s) {
  for (auto it = cache_.begin(); it != cache_.end(); ++it)
    if (it->first == s) {
      cache_.splice(cache_.end(), cache_, it);
      return *cache_.back().second;
    }
  // The submap's points in the frame of its first node, at the current poses (then kept rigid).
  const Submap& sm = submaps_[s];
  const Pose2& anchor = graph_.pose(sm.first);
  std::vector<Point2> pts;
  for (std::size_t j = sm.first; j <= sm.last; ++j) {
    const Pose2 rel = relative(anchor, graph_.pose(j));
    for (const Point2& p : nodes_[j].points) pts.push_back(transform(rel, p));
  }
  thinInPlace(pts, o_.resolution);
  cache_.emplace_back(s, std::make_unique<CorrelationGrid>(pts, o_.resolution, o_.field_sigma, o_.depth));
  while (cache_.size() > static_cast<std::size_t>(o_.grid_cache)) cache_.pop_front();
  return *cache_.back().second;
}

void LoopCloser::searchForClosures(LoopClosureStep& step) {
  const std::size_t i = nodes_.size() - 1;
  if (i + 1 < static_cast<std::size_t>(o_.query_nodes)) return;
  const auto t0 = std::chrono::steady_clock::now();
  const Node& cur = nodes_[i];
  const Pose2& x = graph_.pose(i);
  const double since = cur.travelled - travelled_at_closure_;
  // The window grows with the travel since the last closure and covers the odometry's dead reckoning from there.
  const double off_xy = std::hypot(dead_reckoned_.x - x.x, dead_reckoned_.y - x.y);
  const double off_th = std::abs(wrapAngle(dead_reckoned_.theta - x.theta));
  const double wxy = std::min(o_.window_xy_max, o_.window_xy_min + o_.window_xy_per_m * since + off_xy);
  const double wth = std::min(o_.window_theta_max, o_.window_theta_min + o_.window_theta_per_m * since + off_th);
  // Candidates: complete submaps left at least min_travel ago, one of whose poses lies within the window (plus
  // the reach of a view) of the current estimate; nearest first.
  const double reach = wxy + 0.5 * o_.point_range;
  std::vector<std::pair<double, std::size_t>> cand;
  for (std::size_t s = 0; s < submaps_.size(); ++s) {
    const Submap& sm = submaps_[s];
    if (sm.last + 1 - sm.first < static_cast<std::size_t>(o_.submap_nodes)) continue;
    if (cur.travelled - nodes_[sm.last].travelled < o_.min_travel) continue;
    double best = reach;
    for (std::size_t j = sm.first; j <= sm.last; ++j) {
      const Pose2& p = graph_.pose(j);
      best = std::min(best, std::hypot(p.x - x.x, p.y - x.y));
    }
    if (best < reach) cand.emplace_back(best, s);
  }
  std::sort(cand.begin(), cand.end());
  if (cand.size() > static_cast<std::size_t>(o_.max_candidates)) cand.resize(static_cast<std::size_t>(o_.max_candidates));
  if (cand.empty()) {
    search_s_ += secondsSince(t0);
    return;
  }
  const std::vector<Point2> query = queryOf(i);
  if (query.size() < 20) {
    search_s_ += secondsSince(t0);
    return;
  }
  double d_max = o_.resolution;
  for (const Point2& q : query) d_max = std::max(d_max, std::hypot(q.x, q.y));
  const double dtheta = std::acos(std::max(-1.0, 1.0 - o_.resolution * o_.resolution / (2.0 * d_max * d_max)));
  for (const auto& [dist, s] : cand) {
    (void)dist;
    const Submap& sm = submaps_[s];
    const CorrelationGrid& grid = gridOf(s);
    SearchWindow w;
    w.center = relative(graph_.pose(sm.first), x);
    w.xy = wxy;
    w.theta = wth;
    ++step.searches;
    const auto found = branchAndBoundSearch(grid, query, w, o_.min_score);
    if (!found) continue;
    const CorrelativeMatch m = refineMatch(grid, query, found->pose, dtheta);
    if (m.score < o_.min_score) continue;
    // Refuse look-alikes: a distinct pose of the window that scores nearly as well.
    const Point2 at{m.pose.x, m.pose.y};
    double second = 0.0;
    if (o_.ambiguity_ratio < 1.0) {
      const auto other = branchAndBoundSearch(grid, query, w, std::max(o_.min_score, o_.ambiguity_ratio * m.score), &at,
                                              o_.ambiguity_distance);
      if (other) {
        ++step.refused_ambiguous;
        continue;
      }
    }
    PoseGraphEdge e;
    e.a = sm.first;
    e.b = i;
    e.z = m.pose;
    e.sqrt_information = sqrtInformationOfSigmas(o_.loop_sigma_xy, o_.loop_sigma_xy, o_.loop_sigma_theta);
    e.robust = true;
    graph_.addEdge(e);
    LoopClosureRecord rec;
    rec.node = i;
    rec.scan_index = cur.scan_index;
    rec.timestamp = cur.timestamp;
    rec.submap_node = sm.first;
    rec.score = m.score;
    rec.second_score = second;
    rec.window_xy = wxy;
    rec.offset_xy = std::hypot(m.pose.x - w.center.x, m.pose.y - w.center.y);
    rec.offset_theta = std::abs(wrapAngle(m.pose.theta - w.center.theta));
    closures_.push_back(rec);
    ++step.accepted;
    travelled_at_closure_ = cur.travelled;
    dead_reckoned_ = compose(graph_.pose(sm.first), m.pose);
  }
  search_s_ += secondsSince(t0);
}

void LoopCloser::optimizePoseGraph(LoopClosureStep& step) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t i = nodes_.size() - 1;
  const Pose2 before = graph_.pose(i);
  PoseGraphSolveOptions so;
  so.huber_scale = o_.huber_scale;
  so.max_iterations = o_.max_iterations;
  graph_.optimize(so);
  const Pose2 after = graph_.pose(i);
  const Pose2 d = relative(before, after);
  for (std::size_t k = pending_from_; k < closures_.size(); ++k) {
    closures_[k].correction_xy = std::hypot(after.x - before.x, after.y - before.y);
    closures_[k].correction_theta = std::abs(d.theta);
  }
  pending_from_ = closures_.size();
  last_optimized_node_ = i;
  step.optimized = true;
  step.newest_before = before;
  step.newest_after = after;
  step.feedback = o_.feedback && (std::hypot(after.x - before.x, after.y - before.y) > o_.feedback_min_correction ||
                                  std::abs(d.theta) > o_.feedback_min_rotation);
  optimize_s_ += secondsSince(t0);
}

std::string closuresText(const std::vector<LoopClosureRecord>& closures) {
  std::ostringstream out;
  out << "# closures: node scan_index timestamp submap_node score window_xy offset_xy offset_theta correction_xy "
         "correction_theta\n";
  out << std::setprecision(10);
  for (const LoopClosureRecord& c : closures)
    out << "# closure " << c.node << ' ' << c.scan_index << ' ' << c.timestamp << ' ' << c.submap_node << ' '
        << std::setprecision(4) << c.score << ' ' << c.window_xy << ' ' << c.offset_xy << ' ' << c.offset_theta
        << ' ' << c.correction_xy << ' ' << c.correction_theta << std::setprecision(10) << '\n';
  return out.str();
}

}  // namespace gridtopo::slam
