#include "gridtopo/eval/graph_evaluation.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "gridtopo/core/distance_transform.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::eval {

using namespace gridtopo::topology;

namespace {
constexpr int kRoom = static_cast<int>(places::PlaceLabel::Room);
constexpr int kCorridor = static_cast<int>(places::PlaceLabel::Corridor);
constexpr int kDoorway = static_cast<int>(places::PlaceLabel::Doorway);
constexpr unsigned char kRoomCode = 77, kCorridorCode = 115, kDoorwayCode = 179;

// Angle swept by the polyline around p (radians, counter-clockwise in image axes positive).
double sweptAngle(const std::vector<cv::Point2d>& line, cv::Point2d p) {
  double sum = 0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    const cv::Point2d u = line[i - 1] - p, v = line[i] - p;
    sum += std::atan2(u.x * v.y - u.y * v.x, u.x * v.x + u.y * v.y);
  }
  return sum;
}

// The drawn geometry of a graph edge from node `from` to its other end: the routed path, or the straight line
// between the anchors for an edge without one.
std::vector<cv::Point2d> edgeLine(const TopologicalGraph& g, const GraphEdge& e, int from) {
  std::vector<cv::Point2d> line;
  if (e.path_px.size() >= 2) {
    for (const cv::Point& q : e.path_px) line.emplace_back(q);
  } else {
    line.emplace_back(g.node(e.a)->anchor_px);
    line.emplace_back(g.node(e.b)->anchor_px);
  }
  if (from != e.a) std::reverse(line.begin(), line.end());
  return line;
}
}  // namespace

PlanGraph planGraphFromReference(const cv::Mat& map_free, const cv::Mat& reference_free, const cv::Mat& reference_codes,
                                 const cv::Mat& reference_rooms, const ReferenceAlignment& alignment,
                                 double resolution, const PlanGraphOptions& o) {
  CV_Assert(reference_codes.type() == CV_8U && reference_rooms.type() == CV_32S);
  CV_Assert(reference_codes.size() == reference_rooms.size() && reference_free.size() == reference_rooms.size());
  PlanGraph plan;
  const cv::Size size = map_free.size();
  // Plan regions on the map's free cells; small ones are not scored.
  plan.regions = warpReferenceToMap(reference_rooms, alignment, size);
  plan.regions.setTo(0, map_free == 0);
  std::map<int, int> cells;
  for (int y = 0; y < plan.regions.rows; ++y)
    for (int x = 0; x < plan.regions.cols; ++x)
      if (const int r = plan.regions.at<int>(y, x)) ++cells[r];
  for (int y = 0; y < plan.regions.rows; ++y)
    for (int x = 0; x < plan.regions.cols; ++x) {
      int& r = plan.regions.at<int>(y, x);
      if (r && cells[r] < o.min_region_cells) r = 0;
    }
  // Kind: the majority of the room and corridor labels of the region's plan pixels.
  std::map<int, std::pair<long long, long long>> votes;
  for (int y = 0; y < reference_rooms.rows; ++y)
    for (int x = 0; x < reference_rooms.cols; ++x) {
      const int r = reference_rooms.at<int>(y, x);
      const unsigned char c = reference_codes.at<unsigned char>(y, x);
      if (!r || !cells.count(r) || cells[r] < o.min_region_cells) continue;
      auto& v = votes[r];
      v.first += c == kRoomCode, v.second += c == kCorridorCode;
    }
  for (const auto& [r, v] : votes) plan.kind[r] = v.second > v.first ? kCorridor : kRoom;
  // Openings: free plan pixels outside every ground-truth region (the lines that close doors and passages), each
  // 8-connected set joining the scored plan regions within reach; a doorway when a doorway pixel is within reach.
  cv::Mat open_ids;
  const int openings = cv::connectedComponents((reference_free != 0) & (reference_rooms == 0), open_ids, 8, CV_32S);
  std::vector<std::set<int>> sides(static_cast<std::size_t>(openings));
  std::vector<bool> is_door(static_cast<std::size_t>(openings), false);
  const int k = o.doorway_reach;
  for (int y = 0; y < open_ids.rows; ++y)
    for (int x = 0; x < open_ids.cols; ++x) {
      const int d = open_ids.at<int>(y, x);
      if (!d) continue;
      for (int yy = std::max(0, y - k); yy <= std::min(open_ids.rows - 1, y + k); ++yy)
        for (int xx = std::max(0, x - k); xx <= std::min(open_ids.cols - 1, x + k); ++xx) {
          if (const int r = reference_rooms.at<int>(yy, xx); r && plan.kind.count(r)) sides[static_cast<std::size_t>(d)].insert(r);
          if (reference_codes.at<unsigned char>(yy, xx) == kDoorwayCode) is_door[static_cast<std::size_t>(d)] = true;
        }
    }
  for (std::size_t d = 1; d < sides.size(); ++d)
    for (auto i = sides[d].begin(); i != sides[d].end(); ++i)
      for (auto j = std::next(i); j != sides[d].end(); ++j) {
        const auto [it, fresh] = plan.links.emplace(std::make_pair(*i, *j), is_door[d]);
        if (!fresh) it->second = it->second || is_door[d];
      }
  // Loops: holes of the plan's corridor cells on the map's free cells (4-connected components of the other cells
  // that touch no image border), at least min_loop_area; the point is the hole's cell farthest from its border.
  cv::Mat codes = warpReferenceToMap(reference_codes, alignment, size);
  const cv::Mat corridor = (codes == kCorridorCode) & (map_free != 0);
  cv::Mat hole_ids, stats, centroids;
  const int holes = cv::connectedComponentsWithStats(corridor == 0, hole_ids, stats, centroids, 4, CV_32S);
  const double min_cells = o.min_loop_area / (resolution * resolution);
  for (int h = 1; h < holes; ++h) {
    const int x0 = stats.at<int>(h, cv::CC_STAT_LEFT), y0 = stats.at<int>(h, cv::CC_STAT_TOP);
    const int w = stats.at<int>(h, cv::CC_STAT_WIDTH), ht = stats.at<int>(h, cv::CC_STAT_HEIGHT);
    if (x0 == 0 || y0 == 0 || x0 + w == size.width || y0 + ht == size.height) continue;
    if (stats.at<int>(h, cv::CC_STAT_AREA) < min_cells) continue;
    const cv::Rect roi(x0 - 1, y0 - 1, w + 2, ht + 2);
    const cv::Mat dist = preciseDistance(hole_ids(roi) == h);
    cv::Point at;
    cv::minMaxLoc(dist, nullptr, nullptr, nullptr, &at);
    plan.loop_points.push_back(at + roi.tl());
  }
  return plan;
}

