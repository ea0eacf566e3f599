#pragma once
// From place labels to the topological map: region correction, regions, graph, room segmentation.
// Options of the whole `gridtopo-topology` run, loadable from an INI file (config-ini/topology.ini).
#include <mrpt/config/CLoadableOptions.h>

#include <opencv2/core.hpp>
#include <functional>
#include <string>
#include <vector>

#include "gridtopo/core/byte_runs.h"
#include "gridtopo/core/map_image.h"
#include "gridtopo/core/option_schema.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/blob_vote.h"
#include "gridtopo/topology/correction.h"
#include "gridtopo/topology/door_passages.h"
#include "gridtopo/topology/corridor_split.h"
#include "gridtopo/topology/doorway_geometry.h"
#include "gridtopo/topology/graph.h"
#include "gridtopo/topology/graph_rules.h"
#include "gridtopo/topology/map_preparation.h"
#include "gridtopo/topology/open_spaces.h"
#include "gridtopo/topology/thoroughfares.h"
#include "gridtopo/topology/regions.h"
#include "gridtopo/topology/segmentation.h"

namespace gridtopo::topology {

struct TopologyOptions : public mrpt::config::CLoadableOptions {
  places::RelaxationOptions relaxation;  ///< section [relaxation]
  CorrectionOptions correction;          ///< section [correction]
  int threads = 2;                       ///< section [topology]
  double resolution = 0.05;              ///< [topology] m per pixel for plain images without a YAML file
  int free_threshold = 250;              ///< [topology] grey >= this is free in plain images
  /// [topology] grey = round(255 p_free) >= this is free in probabilistic grids (.gridmap/.gridmap.gz, e.g. a
  /// gridtopo-slam map, whose clamped log-odds never reach grey 250). 204 = p_free >= 0.8, i.e. ROS map_saver's
  /// free_thresh 0.196.
  int grid_free_threshold = 204;
  /// [topology] radius (m) of the morphological opening of the free space (places::openFreeSpace) for plain
  /// images (0 = off: the labelled floor plans are drawn, not scanned) ...
  double free_opening_radius = 0;
  /// ... and for maps that come with a ROS .yaml, .gridmap(.gz) files and the GUI's SLAM map: 0.05 m (one cell
  /// at 5 cm) closes the one-cell gaps of dotted walls and removes one-cell ray streaks.
  double grid_free_opening_radius = 0.05;
  /// [topology] places_prepare: which maps go through the map preparation (map_preparation.h): "maps" (ROS maps and
  /// probabilistic grids: what a robot built; drawn plans are all floor), "all", "off".
  std::string places_prepare = "maps";
  MapPreparationOptions preparation;     ///< [topology] places_robot_radius, places_view_range, places_min_area, ...
  int overlay_scale = 2;                 ///< [topology] enlargement of the PNG overlay
  std::string segmentation = "regions";  ///< [topology] regions | doorways (see segmentation.h)
  SegmentationRules seg_rules;           ///< [topology] merge_contact (S0), split_neck_width, split_min_part_area (S1)
  DoorwayGeometryOptions doorways;       ///< [topology] doorways_from_geometry, doorway_* (before the correction)
  DoorPassageOptions door_passages;      ///< [topology] door_passages, door_passage_* (with the robot's path)
  OpenSpaceOptions open_spaces;          ///< [topology] open_spaces, open_space_* (with the robot's path)
  ThoroughfareOptions thoroughfares;     ///< [topology] thoroughfares, thoroughfare_* (with the robot's path)
  BlobVoteOptions blob_vote;             ///< [topology] blob_vote, blob_vote_* (step 7b, off by default)
  CorridorSplitOptions corridor_split;   ///< [topology] corridor_split, corridor_min_branch, corridor_min_piece_area
  GraphRuleOptions graph_rules;  ///< [topology] graph_min_node_area (G1), graph_merge_doorways (G2), graph_rooms_by_segment (G3)

  /// Reads [topology], [relaxation], [correction] (`section` is the name of the first one).
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  /// Writes every key of [topology] (as `section`), [relaxation] and [correction], loadable to the same values.
  void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  void dumpToTextStream(std::ostream& out) const override;

  /// The free threshold for a map of kind `kind` (MapImage::kind, as the map reader or builder set it): grid_free_threshold for probabilistic
  /// grids (.gridmap(.gz), the SLAM's map), free_threshold otherwise (plain images and ROS YAML maps, whose readers
  /// already give 0 / 205 / 254-255 greys).
  int freeThresholdFor(MapKind kind) const;

