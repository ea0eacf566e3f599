#include "gridtopo/topology/open_spaces.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <utility>

#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/door_passages.h"
#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

namespace {
constexpr int kRoomLabel = static_cast<int>(places::PlaceLabel::Room);
constexpr int kCorridorLabel = static_cast<int>(places::PlaceLabel::Corridor);

bool isPlace(int label) { return label == kRoomLabel || label == kCorridorLabel; }

// A maximal stretch of consecutive path samples in one region.
struct Run {
  int id = 0;
  std::size_t first = 0, last = 0;
};

int findRoot(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}
}  // namespace

cv::Mat mergeOpenSpaces(const cv::Mat& labels, const std::vector<cv::Point2d>& path, double resolution,
                        const OpenSpaceOptions& o, std::vector<OpenSpace>* spaces) {
  cv::Mat out = labels.clone();
  std::vector<OpenSpace> found;
  if (!o.enabled || path.empty()) {
    if (spaces) *spaces = found;
    return out;
  }
  const RegionMap rm = extractRegions(labels, resolution);
  const std::size_t n = rm.regions.size();
  // Border length (m) of each pair of regions: 8-neighbour cell pairs / 3 cells (as the segmentation's S0).
  std::map<std::pair<int, int>, double> contact;
  for (const auto& [ab, pairs] : regionAdjacency(rm.ids)) contact[ab] = pairs / 3.0 * resolution;
  const auto wide = [&](int a, int b) {
    const auto it = contact.find({std::min(a, b), std::max(a, b)});
    return it != contact.end() && it->second >= o.min_contact;
  };

  // The path's runs through regions; a sample off every region or a gap ends a run without a straight step.
  const PathOverRegions over = pathOverRegions(path, rm.ids, resolution);
  const std::vector<cv::Point2d>& samples = over.samples;
  std::vector<Run> runs;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const int id = over.region[i];
    if (id <= 0) continue;
    if (!runs.empty() && runs.back().id == id && runs.back().last + 1 == i)
      runs.back().last = i;
    else
      runs.push_back({id, i, i});
  }
  // A straight step from run k to run k + 1: consecutive samples, both room / corridor pieces of other labels
  // (a doorway between them is a run of its own), sharing a border of at least min_contact.
  const auto straight = [&](std::size_t k) {
    const Run &a = runs[k], &b = runs[k + 1];
    return b.first == a.last + 1 && isPlace(rm.region(a.id).label) && isPlace(rm.region(b.id).label) &&
           rm.region(a.id).label != rm.region(b.id).label && wide(a.id, b.id);
  };
  const auto step_at = [&](std::size_t k) { return (samples[runs[k].last] + samples[runs[k + 1].first]) * 0.5; };
  std::set<std::pair<int, int>> joins;  // (a, b), a < b
  std::vector<char> crossed(n + 1, 0);  // the path went through the piece between two straight steps
  for (std::size_t k = 0; k + 1 < runs.size(); ++k) {
    if (!straight(k)) continue;
    joins.insert({std::min(runs[k].id, runs[k + 1].id), std::max(runs[k].id, runs[k + 1].id)});
    if (k + 2 < runs.size() && straight(k + 1) &&
        cv::norm(step_at(k + 1) - step_at(k)) * resolution >= o.min_through)
      crossed[static_cast<std::size_t>(runs[k + 1].id)] = 1;
  }
  if (joins.empty()) {
    if (spaces) *spaces = found;
    return out;
  }

  // The border of each joined region (8-neighbour cell pairs with a cell outside it: other regions, walls, unknown,
  // the image's edge), in the units of `contact`; only the joined regions' bounding boxes are scanned.
  std::vector<double> border(n + 1, 0.0);
  {
    std::set<int> joined;
    for (const auto& [a, b] : joins) joined.insert(a), joined.insert(b);
    const int rows = rm.ids.rows, cols = rm.ids.cols;
    for (int id : joined) {
      const cv::Rect box = rm.region(id).bbox;
      long long pairs = 0;
      for (int y = box.y; y < box.y + box.height; ++y) {
        const int* row = rm.ids.ptr<int>(y);
        for (int x = box.x; x < box.x + box.width; ++x) {
          if (row[x] != id) continue;
          for (int dy = -1; dy <= 1; ++dy) {
            const int yy = y + dy;
            const int* other = yy >= 0 && yy < rows ? rm.ids.ptr<int>(yy) : nullptr;
            for (int dx = -1; dx <= 1; ++dx) {
              if (!dx && !dy) continue;
              const int xx = x + dx;
              if (!other || xx < 0 || xx >= cols || other[xx] != id) ++pairs;
            }
          }
        }
      }
      border[static_cast<std::size_t>(id)] = pairs / 3.0 * resolution;
    }
  }

  // Spaces of the joined pieces; a piece that would change its label without having been crossed leaves its space.
  std::vector<char> active(n + 1, 1);
  std::vector<int> parent(n + 1), winner(n + 1, -1);
  for (;;) {
    std::iota(parent.begin(), parent.end(), 0);
    for (const auto& [a, b] : joins)
      if (active[static_cast<std::size_t>(a)] && active[static_cast<std::size_t>(b)])
        parent[static_cast<std::size_t>(findRoot(parent, a))] = findRoot(parent, b);
    // Area per label in each space (cells).
    std::map<int, std::pair<long long, long long>> area;  // root -> (room cells, corridor cells)
    std::map<int, int> members;
    for (const auto& [a, b] : joins)
      for (int id : {a, b})
        if (active[static_cast<std::size_t>(id)]) members[id] = findRoot(parent, id);
    for (const auto& [id, root] : members) {
      auto& [room, corridor] = area[root];
      (rm.region(id).label == kRoomLabel ? room : corridor) += rm.region(id).cells;
    }
    // Each member's border with the other members of its space.
    std::map<int, double> shared;
    for (const auto& [a, b] : joins) {
      const auto ia = members.find(a), ib = members.find(b);
      if (ia == members.end() || ib == members.end() || ia->second != ib->second) continue;
      const double len = contact.at({a, b});
      shared[a] += len;
      shared[b] += len;
    }
    bool changed = false;
    for (const auto& [id, root] : members) {
      const auto& [room, corridor] = area.at(root);
      const int w = room >= corridor ? kRoomLabel : kCorridorLabel;
      winner[static_cast<std::size_t>(id)] = w;
      const double share = shared[id] / std::max(border[static_cast<std::size_t>(id)], 1e-9);
      if (rm.region(id).label != w && (!crossed[static_cast<std::size_t>(id)] || share < o.min_shared)) {
        active[static_cast<std::size_t>(id)] = 0;
        changed = true;
      }
    }
    if (!changed) {
      // Spaces of more than one piece: relabel their pieces.
      std::map<int, std::vector<int>> by_root;
      for (const auto& [id, root] : members) by_root[root].push_back(id);
      std::vector<int> relabel(n + 1, -1);
      for (const auto& [root, ids] : by_root) {
        if (ids.size() < 2) continue;
        OpenSpace s;
        s.label = winner[static_cast<std::size_t>(ids.front())];
        s.pieces = static_cast<int>(ids.size());
        int largest = ids.front();
        for (int id : ids) {
          const Region& r = rm.region(id);
          s.area_m2 += r.area_m2;
          if (r.cells > rm.region(largest).cells) largest = id;
          if (r.label != s.label) {
            ++s.relabelled;
            s.relabelled_m2 += r.area_m2;
            relabel[static_cast<std::size_t>(id)] = s.label;
          }
        }
        const Region& big = rm.region(largest);
        s.at = cv::Point(static_cast<int>(std::floor(big.centroid.x)), static_cast<int>(std::floor(big.centroid.y)));
        if (!big.bbox.contains(s.at) || rm.ids.at<int>(s.at) != largest) {
          // the centroid lies outside the piece: its first cell in row order
          bool done = false;
          for (int y = big.bbox.y; y < big.bbox.y + big.bbox.height && !done; ++y)
            for (int x = big.bbox.x; x < big.bbox.x + big.bbox.width && !done; ++x)
              if (rm.ids.at<int>(y, x) == largest) s.at = {x, y}, done = true;
        }
        if (s.relabelled > 0) found.push_back(s);
      }
      for (int y = 0; y < out.rows; ++y) {
        const int* ids = rm.ids.ptr<int>(y);
        unsigned char* row = out.ptr<unsigned char>(y);
        for (int x = 0; x < out.cols; ++x)
          if (ids[x] > 0 && relabel[static_cast<std::size_t>(ids[x])] >= 0)
            row[x] = static_cast<unsigned char>(relabel[static_cast<std::size_t>(ids[x])]);
      }
      break;
    }
  }
  if (spaces) *spaces = found;
  return out;
}

}  // namespace gridtopo::topology
