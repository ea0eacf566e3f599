#pragma once
// How a topology result is drawn in the map view: the map with its place labels blended in, and the graph over it.
// The topology view draws the session's topology with these, the SLAM view the live topology of the run
// (LiveTopology) over the growing map: one drawing path for both.
#include <opencv2/core.hpp>
#include <string>

#include "gridtopo/session/render.h"
#include "gridtopo/session/topology_state.h"

namespace gridtopo::session {

/// The map of `t` (BGR, aligned with t.map) with the labels of `stage` blended in (labelOverlay; shaded by the
/// label's probability where the labelling is kept), or the grey map alone when `with_labels` is false or the stage
/// has no labels.
cv::Mat topologyImage(const TopologyData& t, LabelStage stage, bool with_labels);

/// The graph of `t` as overlay.png draws it (edges along their routed free paths, or node -> contact point -> node;
/// nodes as discs in their label's colour at their anchors) when `graph`, and the node ids when `region_ids`.
void drawTopologyGraph(cv::Mat& screen, const ViewTransform& v, const TopologyData& t, bool graph, bool region_ids);

/// A line of text in a white box at the top-left corner of the view (e.g. which scan the live topology is of).
void drawCaption(cv::Mat& screen, const std::string& text);

}  // namespace gridtopo::session
