#include "gridtopo/topology/pipeline.h"
#include "gridtopo/core/ini_value.h"

#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <string>
#include <filesystem>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/topology/segmentation.h"

namespace gridtopo::topology {

namespace {
// One table drives load and save of the [topology] keys, so that neither can miss one.
template <class Options, class F>
void forEachTopologyKey(Options& o, F&& f) {
  f("threads", o.threads);
  f("resolution", o.resolution);
  f("free_threshold", o.free_threshold);
  f("grid_free_threshold", o.grid_free_threshold);
  f("free_opening_radius", o.free_opening_radius);
  f("grid_free_opening_radius", o.grid_free_opening_radius);
  f("overlay_scale", o.overlay_scale);
  f("segmentation", o.segmentation);
  f("merge_contact", o.seg_rules.merge_contact);
  f("split_neck_width", o.seg_rules.neck_width);
  f("split_min_part_area", o.seg_rules.min_part_area);
  f("split_fill_obstacle_area", o.seg_rules.fill_obstacle_area);
  f("segment_vote", o.seg_rules.segment_vote);
  f("blob_vote", o.blob_vote.enabled);
  f("blob_vote_neck_width", o.blob_vote.neck_width);
  f("blob_vote_min_core_area", o.blob_vote.min_core_area);
  f("blob_vote_grow_limit", o.blob_vote.grow_limit);
  f("blob_vote_fill_obstacle_area", o.blob_vote.fill_obstacle_area);
  f("blob_vote_min_share", o.blob_vote.min_share);
  f("corridor_split", o.corridor_split.enabled);
  f("corridor_min_branch", o.corridor_split.min_branch);
  f("corridor_min_piece_area", o.corridor_split.min_piece_area);
  f("graph_min_node_area", o.graph_rules.min_node_area);
  f("graph_merge_doorways", o.graph_rules.merge_doorways);
}
}  // namespace

void TopologyOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& s, const std::string& sec) {
  forEachTopologyKey(*this, [&](const char* key, auto& value) { readIniValue(s, sec, key, value); });
  const std::string where = "[" + sec + "]";
  if (threads < 1 || threads > 256) throw InputError(where, 0, "threads", "must be in [1, 256]");
  if (!(resolution > 0) || !std::isfinite(resolution)) throw InputError(where, 0, "resolution", "must be > 0");
  if (free_threshold < 1 || free_threshold > 255) throw InputError(where, 0, "free_threshold", "must be in [1, 255]");
  if (grid_free_threshold < 129 || grid_free_threshold > 255)
    throw InputError(where, 0, "grid_free_threshold", "must be in [129, 255] (p_free > 0.5)");
  if (!(free_opening_radius >= 0 && free_opening_radius <= 1))
    throw InputError(where, 0, "free_opening_radius", "must be in [0, 1] metres (0 = off)");
  if (!(grid_free_opening_radius >= 0 && grid_free_opening_radius <= 1))
    throw InputError(where, 0, "grid_free_opening_radius", "must be in [0, 1] metres (0 = off)");
  if (segmentation != "regions" && segmentation != "doorways")
    throw InputError(where, 0, "segmentation", "must be regions or doorways");
  if (!(seg_rules.merge_contact >= 0 && seg_rules.merge_contact <= 100))
    throw InputError(where, 0, "merge_contact", "must be in [0, 100] metres (0 = off)");
  if (!(seg_rules.neck_width >= 0 && seg_rules.neck_width <= 10))
    throw InputError(where, 0, "split_neck_width", "must be in [0, 10] metres (0 = off)");
  if (!(seg_rules.min_part_area > 0 && seg_rules.min_part_area <= 1000))
    throw InputError(where, 0, "split_min_part_area", "must be in (0, 1000] square metres");
  if (!(seg_rules.fill_obstacle_area >= 0 && seg_rules.fill_obstacle_area <= 1000))
    throw InputError(where, 0, "split_fill_obstacle_area", "must be in [0, 1000] square metres (0 = off)");
  if (!(blob_vote.neck_width > 0 && blob_vote.neck_width <= 20))
    throw InputError(where, 0, "blob_vote_neck_width", "must be in (0, 20] metres");
  if (!(blob_vote.min_core_area > 0 && blob_vote.min_core_area <= 1000))
    throw InputError(where, 0, "blob_vote_min_core_area", "must be in (0, 1000] square metres");
  if (!(blob_vote.grow_limit >= 0 && blob_vote.grow_limit <= 100))
    throw InputError(where, 0, "blob_vote_grow_limit", "must be in [0, 100] metres (0 = no limit)");
  if (!(blob_vote.fill_obstacle_area >= 0 && blob_vote.fill_obstacle_area <= 1000))
    throw InputError(where, 0, "blob_vote_fill_obstacle_area", "must be in [0, 1000] square metres (0 = off)");
  if (!(blob_vote.min_share >= 0.5 && blob_vote.min_share <= 1))
    throw InputError(where, 0, "blob_vote_min_share", "must be in [0.5, 1]");
  if (!(corridor_split.min_branch >= 0 && corridor_split.min_branch <= 100))
    throw InputError(where, 0, "corridor_min_branch", "must be in [0, 100] metres");
  if (!(corridor_split.min_piece_area >= 0 && corridor_split.min_piece_area <= 1000))
    throw InputError(where, 0, "corridor_min_piece_area", "must be in [0, 1000] square metres");
  if (!(graph_rules.min_node_area >= 0 && graph_rules.min_node_area <= 100))
    throw InputError(where, 0, "graph_min_node_area", "must be in [0, 100] square metres (0 = off)");
  if (overlay_scale < 1 || overlay_scale > 8) throw InputError(where, 0, "overlay_scale", "must be in [1, 8]");
  relaxation.loadFromConfigFile(s, "relaxation");
  correction.loadFromConfigFile(s, "correction");
}

void TopologyOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t, const std::string& sec) const {
  forEachTopologyKey(*this, [&](const char* key, const auto& value) { t.write(sec, key, iniText(value)); });
  relaxation.saveToConfigFile(t, "relaxation");
  correction.saveToConfigFile(t, "correction");
}

std::string topologyOptionsIni(const TopologyOptions& options) {
  mrpt::config::CConfigFileMemory ini;
  options.saveToConfigFile(ini, "topology");
  return ini.getContent();
}

void TopologyOptions::dumpToTextStream(std::ostream& out) const {
  out << "[topology]\nthreads        = " << threads << "\nresolution     = " << resolution
      << "\nfree_threshold = " << free_threshold << "\ngrid_free_threshold = " << grid_free_threshold
      << "\nfree_opening_radius = " << free_opening_radius
      << "\ngrid_free_opening_radius = " << grid_free_opening_radius
      << "\noverlay_scale  = " << overlay_scale << "\nsegmentation   = " << segmentation << "\nmerge_contact  = " << seg_rules.merge_contact << "\nsplit_neck_width = " << seg_rules.neck_width
      << "\nsplit_min_part_area = " << seg_rules.min_part_area
      << "\nsplit_fill_obstacle_area = " << seg_rules.fill_obstacle_area
      << "\nsegment_vote   = " << (seg_rules.segment_vote ? "true" : "false")
      << "\nblob_vote      = " << (blob_vote.enabled ? "true" : "false")
      << "\nblob_vote_neck_width = " << blob_vote.neck_width << "\nblob_vote_min_core_area = " << blob_vote.min_core_area
      << "\nblob_vote_grow_limit = " << blob_vote.grow_limit
      << "\nblob_vote_fill_obstacle_area = " << blob_vote.fill_obstacle_area
      << "\nblob_vote_min_share = " << blob_vote.min_share
      << "\ncorridor_split = " << (corridor_split.enabled ? "true" : "false")
      << "\ncorridor_min_branch = " << corridor_split.min_branch
      << "\ncorridor_min_piece_area = " << corridor_split.min_piece_area
      << "\ngraph_min_node_area = " << graph_rules.min_node_area
      << "\ngraph_merge_doorways = " << (graph_rules.merge_doorways ? "true" : "false") << "\n[relaxation]\n";
  relaxation.dumpToTextStream(out);
  out << "[correction]\n";
  correction.dumpToTextStream(out);
}

