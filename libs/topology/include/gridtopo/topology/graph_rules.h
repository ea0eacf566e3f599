#pragma once
// Rules that make the topological graph readable (issue 15, item 4); they change only the graph's regions, never
// the place labels or the room segmentation:
//  G1 tiny regions: a room or corridor region smaller than `min_node_area` joins the neighbouring region it shares
//     the longest border with (any label; doorway regions are never absorbed, they are the graph's edge-nodes); a
//     tiny region with no neighbour is removed from the graph (its cells get region id 0).
//  G2 doorway edge-nodes: doorway regions that join the same two room / corridor regions (a double door, or a door
//     the classifier cut in two) become one doorway node.
//  G3 rooms follow the room segmentation: a room region that the segmentation cuts into several segments (rule S1
//     splits rooms joined through a door the classifier missed; S0 keeps a room and the corridor it is open to
//     together) becomes one region per segment, so every segmented room is its own node, joined to its
//     neighbour across the cut. Applied first; G1 then absorbs the pieces too small to be a node.
// The graph's regions are extractRegions (8-connected equal labels), G3 with the room segmentation, splitCorridors
// (corridor pieces), then G1 and G2: graphRegions() is that chain, the one both gridtopo-topology and
// gridtopo-topology-compare call.
#include <opencv2/core.hpp>

#include "gridtopo/topology/corridor_split.h"
#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

struct GraphRuleOptions {
  double min_node_area = 1.0;  ///< m^2 (G1); 0 = off
  bool merge_doorways = true;  ///< G2
  bool rooms_by_segment = true;  ///< G3
};

/// G3: every room region of `regions` that meets several segments of `segmentation` (CV_32S, same size, the room
/// segmentation of these regions) becomes one region per 8-connected part of its cells within each segment. Other
/// regions are kept. Regions are renumbered 1..N in input order (a split room's parts in the order of their first
/// cell, row by row).
RegionMap splitRoomsBySegments(const RegionMap& regions, const cv::Mat& segmentation, double resolution);

/// G1 then G2 on `regions` (every region's cells, area, centroid and bounding box recomputed; ids renumbered
/// 1..N in the order of the input's surviving regions).
RegionMap applyGraphRules(const RegionMap& regions, double resolution, const GraphRuleOptions& options = {});

/// The graph's regions from the 8-connected `regions` of the final labels and their room `segmentation` (CV_32S;
/// used when rules.rooms_by_segment): G3, splitCorridors(`split`), applyGraphRules(`rules`).
RegionMap graphRegions(const RegionMap& regions, const cv::Mat& segmentation, double resolution,
                       const CorridorSplitOptions& split, const GraphRuleOptions& rules);
/// The same, letting go of `regions` (and each step's input) as soon as it is used: less memory on large maps.
RegionMap graphRegions(RegionMap&& regions, const cv::Mat& segmentation, double resolution,
                       const CorridorSplitOptions& split, const GraphRuleOptions& rules);

}  // namespace gridtopo::topology
