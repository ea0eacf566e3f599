#include "gridtopo/topology/graph_rules.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "gridtopo/places/place_label.h"
#include "region_merge.h"

namespace gridtopo::topology {

namespace {
constexpr int kDoorway = static_cast<int>(places::PlaceLabel::Doorway);

// Region map whose ids are `remap[old id]` (0 = dropped); labels from `label[new id]`, geometry recomputed.
RegionMap relabel(const RegionMap& rm, const std::vector<int>& remap, const std::vector<int>& label, double resolution) {
  const int n = static_cast<int>(label.size()) - 1;
  RegionMap out;
  out.ids = cv::Mat(rm.ids.size(), CV_32S, cv::Scalar(0));
  std::vector<long long> cells(static_cast<std::size_t>(n) + 1, 0), sx(cells), sy(cells);
  std::vector<cv::Rect> box(static_cast<std::size_t>(n) + 1);
  for (int y = 0; y < rm.ids.rows; ++y)
    for (int x = 0; x < rm.ids.cols; ++x) {
      const int old = rm.ids.at<int>(y, x);
      if (old <= 0) continue;
      const int id = remap[static_cast<std::size_t>(old)];
      if (id <= 0) continue;
      out.ids.at<int>(y, x) = id;
      const auto u = static_cast<std::size_t>(id);
      box[u] = cells[u] == 0 ? cv::Rect(x, y, 1, 1) : (box[u] | cv::Rect(x, y, 1, 1));
      ++cells[u], sx[u] += x, sy[u] += y;
    }
  for (int id = 1; id <= n; ++id) {
    const auto u = static_cast<std::size_t>(id);
    Region r;
    r.id = id;
    r.label = label[u];
    r.cells = static_cast<int>(cells[u]);
    r.area_m2 = r.cells * resolution * resolution;
    r.centroid = cells[u] ? cv::Point2d(double(sx[u]) / cells[u], double(sy[u]) / cells[u]) : cv::Point2d();
    r.bbox = box[u];
    out.regions.push_back(r);
  }
  return out;
}
}  // namespace

RegionMap applyGraphRules(const RegionMap& rm, double resolution, const GraphRuleOptions& o) {
  const int n = static_cast<int>(rm.regions.size());
  std::vector<long long> sizes(static_cast<std::size_t>(n) + 1, 0);
  for (const Region& r : rm.regions) sizes[static_cast<std::size_t>(r.id)] = r.cells;
  RegionMerger merge(rm.ids, std::move(sizes));
  std::vector<int>& parent = merge.parent;
  const std::vector<long long>& cells = merge.size;
  const std::vector<std::map<int, long long>>& border = merge.border;
  std::vector<bool> removed(static_cast<std::size_t>(n) + 1, false);
  // G1, smallest region first; borders and sizes follow the merges.
  const long long min_cells = static_cast<long long>(std::ceil(o.min_node_area / (resolution * resolution)));
  for (;;) {
    int small = 0;
    for (int i = 1; i <= n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      if (parent[u] != i || removed[u] || rm.region(i).label == kDoorway || cells[u] >= min_cells) continue;
      if (!small || cells[u] < cells[static_cast<std::size_t>(small)]) small = i;
    }
    if (!small) break;
    const auto us = static_cast<std::size_t>(small);
    if (border[us].empty()) {
      removed[us] = true;
      continue;
    }
    merge.absorbIntoLongestBorder(small);
  }
  // G2: doorway regions keyed by the set of non-doorway regions they touch (after G1).
  if (o.merge_doorways) {
    std::map<std::set<int>, int> first_door;
    for (int i = 1; i <= n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      if (parent[u] != i || removed[u] || rm.region(i).label != kDoorway) continue;
      std::set<int> sides;
      for (const auto& [other, len] : border[u])
        if (rm.region(other).label != kDoorway) sides.insert(other);
      if (sides.size() != 2) continue;
      const auto [it, fresh] = first_door.emplace(sides, i);
      if (!fresh) parent[u] = it->second;
    }
  }
  // Renumber the surviving roots in input order.
  std::vector<int> remap(static_cast<std::size_t>(n) + 1, 0), label{0};
  for (int i = 1; i <= n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    if (parent[u] == i && !removed[u]) remap[u] = static_cast<int>(label.size()), label.push_back(rm.region(i).label);
  }
  for (int i = 1; i <= n; ++i) remap[static_cast<std::size_t>(i)] = remap[static_cast<std::size_t>(merge.root(i))];
  return relabel(rm, remap, label, resolution);
}

RegionMap graphRegions(const cv::Mat& labels, double resolution, const CorridorSplitOptions& split,
                       const GraphRuleOptions& rules) {
  return applyGraphRules(splitCorridors(extractRegions(labels, resolution), resolution, split), resolution, rules);
}

}  // namespace gridtopo::topology
