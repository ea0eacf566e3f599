#include "gridtopo/topology/graph.h"

#include <functional>
#include <cmath>
#include <map>
#include <numeric>

#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/edge_route.h"

namespace gridtopo::topology {

const GraphNode* TopologicalGraph::node(int id) const {
  for (const auto& n : nodes)
    if (n.id == id) return &n;
  return nullptr;
}

int TopologicalGraph::connectedComponents() const {
  std::vector<int> parent(nodes.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); };
  auto index = [&](int id) {
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].id == id) return static_cast<int>(i);
    return -1;
  };
  int comps = static_cast<int>(nodes.size());
  for (const auto& e : edges) {
    const int a = find(index(e.a)), b = find(index(e.b));
    if (a != b) parent[a] = b, --comps;
  }
  return comps;
}

TopologicalGraph buildGraph(const RegionMap& rm, double resolution, cv::Point2d origin, cv::Point offset,
                            cv::Size map_size) {
  TopologicalGraph g;
  g.resolution = resolution;
  g.rows = map_size.empty() ? rm.ids.rows : map_size.height;
  g.cols = map_size.empty() ? rm.ids.cols : map_size.width;
  // The centroids in the map's frame: from integer sums of map coordinates (as extractRegions and the graph rules
  // compute them on the whole map), not the part's centroid plus the offset (which can round differently).
  std::vector<cv::Point2d> centroid(rm.regions.size());
  for (const Region& r : rm.regions) centroid[static_cast<std::size_t>(r.id - 1)] = r.centroid;
  if (offset != cv::Point()) {
    std::vector<long long> cells(rm.regions.size() + 1, 0), sx(cells), sy(cells);
    for (int y = 0; y < rm.ids.rows; ++y) {
      const int* row = rm.ids.ptr<int>(y);
      for (int x = 0; x < rm.ids.cols; ++x)
        if (row[x] > 0 && row[x] <= static_cast<int>(rm.regions.size())) {
          const auto u = static_cast<std::size_t>(row[x]);
          ++cells[u], sx[u] += x + offset.x, sy[u] += y + offset.y;
        }
    }
    for (const Region& r : rm.regions) {
      const auto u = static_cast<std::size_t>(r.id);
      if (cells[u] > 0)
        centroid[u - 1] = cv::Point2d(static_cast<double>(sx[u]) / cells[u], static_cast<double>(sy[u]) / cells[u]);
      else
        centroid[u - 1] = r.centroid + cv::Point2d(offset);
    }
  }
  for (const Region& r : rm.regions) {
    GraphNode n;
    n.id = r.id, n.label = r.label, n.cells = r.cells, n.area_m2 = r.area_m2;
    n.centroid_px = centroid[static_cast<std::size_t>(r.id - 1)];
    n.centroid_m = origin + cv::Point2d((n.centroid_px.x + 0.5) * resolution, (g.rows - n.centroid_px.y - 0.5) * resolution);
    n.bbox_px = r.bbox + offset;
    g.nodes.push_back(n);
  }
  // Anchors: a cell well inside every region (the centroid when the region is compact around it).
  const std::vector<cv::Point> anchors = regionAnchors(rm, offset, &centroid);
  const cv::Rect part(offset, rm.ids.size());
  for (auto& n : g.nodes) {
    const cv::Point c(static_cast<int>(std::lround(n.centroid_px.x)), static_cast<int>(std::lround(n.centroid_px.y)));
    n.centroid_inside = c.inside(part) && rm.ids.at<int>(c - offset) == n.id;
    n.anchor_px = anchors[static_cast<std::size_t>(n.id - 1)] + offset;
    n.anchor_m = origin + cv::Point2d((n.anchor_px.x + 0.5) * resolution, (g.rows - n.anchor_px.y - 0.5) * resolution);
  }
  // Edges with their contact points (same half-neighbourhood scan as regionAdjacency).
  struct Acc {
    int n = 0;
    double sx = 0, sy = 0;
  };
  std::map<std::pair<int, int>, Acc> acc;
  static const int d[4][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};
  for (int y = 0; y < rm.ids.rows; ++y)
    for (int x = 0; x < rm.ids.cols; ++x) {
      const int a = rm.ids.at<int>(y, x);
      if (a <= 0) continue;
      for (const auto& o : d) {
        const int yy = y + o[0], xx = x + o[1];
        if (yy < 0 || xx < 0 || yy >= rm.ids.rows || xx >= rm.ids.cols) continue;
        const int b = rm.ids.at<int>(yy, xx);
        if (b <= 0 || b == a) continue;
        Acc& e = acc[{std::min(a, b), std::max(a, b)}];
        e.n++, e.sx += 0.5 * ((x + offset.x) + (xx + offset.x)), e.sy += 0.5 * ((y + offset.y) + (yy + offset.y));
      }
    }
  const int door = static_cast<int>(places::PlaceLabel::Doorway);
  for (const auto& [k, v] : acc) {
    GraphEdge e;
    e.a = k.first, e.b = k.second, e.border_cells = v.n;
    e.contact_px = cv::Point2d(v.sx / v.n, v.sy / v.n);
    e.via_doorway = rm.region(e.a).label == door || rm.region(e.b).label == door;
    g.edges.push_back(e);
  }
  const EdgeRouter router(rm, anchors, resolution);
  for (auto& e : g.edges) {
    e.path_px = router.route(e.a, e.b);
    for (cv::Point& q : e.path_px) q += offset;
  }
  return g;
}

}  // namespace gridtopo::topology
