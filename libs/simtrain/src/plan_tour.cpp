#include "gridtopo/simtrain/plan_tour.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <queue>
#include <random>

#include "gridtopo/core/distance_transform.h"
#include "gridtopo/core/error.h"

namespace gridtopo::simtrain {

namespace {

constexpr unsigned char kRoomCode = 77, kCorridorCode = 115, kDoorwayCode = 179;

// Least-cost paths over the traversable cells, from one start to the nearest of a set of goals: 8-connected steps
// costing their length times 1 + (0.5 m / clearance)², so paths keep to the middle of corridors and doors.
class LegPlanner {
 public:
  LegPlanner(const cv::Mat& traversable, const cv::Mat& dist_m) : trav_(traversable), rows_(traversable.rows),
                                                                    cols_(traversable.cols) {
    step_cost_.resize(static_cast<std::size_t>(rows_) * cols_);
    for (int r = 0; r < rows_; ++r)
      for (int c = 0; c < cols_; ++c) {
        const float d = std::max(dist_m.at<float>(r, c), 0.01f);
        step_cost_[idx(r, c)] = 1.0f + (0.5f / d) * (0.5f / d);
      }
    cost_.resize(step_cost_.size());
    parent_.resize(step_cost_.size());
  }
  std::size_t idx(int r, int c) const { return static_cast<std::size_t>(r) * cols_ + c; }

  /// Path (start first) to the nearest cell with is_goal[idx] set; empty if none is reachable.
  std::vector<cv::Point> toNearest(cv::Point start, const std::vector<char>& is_goal) {
    std::fill(cost_.begin(), cost_.end(), std::numeric_limits<float>::infinity());
    using Item = std::pair<float, std::size_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
    const std::size_t s = idx(start.y, start.x);
    cost_[s] = 0;
    parent_[s] = s;
    q.push({0.0f, s});
    static const int dr[8] = {-1, -1, -1, 0, 0, 1, 1, 1}, dc[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
    while (!q.empty()) {
      const auto [c0, i] = q.top();
      q.pop();
      if (c0 > cost_[i]) continue;
      if (is_goal[i] && i != s) {
        std::vector<cv::Point> path;
        for (std::size_t j = i;; j = parent_[j]) {
          path.emplace_back(static_cast<int>(j % cols_), static_cast<int>(j / cols_));
          if (j == s) break;
        }
        std::reverse(path.begin(), path.end());
        return path;
      }
      const int r = static_cast<int>(i / cols_), c = static_cast<int>(i % cols_);
      for (int k = 0; k < 8; ++k) {
        const int rr = r + dr[k], cc = c + dc[k];
        if (rr < 0 || cc < 0 || rr >= rows_ || cc >= cols_ || !trav_.at<unsigned char>(rr, cc)) continue;
        const std::size_t j = idx(rr, cc);
        const float len = (dr[k] != 0 && dc[k] != 0) ? 1.41421356f : 1.0f;
        const float nc = c0 + len * 0.5f * (step_cost_[i] + step_cost_[j]);
        if (nc < cost_[j]) {
          cost_[j] = nc;
          parent_[j] = i;
          q.push({nc, j});
        }
      }
    }
    return {};
  }

 private:
  const cv::Mat& trav_;
  int rows_, cols_;
  std::vector<float> step_cost_, cost_;
  std::vector<std::size_t> parent_;
};

bool lineTraversable(const cv::Mat& trav, cv::Point a, cv::Point b) {
  cv::LineIterator it(trav, a, b, 8);
  for (int k = 0; k < it.count; ++k, ++it)
    if (!**it) return false;
  return true;
}

}  // namespace

Tour planTour(const cv::Mat& free_cells, const cv::Mat& codes, double res, const TourOptions& o,
              const std::string& source) {
  if (free_cells.empty() || free_cells.type() != CV_8U || codes.type() != CV_8U || codes.size() != free_cells.size())
    throw InputError(source, "the plan and its labels must be 8-bit images of the same size");
  if (!(res > 0) || !(o.clearance >= 0) || !(o.door_clearance >= 0) || !(o.corridor_goal_spacing > 0) || !(o.min_room_area >= 0) ||
      !(o.room_visit_probability >= 0 && o.room_visit_probability <= 1))
    throw std::invalid_argument("planTour: bad options");
  Tour t;
  const int rows = free_cells.rows, cols = free_cells.cols;
  cv::Mat free = free_cells != 0;
  cv::Mat dist = preciseDistance(free);
  dist *= res;  // metres from the cell centre to the nearest non-free cell's centre
  cv::Mat trav = free & ((dist >= o.clearance) | ((codes == kDoorwayCode) & (dist >= o.door_clearance)));
  // The robot drives in the traversable component that holds most corridor cells.
  cv::Mat comp;
  const int ncomp = cv::connectedComponents(trav, comp, 8, CV_32S);
  std::vector<long> corridor_cells(static_cast<std::size_t>(ncomp), 0);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (trav.at<unsigned char>(r, c) && codes.at<unsigned char>(r, c) == kCorridorCode)
        ++corridor_cells[static_cast<std::size_t>(comp.at<int>(r, c))];
  const int main_comp =
      static_cast<int>(std::max_element(corridor_cells.begin() + 1, corridor_cells.end()) - corridor_cells.begin());
  if (ncomp < 2 || corridor_cells[static_cast<std::size_t>(main_comp)] == 0)
    throw InputError(source, "no corridor cell lies " + std::to_string(o.clearance) +
                                 " m from every obstacle: nowhere to start the robot's tour");
  trav = comp == main_comp;
  // Start: the deepest corridor cell.
  cv::Point start(-1, -1);
  float best = -1;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (trav.at<unsigned char>(r, c) && codes.at<unsigned char>(r, c) == kCorridorCode && dist.at<float>(r, c) > best)
        best = dist.at<float>(r, c), start = {c, r};

  std::vector<char> is_goal(static_cast<std::size_t>(rows) * cols, 0);
  std::vector<int> goal_room(is_goal.size(), 0);  // room id of a room goal, -1 for a corridor goal
  // Rooms: 8-connected regions of free room cells; the goal of an entered room is its deepest reachable cell.
  cv::Mat room_mask = free & (codes == kRoomCode), stats, centroids;
  const int nrooms = cv::connectedComponentsWithStats(room_mask, t.room_ids, stats, centroids, 8, CV_32S);
  const double min_px = o.min_room_area / (res * res);
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<cv::Point> room_goal(static_cast<std::size_t>(nrooms), cv::Point(-1, -1));
  std::vector<float> room_depth(static_cast<std::size_t>(nrooms), -1.0f);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int id = t.room_ids.at<int>(r, c);
      if (id > 0 && trav.at<unsigned char>(r, c) && dist.at<float>(r, c) > room_depth[static_cast<std::size_t>(id)])
        room_depth[static_cast<std::size_t>(id)] = dist.at<float>(r, c), room_goal[static_cast<std::size_t>(id)] = {c, r};
    }
  t.room_entered.assign(static_cast<std::size_t>(std::max(0, nrooms - 1)), false);
  for (int id = 1; id < nrooms; ++id) {
    if (stats.at<int>(id, cv::CC_STAT_AREA) < min_px) continue;
    ++t.rooms;
    const bool enter = u01(rng) < o.room_visit_probability;  // drawn for every room: the draws do not depend on reach
    const cv::Point g = room_goal[static_cast<std::size_t>(id)];
    if (g.x < 0) {
      ++t.rooms_unreachable;
      continue;
    }
    if (!enter) continue;
    const std::size_t i = static_cast<std::size_t>(g.y) * cols + g.x;
    is_goal[i] = 1;
    goal_room[i] = id;
  }
  // Corridors: the deepest reachable corridor cell of every square of side corridor_goal_spacing.
  const int side = std::max(1, static_cast<int>(std::lround(o.corridor_goal_spacing / res)));
  for (int br = 0; br < rows; br += side)
    for (int bc = 0; bc < cols; bc += side) {
      cv::Point g(-1, -1);
      float d = -1;
      for (int r = br; r < std::min(rows, br + side); ++r)
        for (int c = bc; c < std::min(cols, bc + side); ++c)
          if (trav.at<unsigned char>(r, c) && codes.at<unsigned char>(r, c) == kCorridorCode && dist.at<float>(r, c) > d)
            d = dist.at<float>(r, c), g = {c, r};
      if (g.x < 0 || g == start) continue;
      const std::size_t i = static_cast<std::size_t>(g.y) * cols + g.x;
      is_goal[i] = 1;
      goal_room[i] = -1;
    }

