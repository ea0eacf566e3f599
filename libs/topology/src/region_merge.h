#pragma once
// Merging small regions into their neighbours, shared by graph rule G1 and the corridor pieces (library-internal).
#include <opencv2/core.hpp>

#include <map>
#include <numeric>
#include <vector>

#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

/// Union-find over the regions 1..n of an id image (CV_32S), with each region's size in cells and the border
/// length it shares with each neighbour (regionAdjacency); sizes and borders follow the merges.
struct RegionMerger {
  std::vector<int> parent;
  std::vector<long long> size;                   ///< cells, indexed by id; 0 once merged away
  std::vector<std::map<int, long long>> border;  ///< neighbour id -> shared border length, indexed by id

  /// `sizes` indexed by id (0 unused): n = sizes.size() - 1 regions.
  RegionMerger(const cv::Mat& ids, std::vector<long long> sizes)
      : parent(sizes.size()), size(std::move(sizes)), border(size.size()) {
    std::iota(parent.begin(), parent.end(), 0);
    for (const auto& [ab, len] : regionAdjacency(ids)) {
      border[static_cast<std::size_t>(ab.first)][ab.second] += len;
      border[static_cast<std::size_t>(ab.second)][ab.first] += len;
    }
  }

  int root(int i) const {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)];
    return i;
  }

  /// Region `small` (a root with a neighbour) joins the neighbour it shares most border with (the lowest id among
  /// equals).
  void absorbIntoLongestBorder(int small) {
    const auto us = static_cast<std::size_t>(small);
    int best = 0;
    long long best_len = -1;
    for (const auto& [other, len] : border[us])
      if (len > best_len) best = other, best_len = len;
    const auto ub = static_cast<std::size_t>(best);
    parent[us] = best;
    size[ub] += size[us];
    size[us] = 0;
    for (const auto& [other, len] : border[us]) {
      border[static_cast<std::size_t>(other)].erase(small);
      if (other == best) continue;
      border[ub][other] += len;
      border[static_cast<std::size_t>(other)][best] += len;
    }
    border[us].clear();
  }
};

}  // namespace gridtopo::topology