cv::Mat planLabelsOnMap(const cv::Mat& map_free, const cv::Mat& reference_codes, const ReferenceAlignment& alignment) {
  cv::Mat labels = places::labelsFromCodes(warpReferenceToMap(reference_codes, alignment, map_free.size()));
  labels.setTo(places::kNoLabel, map_free == 0);
  return labels;
}

GraphScore scoreGraph(const TopologicalGraph& g, const RegionMap& rm, const PlanGraph& plan,
                      const GraphScoreOptions& o) {
  CV_Assert(rm.ids.size() == plan.regions.size());
  GraphScore s;
  // Cells of every node in every plan region.
  std::map<int, std::map<int, long long>> count;  // node -> plan region -> cells
  std::map<int, long long> in_plan, plan_cells;
  for (int y = 0; y < rm.ids.rows; ++y)
    for (int x = 0; x < rm.ids.cols; ++x) {
      const int p = plan.regions.at<int>(y, x);
      if (!p) continue;
      ++plan_cells[p];
      if (const int n = rm.ids.at<int>(y, x); n > 0) ++count[n][p], ++in_plan[n];
    }
  std::map<int, int> lies_in, mostly_in;  // node -> plan region holding >= purity / the most of its cells
  for (const auto& [n, per] : count) {
    const auto best = std::max_element(per.begin(), per.end(), [](auto& a, auto& b) { return a.second < b.second; });
    mostly_in[n] = best->first;
    if (best->second >= o.purity * static_cast<double>(in_plan[n])) lies_in[n] = best->first;
  }
  std::map<int, std::vector<const GraphEdge*>> incident;
  for (const auto& e : g.edges) incident[e.a].push_back(&e), incident[e.b].push_back(&e);
  auto other = [](const GraphEdge& e, int n) { return e.a == n ? e.b : e.a; };
  auto label = [&](int n) { return g.node(n) ? g.node(n)->label : -1; };
  // Plan rooms.
  for (const auto& [p, kind] : plan.kind) {
    if (kind != kRoom || !plan_cells.count(p)) continue;
    PlanRoomMatch m;
    m.plan_region = p;
    int inside = 0;
    for (const auto& [n, q] : lies_in)
      if (q == p && label(n) != kDoorway) ++m.nodes_inside, inside = n;
    m.one_room_node = m.nodes_inside == 1 && label(inside) == kRoom &&
                      count[inside][p] >= o.coverage * static_cast<double>(plan_cells[p]);
    if (m.one_room_node) m.node = inside;
    for (const auto& [ab, door] : plan.links)
      if (ab.first == p || ab.second == p) m.has_plan_opening = true;
    // Is node t the right end of an opening from p (through a doorway node when `via_door`)? The far end only has
    // to hold more of its cells in Q than in any other plan region: a corridor piece at a junction spans the plan's
    // corridor regions that meet there.
    auto right_end = [&](int t, bool via_door) {
      if (t == m.node || label(t) == kDoorway || !mostly_in.count(t)) return false;
      const int q = mostly_in[t];
      const auto it = plan.links.find({std::min(p, q), std::max(p, q)});
      return it != plan.links.end() && (via_door || !it->second);
    };
    if (m.one_room_node)
      for (const GraphEdge* e : incident[m.node]) {
        const int d = other(*e, m.node);
        if (label(d) != kDoorway) {
          m.attached = m.attached || right_end(d, false);
          continue;
        }
        for (const GraphEdge* f : incident[d]) m.attached = m.attached || right_end(other(*f, d), true);
      }
    ++s.plan_rooms, s.one_room_node += m.one_room_node, s.attached += m.attached;
    s.rooms.push_back(m);
  }
  // The corridor subgraph: corridor nodes, joined by corridor-corridor edges and through doorway nodes that touch
  // two corridor nodes. Every link keeps its drawn geometry (oriented from `u` to `v`).
  struct Link {
    int u, v;
    std::vector<cv::Point2d> line;
  };
  std::vector<Link> links;
  for (const auto& e : g.edges)
    if (label(e.a) == kCorridor && label(e.b) == kCorridor) links.push_back({e.a, e.b, edgeLine(g, e, e.a)});
  for (const auto& n : g.nodes) {
    if (n.label != kDoorway) continue;
    std::vector<const GraphEdge*> to_corridor;
    for (const GraphEdge* e : incident[n.id])
      if (label(other(*e, n.id)) == kCorridor) to_corridor.push_back(e);
    for (std::size_t i = 0; i < to_corridor.size(); ++i)
      for (std::size_t j = i + 1; j < to_corridor.size(); ++j) {
        const int u = other(*to_corridor[i], n.id), v = other(*to_corridor[j], n.id);
        std::vector<cv::Point2d> line = edgeLine(g, *to_corridor[i], u), second = edgeLine(g, *to_corridor[j], n.id);
        line.insert(line.end(), second.begin(), second.end());
        links.push_back({u, v, line});
      }
  }
  // Spanning forest (breadth-first, in node order); every other link closes one fundamental cycle. The winding
  // number of a cycle around a point is the sum of its links' swept angles, and the fundamental cycles are a basis
  // of all cycles: a loop point is encircled by some cycle of corridor nodes iff by some fundamental cycle.
  std::map<int, std::vector<int>> adj;
  for (std::size_t i = 0; i < links.size(); ++i)
    adj[links[i].u].push_back(static_cast<int>(i)), adj[links[i].v].push_back(static_cast<int>(i));
  std::map<int, int> parent_link, depth;
  std::vector<bool> tree(links.size(), false);
  for (const auto& n : g.nodes) {
    if (n.label != kCorridor || depth.count(n.id)) continue;
    depth[n.id] = 0, parent_link[n.id] = -1;
    std::vector<int> queue{n.id};
    for (std::size_t h = 0; h < queue.size(); ++h)
      for (int li : adj[queue[h]]) {
        const int w = links[static_cast<std::size_t>(li)].u == queue[h] ? links[static_cast<std::size_t>(li)].v
                                                                         : links[static_cast<std::size_t>(li)].u;
        if (depth.count(w)) continue;
        depth[w] = depth[queue[h]] + 1, parent_link[w] = li, tree[static_cast<std::size_t>(li)] = true;
        queue.push_back(w);
      }
  }
  // Swept angle of a link traversed from node `from`.
  auto swept = [&](int li, int from, cv::Point2d p) {
    const Link& l = links[static_cast<std::size_t>(li)];
    const double a = sweptAngle(l.line, p);
    return l.u == from ? a : -a;
  };
  auto up = [&](int node) {  // the parent of `node` in the forest
    const Link& l = links[static_cast<std::size_t>(parent_link[node])];
    return l.u == node ? l.v : l.u;
  };
  std::vector<bool> closed(plan.loop_points.size(), false);
  for (std::size_t li = 0; li < links.size(); ++li) {
    if (tree[li]) continue;
    ++s.corridor_cycles;
    for (std::size_t k = 0; k < plan.loop_points.size(); ++k) {
      const cv::Point2d p(plan.loop_points[k]);
      // Cycle: u -> v along the link, then v up to the common ancestor and down to u.
      int u = links[li].u, v = links[li].v;
      double total = swept(static_cast<int>(li), u, p);
      std::vector<std::pair<int, int>> down;  // (link, from) traversed from the ancestor towards u, in reverse
      while (u != v) {
        if (depth[v] >= depth[u]) {
          const int w = up(v);
          total += swept(parent_link[v], v, p);
          v = w;
        } else {
          const int w = up(u);
          down.push_back({parent_link[u], w});
          u = w;
        }
      }
      for (const auto& [l, from] : down) total += swept(l, from, p);
      if (std::lround(total / (2 * M_PI)) != 0) closed[k] = true;
    }
  }
  s.plan_loops = static_cast<int>(plan.loop_points.size());
  s.loops_closed = static_cast<int>(std::count(closed.begin(), closed.end(), true));
  return s;
}

