#pragma once
// The topological graph as an MRPT type: a 2D pose graph (mrpt::graphs::CNetworkOfPoses2D) with one node per
// region at its anchor (GraphNode::anchor_m: a cell inside the region; metres, heading 0) and one edge per touching
// pair (the relative pose between the two anchors). MRPT tools can load, draw and serialize it; saveToTextFile() writes the VERTEX_SE2 / EDGE_SE2
// text format.
#include <mrpt/graphs/CNetworkOfPoses.h>

#include "gridtopo/topology/graph.h"

namespace gridtopo::topology {

mrpt::graphs::CNetworkOfPoses2D toMrptPoseGraph(const TopologicalGraph& g);

}  // namespace gridtopo::topology
