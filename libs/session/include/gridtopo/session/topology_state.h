#pragma once
// The place labelling + topology of one map, kept with everything needed to explain a cell's label: the
// simulated scan and the feature vector of every lattice sample, the label distributions before and after
// relaxation, the labels before and after region correction, the regions and the graph. The pipeline is the
// one of places::labelPlaces() + topology::buildTopology() (the same calls, in the same order), split so the
// intermediate scans and features are kept.
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gridtopo/places/labelling.h"
#include "gridtopo/places/model.h"
#include "gridtopo/places/scan_simulation.h"
#include "gridtopo/session/map_layer.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::session {

/// Which labels the overlay shows.
enum class LabelStage { Classified, Relaxed, Corrected };

struct TopologyData {
  MapLayer map;                  ///< the map the labels are aligned with
  places::OccupancyImage occ;
  bool has_labelling = false;    ///< false when loaded from a previous output (graph + labels image only)
  std::shared_ptr<const places::PlacesModel> model;
  places::LabellingResult labelling;  ///< lattice, probabilities, labels before/after relaxation
  places::SimulatedScans scans;       ///< per lattice sample
  cv::Mat features;                   ///< CV_32F samples x features
  topology::TopologyResult topo;      ///< labels after correction, regions, graph, segmentation
  double seconds = 0.0;

  /// Labels of a stage (CV_8U, 0..2, places::kNoLabel elsewhere); empty when not available.
  const cv::Mat& labels(LabelStage s) const;
};

/// Runs labelling + topology on `map` (thresholded and opened for its kind, MapLayer::kind, as gridtopo-topology
/// does for a file of that kind). `progress(stage, done, total)`.
/// Throws gridtopo::InputError for a map without free cells.
TopologyData computeTopology(const MapLayer& map, std::shared_ptr<const places::PlacesModel> model,
                             const topology::TopologyOptions& options,
                             const std::function<void(const std::string&, std::size_t, std::size_t)>& progress = {});

/// A previous gridtopo-topology output: topology.json (or .graphml) and, if present beside it, labels.png
/// (77/115/179/0 code) to show the label overlay. `map` must be the map it was computed on (same size) when
/// labels are present. Its free space is the map's, thresholded and opened for the map's kind with `options` as
/// computeTopology does (a SLAM grid's free cells are not those of a plain image). Throws gridtopo::InputError naming
/// file and line.
TopologyData loadTopologyOutput(const std::string& path, const MapLayer& map,
                                const topology::TopologyOptions& options = {});

/// Parses a GraphML file written by topology::toGraphML(). Throws gridtopo::InputError (file:line).
topology::TopologicalGraph graphFromGraphML(const std::string& path);

/// Everything the inspector shows for one cell.
struct CellInspection {
  int row = 0, col = 0;
  double x = 0, y = 0;        ///< world (m)
  double occupancy = 0;       ///< p(occupied)
  bool free = false;
  bool has_sample = false;    ///< the cell belongs to a classified lattice block
  int sample = -1;
  cv::Point sample_cell;      ///< (col,row) of the block's sample cell, whose scan was classified
  std::array<float, 3> p_classified{}, p_relaxed{};  ///< room, corridor, doorway
  int label_classified = -1, label_relaxed = -1, label_corrected = -1;  ///< -1: none
  int region = 0;             ///< region id after correction (0: none)
  std::vector<std::string> feature_names, feature_descriptions;
  std::vector<float> features;
  std::vector<cv::Point2d> scan_world;  ///< end points of the simulated 360° scan (world m)
  std::string text() const;   ///< human-readable summary
};

/// Inspects the cell at (row, col) of `t.map`. Throws std::out_of_range outside the map.
CellInspection inspectCell(const TopologyData& t, int row, int col);

struct NodeInspection {
  int id = 0, label = 0, cells = 0;
  double area_m2 = 0;
  cv::Point2d centroid_world;
  std::vector<int> neighbours;
  std::string text() const;
};
/// The graph node nearest to a world point within `radius_m`, if any.
std::optional<NodeInspection> inspectNodeAt(const TopologyData& t, double x, double y, double radius_m);

/// World position of the centre of map pixel `px` (column, row; row 0 at the top of the map image).
cv::Point2d pixelWorld(const TopologyData& t, const cv::Point2d& px);

/// World position of a graph node (its centroid, in the frame of t.map).
cv::Point2d nodeWorld(const TopologyData& t, const topology::GraphNode& n);
/// World coordinates of a node's anchor: a cell of its region (the centroid when it lies inside the region). The graph
/// is drawn through anchors so that, e.g., a corridor ring's node sits on the corridor, not in the courtyard.
cv::Point2d nodeAnchorWorld(const TopologyData& t, const topology::GraphNode& n);

/// Writes the files gridtopo-topology writes (topology.graphml/.json/.dot, overlay.png, labels.png,
/// labels_before_correction.png, segmentation.png, segmentation_colour.png, options.ini) into `dir`, all or
/// nothing.
void saveTopologyOutputs(const TopologyData& t, const std::string& dir, const topology::TopologyOptions& options);

}  // namespace gridtopo::session
