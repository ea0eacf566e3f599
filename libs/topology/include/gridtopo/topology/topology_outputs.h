#pragma once
// The output set of a topology run, written by one function for gridtopo-topology and the GUI's save:
// topology.graphml, topology.json, topology.dot, topology_posegraph.graph (MRPT CNetworkOfPoses2D text), overlay.png,
// labels.png, labels_before_correction.png, segmentation.png (16-bit room ids), segmentation_colour.png, options.ini;
// all or nothing (gridtopo::OutputSet).
#include <opencv2/core.hpp>
#include <string>

#include "gridtopo/core/output_set.h"
#include "gridtopo/places/occupancy.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::topology {

/// Writes the set into `dir` (created if needed), or nothing. `labels_before_correction`: the labelling's labels;
/// when empty, `topo.labels_classified` (a topologyOfMap run with outputs_only); when both are empty, and for an
/// empty `topo.segmentation`, their pictures are left out. `options_ini` is the text of options.ini.
void writeTopologyOutputs(const std::string& dir, const places::OccupancyImage& occ, const TopologyResult& topo,
                          const cv::Mat& labels_before_correction, int overlay_scale, const std::string& options_ini);
/// The same files as temporary files of `set`, which the caller commits with its other files (gridtopo-map).
void addTopologyOutputs(OutputSet& set, const std::string& dir, const places::OccupancyImage& occ,
                        const TopologyResult& topo, const cv::Mat& labels_before_correction, int overlay_scale,
                        const std::string& options_ini);

}  // namespace gridtopo::topology