  /// The free-space opening radius for a map of kind `kind`: free_opening_radius for plain images,
  /// grid_free_opening_radius for ROS maps and probabilistic grids.
  double freeOpeningRadiusFor(MapKind kind) const;

  /// The map preparation for a map of kind `kind`: `preparation`, disabled when places_prepare excludes the kind.
  MapPreparationOptions preparationFor(MapKind kind) const;
};

/// The key table of [topology]: the keys TopologyOptions holds itself ([relaxation] and [correction] have their own:
/// places::relaxationOptionSchema, correctionOptionSchema).
const OptionSchema<TopologyOptions>& topologyOptionSchema();

/// The three option sections of a topology run ([topology], [relaxation], [correction]) with the values of `o`.
std::vector<OptionSection> describeTopologyOptions(const TopologyOptions& o);

/// The help of every topology option (gridtopo-topology --help-options): optionsHelp of the three sections.
std::string topologyOptionsHelp();

/// The options as a loadable INI text ([topology], [relaxation], [correction]; doubles to 17 digits): what
/// loadTopologyOptions reads back to the same options.
std::string topologyOptionsIni(const TopologyOptions& options);

/// Reads a topology INI (config-ini/topology.ini: [topology], [relaxation], [correction]); an empty path gives the
/// defaults. Errors (missing file, bad value) are InputErrors that name the INI file and the key.
TopologyOptions loadTopologyOptions(const std::string& ini_path);

struct TopologyResult {
  cv::Mat labels;     ///< CV_8U after correction (and the segment vote if on): 0..2, places::kNoLabel for non-free cells
  cv::Mat labels_corrected;  ///< CV_8U after the region-correction rules only (= labels without segment vote)
  cv::Mat labels_blob_vote;  ///< CV_8U after the blob vote, before correction (empty when the blob vote is off)
  CorrectionStats correction;
  RegionMap regions;        ///< the graph's regions: 8-connected equal-label regions, corridors split at junctions
  TopologicalGraph graph;
  cv::Mat segmentation;  ///< room segmentation, 0 for non-free cells: CV_32S (CV_16U with `crop` when the ids fit)
  std::vector<DoorPassage> door_passages;  ///< the doors the robot's path went through (door_passages.h)
  std::vector<cv::Point> room_entries;     ///< where it stepped from a corridor into a room without a door (cells)
  std::vector<OpenSpace> open_spaces;      ///< the open spaces it crossed whose pieces were joined (open_spaces.h)
  std::vector<Thoroughfare> thoroughfares;  ///< room regions it travelled through, relabelled corridor (thoroughfares.h)
  /// With `crop` only: the labels buildTopology was given (the labelling's, before the blob vote and every later
  /// step), as runs in the map's frame: what labels_before_correction.png shows when the caller let its image go.
  ByteRuns labels_classified;  ///< (runs of the labelled cells: the background is places::kNoLabel)
  /// With topologyOfMap's outputs_only: the region borders the overlay draws (regionBorders of regions.ids, whose
  /// image is then let go: `regions` keeps its list), in the frame of `labels`.
  cv::Mat region_borders;
  /// The part of the map that the images above and `regions` cover: their cell (0, 0) is the map's cell frame.tl(),
  /// the map is `map_size` cells. The whole map unless buildTopology worked on the box of the labelled cells
  /// (`crop`). The graph and the positions of the door passages, room entries, open spaces and thoroughfares are in
  /// the map's frame either way.
  cv::Rect frame;
  cv::Size map_size;
  /// `image` (one of the images above) as an image of the whole map, `fill` outside the frame.
  cv::Mat inMap(const cv::Mat& image, double fill) const;
};

/// The occupancy image that labelling sees: places::occupancyFromMap with the free threshold for the map's kind
/// (o.freeThresholdFor(map.kind)), then places::openFreeSpace with o.freeOpeningRadiusFor(map.kind), then the map
/// preparation (prepareMap with o.preparationFor(map.kind) and map.path): free cells that are no place become
/// places::kSeen. `prepared`, when given, receives what the preparation found. Throws InputError (naming
/// map.source) for an unusable image or a map without free cells or without places. `map` is taken by value: a
/// caller that moves its map in lets its grey image go once the occupancy is made from it.
places::OccupancyImage occupancyForTopology(MapImage map, const TopologyOptions& o,
                                            PreparedMap* prepared = nullptr);

/// Steps 6-8 of the method, the one call every app and the GUI make after labelling: builds regions, graph and
/// segmentation from per-cell labels (e.g. LabellingResult::labels) with the run's options (`o.correction`,
/// `o.segmentation`, `o.seg_rules`, `o.corridor_split`, `o.blob_vote`). The segmentation is made from the
/// 8-connected regions (segmentRooms); the returned regions and graph then have rooms split along that segmentation
/// (G3), corridors split into pieces at their junctions (corridor_split.h) and the graph rules G1, G2 applied
/// (graph_rules.h): without the segment vote they are graphRegionsOfLabels(result.labels, ...). With `o.blob_vote.enabled`, the room / corridor labels are first voted in geometric blobs
/// (step 7b), which needs the labelling the labels come from (its lattice and relaxed probabilities): throws
/// std::invalid_argument without it. `origin`: world coordinates of the map's cell (0, 0) corner, for the graph.
/// `path`: the robot's path in cells (pathInCells of MapImage::path; empty = unknown): the doors it went through
/// become doorways (door_passages.h, `o.door_passages`) after the doorways from geometry, before the correction;
/// after it, the room / corridor pieces of one open space it crossed take one label (open_spaces.h,
/// `o.open_spaces`), the room regions it travelled through become corridor (thoroughfares.h, `o.thoroughfares`), then
/// its steps from a corridor straight into a room become doorways (addRoomEntries).
/// `crop`: every step after the blob vote works on the box of the labelled cells with a frame of one cell (the
/// result's images and regions cover that box, TopologyResult::frame): on a large map whose places fill a part of
/// it, each full-map image of the steps is that much smaller. The graph and every output are those of the whole map.
/// `labels` is taken by value: a caller that moves its image in lets it go once the box is cut (its labels are then
/// kept as runs, TopologyResult::labels_classified).
TopologyResult buildTopology(cv::Mat labels, double resolution, const TopologyOptions& o,
                             const places::LabellingResult* labelling = nullptr, cv::Point2d origin = {0, 0},
                             const std::vector<cv::Point2d>& path = {}, bool crop = false);

/// The room segmentation of the 8-connected `regions` with the run's rules (`o.segmentation`, `o.seg_rules`: S0, S1):
/// CV_32S, or CV_16U with `sixteen_bits` when the ids fit.
cv::Mat segmentRooms(const RegionMap& regions, double resolution, const TopologyOptions& o,
                     bool sixteen_bits = false);

/// The graph's regions of final labels (e.g. a run's labels.png): extractRegions, segmentRooms, graphRegions. What
/// gridtopo-topology-compare scores; equal to buildTopology's regions unless the segment vote is on (buildTopology
/// then segments the labels before the vote).
RegionMap graphRegionsOfLabels(const cv::Mat& labels, double resolution, const TopologyOptions& o);

/// A whole topology run on one typed map (grey image, resolution, world position of its lower-left corner, kind,
/// the robot's path): the free space for the map's kind (occupancyForTopology), the places (places::labelPlaces),
/// then the regions and graph (buildTopology, with the path's door passages). gridtopo-topology, the GUI and the topology map builder call this one function.
struct MapTopology {
  places::OccupancyImage occ;  ///< free cells that are places kFree, the others the preparation left kSeen
  PreparedMap prepared;
  places::LabellingResult labelling;
  TopologyResult topo;
  double seconds_prepare = 0;  ///< occupancy and map preparation (occupancyForTopology)
  double seconds_graph = 0;    ///< buildTopology: doorways, correction, regions, segmentation, graph
};
/// `outputs_only`: each full-map image that the outputs (writeTopologyOutputs) and the run summary do not read is
/// let go as soon as the run no longer needs it (the preparation's masks; the lattice grids of probabilities, the
/// classifier's labels before relaxation, the lattice's block grid; the labels before the segment vote and the blob
/// vote's; the initial probabilities and labels; the labelling's labels, kept as runs, TopologyResult::
/// labels_classified; the regions' id image, of which the overlay keeps the borders, TopologyResult::region_borders),
/// the occupancy is held as runs while the topology is built (it is the outputs' again afterwards), and the steps
/// after labelling work on the box of the labelled cells (buildTopology's `crop`): less memory at once on a large
/// map. gridtopo-topology runs so; the GUI, which shows them, does not. `map` is taken by value: a caller that moves its map in lets its grey image go once the
/// occupancy exists.
MapTopology topologyOfMap(MapImage map, const places::PlacesModel& model, const TopologyOptions& o,
                          const std::function<void(const std::string&, std::size_t, std::size_t)>& progress = {},
                          bool keep_scans_and_features = false, bool outputs_only = false);

}  // namespace gridtopo::topology