GraphComparison compareGraphWithPlan(const cv::Mat& map_free, const cv::Mat& labels, double resolution,
                                     const TopologyOptions& options, const cv::Mat& reference_free,
                                     const cv::Mat& reference_codes, const cv::Mat& reference_rooms,
                                     const ReferenceAlignment& alignment) {
  GraphComparison c;
  c.regions = graphRegionsOfLabels(labels, resolution, options);
  c.graph = buildGraph(c.regions, resolution);
  c.plan = planGraphFromReference(map_free, reference_free, reference_codes, reference_rooms, alignment, resolution);
  const PlanGraph& plan = c.plan;
  c.score = scoreGraph(c.graph, c.regions, plan);
  TopologyOptions no_vote = options;
  no_vote.blob_vote.enabled = false;
  const TopologyResult ceiling =
      buildTopology(planLabelsOnMap(map_free, reference_codes, alignment), resolution, no_vote);
  c.plan_labels = scoreGraph(ceiling.graph, ceiling.regions, plan);
  c.plan_labels_labels = ceiling.labels;
  c.plan_labels_segmentation = ceiling.segmentation;
  return c;
}

std::string GraphScore::toJson() const {
  std::ostringstream o;
  o << "{\"plan_rooms\": " << plan_rooms << ", \"one_room_node\": " << one_room_node << ", \"attached\": " << attached
    << ", \"attached_fraction\": " << attachedFraction() << ", \"plan_loops\": " << plan_loops
    << ", \"loops_closed\": " << loops_closed << ", \"loops_are_corridor_cycles\": " << (loopsClosed() ? "true" : "false")
    << ", \"corridor_cycles\": " << corridor_cycles << ",\n    \"rooms\": [";
  for (std::size_t i = 0; i < rooms.size(); ++i) {
    const auto& m = rooms[i];
    o << (i ? ", " : "") << "{\"plan_region\": " << m.plan_region << ", \"nodes_inside\": " << m.nodes_inside
      << ", \"node\": " << m.node << ", \"one_room_node\": " << (m.one_room_node ? "true" : "false")
      << ", \"has_plan_opening\": " << (m.has_plan_opening ? "true" : "false")
      << ", \"attached\": " << (m.attached ? "true" : "false") << "}";
  }
  o << "]}";
  return o.str();
}

}  // namespace gridtopo::eval