TopologyOptions loadTopologyOptions(const std::string& ini_path) {
  TopologyOptions opt;
  if (ini_path.empty()) return opt;
  if (!std::filesystem::is_regular_file(ini_path)) throw InputError(ini_path, "INI file not found");
  try {
    opt.loadFromConfigFile(mrpt::config::CConfigFile(ini_path), "topology");
  } catch (const InputError& e) {
    throw InputError(ini_path, 0, e.file() + " " + e.field(), e.message());
  }
  return opt;
}

int TopologyOptions::freeThresholdFor(MapKind kind) const {
  return kind == MapKind::ProbabilisticGrid ? grid_free_threshold : free_threshold;
}

double TopologyOptions::freeOpeningRadiusFor(MapKind kind) const {
  return kind == MapKind::PlainImage ? free_opening_radius : grid_free_opening_radius;
}

places::OccupancyImage occupancyForTopology(const MapImage& map, const TopologyOptions& o) {
  const double opening_radius = o.freeOpeningRadiusFor(map.kind);
  places::OccupancyImage occ = places::occupancyFromMap(map, o.freeThresholdFor(map.kind));
  const std::string& source = map.source;
  if (places::countFree(occ) == 0) throw InputError(source, "the map has no free cell (nothing to label)");
  places::openFreeSpace(occ, opening_radius);
  if (places::countFree(occ) == 0)
    throw InputError(source, "no free cell is left after the free-space opening of radius " +
                                 std::to_string(opening_radius) + " m (free_opening_radius / grid_free_opening_radius)");
  return occ;
}

TopologyResult buildTopology(const cv::Mat& labels, double resolution, const TopologyOptions& o,
                             const places::LabellingResult* labelling, cv::Point2d origin) {
  TopologyResult r;
  cv::Mat input = labels;
  if (o.blob_vote.enabled) {
    if (!labelling || labelling->probs.empty())
      throw std::invalid_argument("buildTopology: the blob vote needs the labelling (lattice, relaxed probabilities)");
    r.labels_blob_vote = voteInGeometricBlobs(labels, resolution, o.blob_vote, labelling->lattice, labelling->probs);
    input = r.labels_blob_vote;
  }
  r.labels = correctRegions(input, resolution, o.correction, &r.correction);
  r.regions = extractRegions(r.labels, resolution);
  r.segmentation = o.segmentation == "doorways" ? doorwaySegmentation(r.regions)
                                                : roomSegmentation(r.regions, o.seg_rules.merge_contact, resolution);
  if (o.seg_rules.neck_width > 0) r.segmentation = splitAtNecks(r.segmentation, resolution, o.seg_rules);
  r.labels_corrected = r.labels;
  if (o.seg_rules.segment_vote) {
    r.labels = voteLabelsInSegments(r.labels, r.segmentation);
    r.regions = extractRegions(r.labels, resolution);
  }
  r.regions = applyGraphRules(splitCorridors(r.regions, resolution, o.corridor_split), resolution, o.graph_rules);
  r.graph = buildGraph(r.regions, resolution, origin);
  return r;
}

MapTopology topologyOfMap(const MapImage& map, const places::PlacesModel& model, const TopologyOptions& o,
                          const std::function<void(const std::string&, std::size_t, std::size_t)>& progress,
                          bool keep_scans_and_features) {
  MapTopology t;
  t.occ = occupancyForTopology(map, o);
  t.labelling =
      places::labelPlaces(t.occ, model, o.relaxation, o.threads, map.source, progress, keep_scans_and_features);
  if (progress) progress("regions", 0, 1);
  t.topo = buildTopology(t.labelling.labels, t.occ.resolution, o, &t.labelling, map.origin);
  return t;
}

}  // namespace gridtopo::topology
