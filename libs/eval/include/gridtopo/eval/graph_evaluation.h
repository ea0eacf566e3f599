#pragma once
// Graph quality against a labelled plan of the same building (issue 15, item 4; definitions in doc/topology.md,
// "Graph quality against the plan"). Two numbers:
//  - rooms attached: the fraction of plan rooms that are exactly one room node of the graph, attached through a
//    doorway node to the node of the plan region the room's door opens onto (the corridor, for most rooms);
//  - loops closed: whether every corridor loop of the plan (a hole of the plan's corridor cells, such as the block
//    the Intel corridor runs around) is encircled by a cycle of corridor nodes (doorway nodes between two corridor
//    nodes count as the cycle's edges; room nodes do not).
// The plan is the reference of gridtopo-topology-compare: its room-segmentation ground truth (plan regions), its
// place labels (which plan regions are rooms and corridors, where the doorways are) and the alignment to the map.
#include <opencv2/core.hpp>

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "gridtopo/topology/graph.h"
#include "gridtopo/eval/reference_alignment.h"
#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {
struct TopologyOptions;
}

namespace gridtopo::eval {

/// The plan, in the map's frame.
struct PlanGraph {
  cv::Mat regions;                           ///< CV_32S plan region ids on the map's free cells, 0 = none
  std::map<int, int> kind;                   ///< plan region -> 0 room, 1 corridor (majority of its plan labels)
  /// Plan regions (a < b) joined by an opening of the plan -> whether the opening is a labelled doorway (true) or
  /// an open passage (false). An opening is a connected set of plan pixels that are free in the plan's map but in
  /// no ground-truth region (the ground truth closes every door and passage with a line); it joins the plan
  /// regions within doorway_reach of it, and is a doorway when a doorway-labelled pixel lies within that reach.
  std::map<std::pair<int, int>, bool> links;
  std::vector<cv::Point> loop_points;        ///< one cell (map pixels) inside every plan corridor loop
};

struct PlanGraphOptions {
  int min_region_cells = 100;  ///< plan regions with fewer free map cells are not scored (as the segmentation score)
  int doorway_reach = 3;       ///< plan pixels: an opening joins the plan regions within this distance of it
  double min_loop_area = 10;   ///< m^2: smaller holes of the plan's corridor cells (pillars, furniture) are no loop
};

/// Builds the plan graph: `reference_free` (the plan's free pixels), `reference_rooms` (groundTruthRooms of the
/// plan's ground truth) and `reference_codes` (room 77 / corridor 115 / doorway 179) in the plan's frame, aligned
/// to the map by `alignment`; `map_free` (CV_8U, non-zero = free) the map's free cells; `resolution` of the map (m
/// per cell).
PlanGraph planGraphFromReference(const cv::Mat& map_free, const cv::Mat& reference_free, const cv::Mat& reference_codes,
                                 const cv::Mat& reference_rooms, const ReferenceAlignment& alignment,
                                 double resolution, const PlanGraphOptions& options = {});

/// The plan's own place labels on the map's free cells (CV_8U 0..2, places::kNoLabel elsewhere): run through the
/// same steps as a labelling, they give the graph's ceiling on this map (what the graph steps make of perfect labels).
cv::Mat planLabelsOnMap(const cv::Mat& map_free, const cv::Mat& reference_codes, const ReferenceAlignment& alignment);

struct PlanRoomMatch {
  int plan_region = 0;
  int nodes_inside = 0;   ///< room / corridor nodes that lie in the plan room
  int node = 0;           ///< the one room node when one_room_node, else 0
  bool one_room_node = false;
  bool has_plan_opening = false;  ///< the plan has an opening from this room to another scored plan region
  /// one_room_node, and for some opening of the plan room to a plan region Q: an edge through a doorway node (for a
  /// doorway; for an open passage also a direct edge) to a node that holds more of its cells in Q than in any other
  /// plan region
  bool attached = false;
};

struct GraphScoreOptions {
  double purity = 0.8;    ///< a node lies in a plan region holding at least this share of its cells in plan regions
  double coverage = 0.5;  ///< the one room node must cover at least this share of the plan room's cells
};

struct GraphScore {
  std::vector<PlanRoomMatch> rooms;  ///< one per scored plan room, by plan region id
  int plan_rooms = 0, one_room_node = 0, attached = 0;
  int plan_loops = 0, loops_closed = 0;
  int corridor_cycles = 0;  ///< independent cycles of the corridor subgraph (its cycle rank)
  double attachedFraction() const { return plan_rooms ? double(attached) / plan_rooms : 0.0; }
  /// Every plan loop is a cycle of corridor nodes (false when the plan has none).
  bool loopsClosed() const { return plan_loops > 0 && loops_closed == plan_loops; }
  std::string toJson() const;
};

/// Scores the graph `g` whose regions are `regions` (the region map it was built from) against `plan`.
GraphScore scoreGraph(const topology::TopologicalGraph& g, const topology::RegionMap& regions, const PlanGraph& plan,
                      const GraphScoreOptions& options = {});


struct GraphComparison {
  topology::TopologicalGraph graph;   ///< the graph of the labels, rebuilt as gridtopo-topology builds it
  topology::RegionMap regions;        ///< the graph's regions (graphRegionsOfLabels)
  PlanGraph plan;                     ///< the plan in the map's frame
  GraphScore score;         ///< that graph against the plan
  GraphScore plan_labels;   ///< the ceiling: the graph the same steps make of the plan's own labels on the map
  /// The ceiling's labels and room segmentation (what the same steps make of the plan's own labels on the map).
  cv::Mat plan_labels_labels, plan_labels_segmentation;
};

/// What gridtopo-topology-compare reports on the graph: the graph of `labels` (the final labels of a
/// gridtopo-topology run on a map with free cells `map_free`: graphRegions with `options`, then buildGraph), scored
/// against the plan (planGraphFromReference), and the ceiling: buildTopology of planLabelsOnMap with `options`
/// (blob vote off: it needs a labelling), scored the same way.
GraphComparison compareGraphWithPlan(const cv::Mat& map_free, const cv::Mat& labels, double resolution,
                                     const topology::TopologyOptions& options, const cv::Mat& reference_free,
                                     const cv::Mat& reference_codes, const cv::Mat& reference_rooms,
                                     const ReferenceAlignment& alignment);

}  // namespace gridtopo::eval