  // Greedy tour: each leg to the nearest goal left; goals the leg passes count as reached.
  LegPlanner planner(trav, dist);
  t.cells.push_back(start);
  cv::Point at = start;
  for (;;) {
    const auto leg = planner.toNearest(at, is_goal);
    if (leg.empty()) break;
    for (std::size_t k = 1; k < leg.size(); ++k) {
      t.cells.push_back(leg[k]);
      const std::size_t i = static_cast<std::size_t>(leg[k].y) * cols + leg[k].x;
      if (!is_goal[i]) continue;
      is_goal[i] = 0;
      if (goal_room[i] > 0) t.room_entered[static_cast<std::size_t>(goal_room[i] - 1)] = true, ++t.rooms_entered;
      else ++t.corridor_goals;
    }
    at = leg.back();
  }
  // Straight legs: from each waypoint, as far along the path as the straight line stays traversable and within
  // 0.2 m of every path cell it replaces (so a trip into a room and back is not cut short).
  const double tol_px = 0.2 / res;
  auto followsPath = [&](std::size_t i, std::size_t j) {
    const cv::Point2d a = t.cells[i], b = t.cells[j];
    const cv::Point2d ab = b - a;
    const double len = std::hypot(ab.x, ab.y);
    for (std::size_t k = i + 1; k < j; ++k) {
      const cv::Point2d ap = cv::Point2d(t.cells[k]) - a;
      const double along = len > 0 ? (ap.x * ab.x + ap.y * ab.y) / len : 0;
      const double off = len > 0 ? std::abs(ap.x * ab.y - ap.y * ab.x) / len : std::hypot(ap.x, ap.y);
      if (off > tol_px || along < -tol_px || along > len + tol_px) return false;
    }
    return true;
  };
  std::vector<cv::Point> wp{t.cells.front()};
  for (std::size_t i = 0; i + 1 < t.cells.size();) {
    std::size_t j = i + 1;
    while (j + 1 < t.cells.size() && followsPath(i, j + 1) && lineTraversable(trav, t.cells[i], t.cells[j + 1])) ++j;
    wp.push_back(t.cells[j]);
    i = j;
  }
  for (std::size_t k = 0; k < wp.size(); ++k) {
    const double x = (wp[k].x + 0.5) * res, y = (rows - wp[k].y - 0.5) * res;
    double phi = 0;
    if (k + 1 < wp.size()) phi = std::atan2(-(wp[k + 1].y - wp[k].y), wp[k + 1].x - wp[k].x);
    if (k > 0) t.length += std::hypot(x - t.waypoints.back().x, y - t.waypoints.back().y);
    t.waypoints.push_back({x, y, phi});
  }
  return t;
}

}  // namespace gridtopo::simtrain
