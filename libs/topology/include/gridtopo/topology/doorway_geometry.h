#pragma once
// Doorways from geometry, evidence beside the classifier: a door in a map is a narrow passage between two wider
// spaces, a critical point of the free space's generalized Voronoi diagram: a point of the diagram where the
// clearance (the distance to the nearest obstacle) has a local minimum, its critical line joining the two
// obstacles nearest to it (Thrun, "Learning metric-topological maps for indoor mobile robot navigation", AI 1998).
// Found here on the places (map_preparation.h) and kept when
//   - the line's width lies in [min_width, max_width] (a door: 0.6-1.2 m), and
//   - on both sides of the line, within `reach` along the diagram's direction, the clearance grows to the door's
//     half width plus `wider_by` (a door opens onto two wider spaces; a niche in a corridor wall, a narrowing at a
//     corridor's dead end, the mouth of a narrow corridor are refused).
// Each kept line is drawn into the labels as a doorway `depth` thick (a door the classifier missed still becomes
// the doorway node between its room and the corridor); with refuse_unsupported, a classifier doorway region no
// critical line crosses takes the label of the places around it (a "doorway" along a straight corridor wall).
#include <opencv2/core.hpp>

#include <vector>

#include "gridtopo/core/option_schema.h"

namespace gridtopo::topology {

struct DoorwayGeometryOptions {
  bool enabled = true;      ///< [topology] doorways_from_geometry
  double min_width = 0.6;   ///< [topology] doorway_min_width (m)
  double max_width = 1.2;   ///< [topology] doorway_max_width (m)
  double wider_by = 0.3;    ///< [topology] doorway_wider_by (m): each side's clearance beyond the door's half width
  double reach = 2.0;       ///< [topology] doorway_reach (m): how far along the diagram each side is looked at
  double depth = 0.25;      ///< [topology] doorway_depth (m): the doorway's thickness across the line
  bool refuse_unsupported = false;  ///< [topology] doorway_refuse_unsupported
};

/// A critical line: its end points (cells, on the two nearest obstacles), the critical point (a cell), the width.
struct CriticalLine {
  cv::Point2d a, b;
  cv::Point centre;
  double width = 0;  ///< m
};

/// The critical lines of `places` (CV_8U, non-zero = a place; everything else is obstacle) that pass the tests
/// above, in row-major order of their critical points; at most one per critical point's neighbourhood (the door's
/// width).
std::vector<CriticalLine> findDoorways(const cv::Mat& places, double resolution, const DoorwayGeometryOptions& o);

/// `labels` (CV_8U, 0..2 or places::kNoLabel; places are the labelled cells) with the critical lines drawn in as
/// doorway cells, and (refuse_unsupported) the unsupported classifier doorways relabelled. `found` gets the lines.
cv::Mat addGeometricDoorways(const cv::Mat& labels, double resolution, const DoorwayGeometryOptions& o,
                             std::vector<CriticalLine>* found = nullptr);

}  // namespace gridtopo::topology
