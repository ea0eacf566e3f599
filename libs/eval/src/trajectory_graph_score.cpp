#include "gridtopo/eval/trajectory_graph_score.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/door_passages.h"

namespace gridtopo::eval {

using namespace gridtopo::topology;

namespace {
constexpr int kRoom = static_cast<int>(places::PlaceLabel::Room);
constexpr int kCorridor = static_cast<int>(places::PlaceLabel::Corridor);
constexpr int kDoorway = static_cast<int>(places::PlaceLabel::Doorway);

// Whether the graph has a doorway node within door_reach of the crossing point `c` (map cells), and one with a
// neighbour on either side: a node holding, within side_reach of `c`, more cells of plan region a than of b (side
// a) or more of b than of a (side b).
std::pair<bool, bool> judgeCrossing(cv::Point2d c, int a, int b, const TopologicalGraph& g, const RegionMap& rm,
                                    const PlanGraph& plan, double resolution, const TrajectoryScoreOptions& o,
                                    const std::map<int, std::vector<int>>& neighbours) {
  const double side = o.side_reach / resolution, reach = o.door_reach / resolution;
  const int r = static_cast<int>(std::ceil(side));
  const cv::Rect box = cv::Rect(static_cast<int>(std::floor(c.x)) - r, static_cast<int>(std::floor(c.y)) - r,
                                2 * r + 1, 2 * r + 1) &
                       cv::Rect(0, 0, rm.ids.cols, rm.ids.rows);
  std::map<int, long long> in_a, in_b;
  std::set<int> at_door;
  for (int y = box.y; y < box.y + box.height; ++y)
    for (int x = box.x; x < box.x + box.width; ++x) {
      const int n = rm.ids.at<int>(y, x);
      const GraphNode* node = n > 0 ? g.node(n) : nullptr;
      if (!node) continue;
      const double d = std::hypot(x + 0.5 - c.x, y + 0.5 - c.y);
      if (node->label == kDoorway) {
        if (d <= reach) at_door.insert(n);
        continue;
      }
      if (d > side) continue;
      const int p = plan.regions.at<int>(y, x);
      if (p == a) ++in_a[n];
      if (p == b) ++in_b[n];
    }
  const auto count = [](const std::map<int, long long>& m, int n) {
    const auto it = m.find(n);
    return it == m.end() ? 0LL : it->second;
  };
  bool found = false;
  for (int d : at_door) {
    const auto it = neighbours.find(d);
    if (it == neighbours.end()) continue;
    bool on_a = false, on_b = false;
    for (int n : it->second) {
      on_a = on_a || count(in_a, n) > count(in_b, n);
      on_b = on_b || count(in_b, n) > count(in_a, n);
    }
    found = found || (on_a && on_b);
  }
  return {!at_door.empty(), found};
}
}  // namespace

TrajectoryGraphScore scoreGraphAlongPath(const TopologicalGraph& g, const RegionMap& rm, const PlanGraph& plan,
                                         const std::vector<cv::Point2d>& path, double resolution,
                                         const TrajectoryScoreOptions& o) {
  CV_Assert(rm.ids.size() == plan.regions.size());
  TrajectoryGraphScore s;
  s.has_trajectory = !path.empty();
  std::map<int, std::vector<int>> neighbours;
  for (const GraphEdge& e : g.edges) neighbours[e.a].push_back(e.b), neighbours[e.b].push_back(e.a);
  std::map<std::pair<int, int>, std::size_t> door_index;  // plan link -> index in s.doors
  std::set<std::pair<int, int>> spurious_pairs;
  const auto label = [&](int n) { return g.node(n) ? g.node(n)->label : -1; };
  // The last scored plan region and where the path was last in it.
  int last_region = 0;
  cv::Point2d last_in_region;
  // Runs of the path in one non-doorway node, each with the plan region holding most of its cells (0: none):
  // a node change is spurious when the two runs' plan regions are the same (robust to borders offset from the
  // plan's).
  struct Run {
    int node = 0;
    std::map<int, int> plan;
    int region() const {
      int best = 0, most = 0;
      for (const auto& [p, k] : plan)
        if (k > most) best = p, most = k;
      return best;
    }
  };
  Run previous, current;
  const auto close_run = [&]() {
    if (!current.node) return;
    if (previous.node && previous.node != current.node) {
      ++s.node_changes;
      const int a = previous.region(), b = current.region();
      if (a && b) {
        ++s.node_changes_scored;
        if (a == b) {
          ++s.spurious_splits;
          const int la = label(previous.node), lb = label(current.node);
          if ((la == kRoom && lb == kCorridor) || (la == kCorridor && lb == kRoom)) ++s.spurious_label_changes;
          spurious_pairs.insert({std::min(previous.node, current.node), std::max(previous.node, current.node)});
        }
      }
    }
    previous = std::move(current);
    current = Run{};
  };
  for (const cv::Point2d& q : samplePath(path)) {
    if (std::isnan(q.x)) {  // a gap in the trajectory: start afresh
      close_run();
      last_region = 0;
      previous = Run{};
      continue;
    }
    const int x = static_cast<int>(std::floor(q.x)), y = static_cast<int>(std::floor(q.y));
    if (x < 0 || y < 0 || x >= rm.ids.cols || y >= rm.ids.rows) continue;
    int p = plan.regions.at<int>(y, x);
    if (p && !plan.kind.count(p)) p = 0;
    if (p) {
      if (last_region && p != last_region) {
        ++s.region_changes;
        const std::pair<int, int> link{std::min(p, last_region), std::max(p, last_region)};
        const auto it = plan.links.find(link);
        if (it != plan.links.end() && it->second) {  // through a door of the plan
          ++s.region_changes_through_door;
          const auto [at, fresh] = door_index.emplace(link, s.doors.size());
          if (fresh) {
            DoorCrossed c;
            c.plan_a = last_region, c.plan_b = p;
            s.doors.push_back(c);
          }
          DoorCrossed& d = s.doors[at->second];
          const cv::Point2d mid = (last_in_region + q) * 0.5;
          const auto [node, found] = judgeCrossing(mid, last_region, p, g, rm, plan, resolution, o, neighbours);
          if (d.crossings == 0 || (found && !d.found) || (node && !d.doorway_node))
            d.at = cv::Point(static_cast<int>(std::floor(mid.x)), static_cast<int>(std::floor(mid.y)));
          ++d.crossings;
          d.doorway_node = d.doorway_node || node;
          d.found = d.found || found;
        }
      }
      last_region = p;
      last_in_region = q;
    }
    const int n = rm.ids.at<int>(y, x);
    if (n <= 0 || label(n) == kDoorway || label(n) < 0) continue;
    if (n != current.node) {
      close_run();
      current.node = n;
    }
    if (p) ++current.plan[p];
  }
  close_run();
  s.spurious_boundaries = static_cast<int>(spurious_pairs.size());
  for (const DoorCrossed& d : s.doors) {
    ++s.doors_crossed;
    s.doors_with_doorway_node += d.doorway_node;
    s.doors_found += d.found;
  }
  return s;
}

std::string TrajectoryGraphScore::toJson() const {
  std::ostringstream o;
  o << "{\"has_trajectory\": " << (has_trajectory ? "true" : "false") << ", \"doors_crossed\": " << doors_crossed
    << ", \"doors_with_doorway_node\": " << doors_with_doorway_node << ", \"doors_found\": " << doors_found
    << ", \"doors_found_fraction\": " << doorsFoundFraction() << ", \"node_changes\": " << node_changes
    << ", \"node_changes_scored\": " << node_changes_scored << ", \"spurious_splits\": " << spurious_splits
    << ", \"spurious_label_changes\": " << spurious_label_changes
    << ", \"spurious_boundaries\": " << spurious_boundaries << ", \"region_changes\": " << region_changes
    << ", \"region_changes_through_door\": " << region_changes_through_door << ",\n    \"doors\": [";
  for (std::size_t i = 0; i < doors.size(); ++i) {
    const DoorCrossed& d = doors[i];
    o << (i ? ", " : "") << "{\"plan_a\": " << d.plan_a << ", \"plan_b\": " << d.plan_b
      << ", \"at\": [" << d.at.x << ", " << d.at.y << "], \"crossings\": " << d.crossings
      << ", \"doorway_node\": " << (d.doorway_node ? "true" : "false")
      << ", \"found\": " << (d.found ? "true" : "false") << "}";
  }
  o << "]}";
  return o.str();
}

}  // namespace gridtopo::eval
