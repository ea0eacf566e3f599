#pragma once
// Rules that make the topological graph readable (issue 15, item 4); they change only the graph's regions, never
// the place labels or the room segmentation:
//  G1 tiny regions: a room or corridor region smaller than `min_node_area` joins the neighbouring region it shares
//     the longest border with (any label; doorway regions are never absorbed, they are the graph's edge-nodes); a
//     tiny region with no neighbour is removed from the graph (its cells get region id 0).
//  G2 doorway edge-nodes: doorway regions that join the same two room / corridor regions (a double door, or a door
//     the classifier cut in two) become one doorway node.
// The graph's regions are extractRegions (8-connected equal labels), then splitCorridors (corridor pieces), then
// G1 and G2: graphRegions() is that chain, the one both gridtopo-topology and gridtopo-topology-compare call.
#include <opencv2/core.hpp>

#include "gridtopo/topology/corridor_split.h"
#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

struct GraphRuleOptions {
  double min_node_area = 1.0;  ///< m^2 (G1); 0 = off
  bool merge_doorways = true;  ///< G2
};

/// G1 then G2 on `regions` (every region's cells, area, centroid and bounding box recomputed; ids renumbered
/// 1..N in the order of the input's surviving regions).
RegionMap applyGraphRules(const RegionMap& regions, double resolution, const GraphRuleOptions& options = {});

/// The graph's regions of a label image (CV_8U place labels): extractRegions, splitCorridors(`split`),
/// applyGraphRules(`rules`).
RegionMap graphRegions(const cv::Mat& labels, double resolution, const CorridorSplitOptions& split,
                       const GraphRuleOptions& rules);

}  // namespace gridtopo::topology
