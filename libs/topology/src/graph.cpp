#include "gridtopo/topology/graph.h"

#include <functional>
#include <numeric>

#include "gridtopo/places/place_label.h"

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

TopologicalGraph buildGraph(const RegionMap& rm, double resolution) {
  TopologicalGraph g;
  g.resolution = resolution;
  g.rows = rm.ids.rows, g.cols = rm.ids.cols;
  for (const Region& r : rm.regions) {
    GraphNode n;
    n.id = r.id, n.label = r.label, n.cells = r.cells, n.area_m2 = r.area_m2;
    n.centroid_px = r.centroid;
    n.centroid_m = cv::Point2d((r.centroid.x + 0.5) * resolution, (g.rows - r.centroid.y - 0.5) * resolution);
    n.bbox_px = r.bbox;
    g.nodes.push_back(n);
  }
  const int door = static_cast<int>(places::PlaceLabel::Doorway);
  for (const auto& [k, len] : regionAdjacency(rm.ids)) {
    GraphEdge e;
    e.a = k.first, e.b = k.second, e.border_cells = len;
    e.via_doorway = rm.region(e.a).label == door || rm.region(e.b).label == door;
    g.edges.push_back(e);
  }
  return g;
}

}  // namespace gridtopo::topology
