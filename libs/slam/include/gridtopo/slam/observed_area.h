#pragma once
// What a stretch of laser scans saw, and what a match against it is worth there. A correlation score averages the
// grid's value over every query point, so points that fall where the place's scans never looked (behind its walls,
// beyond its stretch's reach) count as misses although nothing contradicts them, and points that fall where the
// place's beams passed freely count the same although they do contradict it. The occupancy grid's three states
// (Moravec & Elfes 1985; the filter's own map, grid_map.h) tell them apart: a global match is judged on the query
// points the place observed (their mean value) and on the share that lands in space the place saw free.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gridtopo/slam/correlative_matcher.h"
#include "gridtopo/slam/pose2.h"

namespace gridtopo::slam {

/// One scan of the stretch: the robot's pose in the area's frame, the laser's position in the robot frame and the
/// scan's hits (robot frame; beams without a return are not needed: leaving them out only shrinks the free space).
struct ObservedScan {
  Pose2 pose;
  Point2 sensor;
  const std::vector<Point2>* hits = nullptr;
};

/// Cells of `cell` m, each unseen, seen, or seen free. A beam marks the cells it crosses as seen and, up to
/// free_margin m before its hit, as passed; a passed cell is free unless a hit lies within hit_clearance of it (a
/// wall another beam grazed, a thin wall's far face). Every cell next to a seen one counts as seen (a query point on the
/// far face of a wall the place saw from the near side is in view).
class ObservedArea {
 public:
  ObservedArea() = default;
  ObservedArea(const std::vector<ObservedScan>& scans, double cell, double free_margin, double hit_clearance);

  bool seen(const Point2& p) const { return at(p, kSeen); }
  bool seenFree(const Point2& p) const { return at(p, kFree); }

 private:
  static constexpr std::uint8_t kSeen = 1, kFree = 2;
  bool at(const Point2& p, std::uint8_t flag) const;
  double cell_ = 0.1, x0_ = 0.0, y0_ = 0.0;
  int w_ = 0, h_ = 0;
  std::vector<std::uint8_t> flags_;
};

/// How a match of `query` at pose `x` in a place's grid reads against what the place observed.
struct MatchEvidence {
  double coverage = 0.0;      ///< share of the query's points the place saw
  double observed_score = 0.0;  ///< the grid's mean interpolated value over those points (0 when none)
  double contradiction = 0.0;   ///< share of the query's points in space the place saw free
};
MatchEvidence matchEvidence(const CorrelationGrid& grid, const ObservedArea& area, const std::vector<Point2>& query,
                            const Pose2& x);

}  // namespace gridtopo::slam
