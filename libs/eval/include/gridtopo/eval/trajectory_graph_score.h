#pragma once
// The graph against a labelled plan along the robot's trajectory (issue 35, item 4; definitions in
// doc/topology-trajectory.md). Two questions a person asks of a topological map of the building the robot drove:
//  - doors crossed: of the plan's doors the trajectory went through (a change of the plan region along the path,
//    between two plan regions the plan joins through a labelled doorway: PlanGraph::links), how many the graph has
//    as a doorway node between the right two spaces: a doorway node within `door_reach` of the crossing point (the
//    middle between the path's last cell in one region and its first in the other) with a neighbour node on
//    either side (a node is on side A when, within `side_reach` of the crossing, it holds more cells of plan
//    region A than of plan region B). A door is found when one of its crossings is;
//  - spurious splits: the changes from one non-doorway graph node to another along the trajectory where the plan
//    has none (the same plan region on both sides): one open space cut into several nodes. Those where the label
//    changes too (room <-> corridor) are counted apart: alternating labels in one space.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "gridtopo/eval/graph_evaluation.h"
#include "gridtopo/topology/graph.h"
#include "gridtopo/topology/regions.h"

namespace gridtopo::eval {

struct TrajectoryScoreOptions {
  double door_reach = 1.0;   ///< m: a doorway node counts for a crossing when one of its cells lies this close
  double side_reach = 1.5;   ///< m: the neighbourhood of the door in which the sides' nodes are counted
};

/// One plan door the trajectory went through.
struct DoorCrossed {
  int plan_a = 0, plan_b = 0;    ///< the plan regions on its two sides (in the first crossing's direction)
  cv::Point at;                  ///< a crossing point (map cells): the first found one, else the first
  int crossings = 0;             ///< how often the path went through it
  bool doorway_node = false;     ///< a doorway node lies at the door
  bool found = false;            ///< ... with a neighbour node on either side
};

struct TrajectoryGraphScore {
  bool has_trajectory = false;
  std::vector<DoorCrossed> doors;   ///< the plan doors crossed (one per plan link), in the order first crossed
  int doors_crossed = 0, doors_with_doorway_node = 0, doors_found = 0;
  int region_changes = 0;               ///< changes of the scored plan region along the trajectory
  int region_changes_through_door = 0;  ///< ... over plan doorway cells (the others: through open passages)
  int node_changes = 0;             ///< changes between non-doorway graph nodes along the trajectory
  int node_changes_scored = 0;      ///< ... with a scored plan region on both sides
  int spurious_splits = 0;          ///< ... of those, with the same plan region on both sides and no door between
  int spurious_label_changes = 0;   ///< ... of those, between a room node and a corridor node
  int spurious_boundaries = 0;      ///< distinct node pairs of the spurious splits
  double doorsFoundFraction() const { return doors_crossed ? double(doors_found) / doors_crossed : 0.0; }
  std::string toJson() const;
};

/// Scores the graph `g` with regions `regions` against `plan` (planGraphFromReference, in the map's frame) along
/// `path` (map cells, topology::pathInCells of the trajectory; resampled every cell, topology::samplePath).
TrajectoryGraphScore scoreGraphAlongPath(const topology::TopologicalGraph& g, const topology::RegionMap& regions,
                                         const PlanGraph& plan, const std::vector<cv::Point2d>& path,
                                         double resolution,
                                         const TrajectoryScoreOptions& options = {});

}  // namespace gridtopo::eval
