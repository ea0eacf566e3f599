#pragma once
// gridtopo-topology-compare's measurement: a gridtopo-topology result (labels.png, segmentation.png, topology.json
// of an output directory) on a map, scored against a labelled reference plan of the same building drawn in another
// frame (reference_alignment.h): cell-label accuracy, room segmentation and the graph against the plan
// (graph_evaluation.h), on the map's free cells.
#include <opencv2/core.hpp>

#include <string>

#include "gridtopo/eval/graph_evaluation.h"
#include "gridtopo/eval/reference_alignment.h"
#include "gridtopo/eval/trajectory_graph_score.h"
#include "gridtopo/places/occupancy.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::eval {

/// The reference plan: its map (free = grey > 250), place labels (77 / 115 / 179) and room-segmentation ground
/// truth (rooms white), all in one frame.
struct ReferencePlan {
  std::string map, labels, segmentation;
  /// The plan is pixel-aligned with the map (the same size and lattice: a simulated map of the plan,
  /// gridtopo-simulate-maps): the alignment is the identity, not searched (ECC would shift it by the cells the map
  /// lacks); its correlation is the ECC of the two free masks as they lie. InputError when the sizes differ.
  bool same_frame = false;
};

struct TopologyComparison {
  std::string map;                ///< the map's path, as given
  places::OccupancyImage occ;     ///< the map's cells as thresholded (no free-space opening)
  cv::Mat map_free;               ///< CV_8U mask of occ's free cells
  cv::Mat labels, segmentation;   ///< the topology's labels (0..2 / kNoLabel) and segments (CV_32S)
  cv::Mat reference_codes, reference_rooms;  ///< the plan's label codes and rooms, in the plan's frame
  ReferenceScore score;           ///< alignment, labels and segmentation against the plan
  GraphComparison graph;          ///< the graph of the labels against the plan, and the plan labels' ceiling
  /// The room segmentation the same steps make of the plan's own labels on the map, against the plan: the ceiling
  /// of the segmentation score on this map (what the map itself allows: rooms seen in part, walls not mapped).
  SegmentationScore segmentation_of_plan_labels;
  /// Cell accuracy after the oracle region vote (oracle_diagnostics.h: in every room / corridor region of the plan's
  /// labels carried to the map, the room / corridor cells take the majority of our labels there; doorway cells and
  /// predicted doorways keep theirs): what any vote over the true places could reach from our labels.
  double region_vote_oracle_accuracy = 0;
  /// The graph along the robot's trajectory (doors crossed found, spurious splits); has_trajectory false without one.
  TrajectoryGraphScore along_path;
};

/// Reads the map (io::readMap: its kind picks the free threshold of `options`) and the topology directory
/// `topology_dir`, aligns the plan and scores. When topology_dir holds topology.json, its node and edge counts must
/// equal the graph the labels give with `options` (InputError otherwise: the INI gridtopo-topology ran with is
/// needed). InputError naming the file for missing or unreadable images and mismatched sizes. `trajectory`
/// (gridtopo-slam's trajectory.txt in the map's frame; empty = none): the graph is also scored along it
/// (scoreGraphAlongPath).
TopologyComparison compareWithReference(const std::string& map, const std::string& topology_dir,
                                        const ReferencePlan& plan, const topology::TopologyOptions& options,
                                        const std::string& trajectory = "");

/// The JSON of gridtopo-topology-compare (format "gridtopo-topology-compare").
std::string comparisonJson(const TopologyComparison& c);

/// One line: alignment correlation, cell accuracy and recalls, segmentation, rooms attached and loops closed.
std::string comparisonSummary(const TopologyComparison& c);

/// Our segments in colours with the plan's room borders (warped to the map) in red.
cv::Mat comparisonOverlay(const TopologyComparison& c);

/// The label errors (labelErrorOverlay) against the plan's labels warped to the map.
cv::Mat comparisonLabelErrors(const TopologyComparison& c);

}  // namespace gridtopo::eval
