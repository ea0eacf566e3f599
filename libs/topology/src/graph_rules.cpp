#include "gridtopo/topology/graph_rules.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "gridtopo/places/place_label.h"
#include "mask_ops.h"
#include "region_merge.h"

namespace gridtopo::topology {

namespace {
constexpr int kDoorway = static_cast<int>(places::PlaceLabel::Doorway);

// Region map whose ids are `remap[old id]` (0 = dropped); labels from `label[new id]`, geometry recomputed.
// `in_place`: the new ids are written over rm.ids (which the result then shares) instead of a new image.
RegionMap relabel(const RegionMap& rm, const std::vector<int>& remap, const std::vector<int>& label, double resolution,
                  bool in_place = false) {
  const int n = static_cast<int>(label.size()) - 1;
  RegionMap out;
  out.ids = in_place ? rm.ids : cv::Mat(rm.ids.size(), CV_32S, cv::Scalar(0));
  std::vector<long long> cells(static_cast<std::size_t>(n) + 1, 0), sx(cells), sy(cells);
  std::vector<cv::Rect> box(static_cast<std::size_t>(n) + 1);
  for (int y = 0; y < rm.ids.rows; ++y)
    for (int x = 0; x < rm.ids.cols; ++x) {
      const int old = rm.ids.at<int>(y, x);
      if (old <= 0) continue;
      const int id = remap[static_cast<std::size_t>(old)];
      out.ids.at<int>(y, x) = std::max(id, 0);
      if (id <= 0) continue;
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

namespace {
// G3 over `rm`'s own id image when `in_place` (the pieces are written over it: a full-map id image less on a large
// map), else over a copy. While the pieces are found, a cell already in a piece holds minus the piece's number.
RegionMap splitRoomsBySegmentsIn(const RegionMap& rm, const cv::Mat& segmentation, double resolution, bool in_place) {
  CV_Assert((segmentation.type() == CV_32S || segmentation.type() == CV_16U) && segmentation.size() == rm.ids.size());
  constexpr int kRoom = static_cast<int>(places::PlaceLabel::Room);
  cv::Mat ids = in_place ? rm.ids : rm.ids.clone();
  // A cell's key: its region, and for room cells also its segment. Pieces are the 8-connected sets of equal keys,
  // found by flood fill row by row (so each region's pieces come in the order of their first cell).
  const auto key = [&](int y, int x) {
    const int id = ids.at<int>(y, x);
    const int seg = id > 0 && rm.region(id).label == kRoom ? idAt(segmentation, y, x) : 0;
    return std::make_pair(id, seg);
  };
  std::vector<int> region_of{0};  // piece -> input region
  std::vector<cv::Point> stack;
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x) {
      if (ids.at<int>(y, x) <= 0) continue;  // no region, or already in a piece
      const int p = static_cast<int>(region_of.size());
      const auto k = key(y, x);
      region_of.push_back(k.first);
      ids.at<int>(y, x) = -p;
      stack.assign(1, cv::Point(x, y));
      while (!stack.empty()) {
        const cv::Point c = stack.back();
        stack.pop_back();
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int ny = c.y + dy, nx = c.x + dx;
            if (ny < 0 || nx < 0 || ny >= ids.rows || nx >= ids.cols || ids.at<int>(ny, nx) <= 0) continue;
            if (key(ny, nx) != k) continue;
            ids.at<int>(ny, nx) = -p;
            stack.emplace_back(nx, ny);
          }
      }
    }
  // New ids: by input region, then by piece (stable: first cell order).
  const int n = static_cast<int>(region_of.size()) - 1;
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i + 1;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return region_of[static_cast<std::size_t>(a)] < region_of[static_cast<std::size_t>(b)];
  });
  std::vector<int> remap(static_cast<std::size_t>(n) + 1, 0), label{0};
  for (int p : order) {
    remap[static_cast<std::size_t>(p)] = static_cast<int>(label.size());
    label.push_back(rm.region(region_of[static_cast<std::size_t>(p)]).label);
  }
  for (int y = 0; y < ids.rows; ++y) {  // piece numbers (0 stays 0), in place
    int* row = ids.ptr<int>(y);
    for (int x = 0; x < ids.cols; ++x) row[x] = -row[x];
  }
  RegionMap pieces;
  pieces.ids = ids;
  return relabel(pieces, remap, label, resolution, true);
}
}  // namespace

RegionMap splitRoomsBySegments(const RegionMap& rm, const cv::Mat& segmentation, double resolution) {
  return splitRoomsBySegmentsIn(rm, segmentation, resolution, false);
}

namespace {
RegionMap applyGraphRulesTo(const RegionMap& rm, double resolution, const GraphRuleOptions& o, bool in_place);
}  // namespace

RegionMap applyGraphRules(const RegionMap& rm, double resolution, const GraphRuleOptions& o) {
  return applyGraphRulesTo(rm, resolution, o, false);
}

namespace {
RegionMap applyGraphRulesTo(const RegionMap& rm, double resolution, const GraphRuleOptions& o, bool in_place) {
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
  return relabel(rm, remap, label, resolution, in_place);
}
}  // namespace

RegionMap graphRegions(RegionMap&& regions, const cv::Mat& segmentation, double resolution,
                       const CorridorSplitOptions& split, const GraphRuleOptions& rules) {
  // Each step's input is let go once the next image exists (on a large map each is a full-map id image).
  if (rules.rooms_by_segment) {
    // Over the caller's id image unless another RegionMap shares it.
    const bool ours = !(regions.ids.u && regions.ids.u->refcount > 1);
    regions = splitRoomsBySegmentsIn(regions, segmentation, resolution, ours);
  }
  RegionMap pieces = splitCorridors(std::move(regions), resolution, split);  // over the input's id image
  return applyGraphRulesTo(pieces, resolution, rules, true);  // `pieces` is ours: its id image becomes the result's
}

RegionMap graphRegions(const RegionMap& regions, const cv::Mat& segmentation, double resolution,
                       const CorridorSplitOptions& split, const GraphRuleOptions& rules) {
  return graphRegions(RegionMap(regions), segmentation, resolution, split, rules);  // the caller's stays as it is
}

}  // namespace gridtopo::topology
