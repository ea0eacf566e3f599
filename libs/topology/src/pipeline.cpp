#include "gridtopo/topology/pipeline.h"

#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <filesystem>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/segmentation.h"

namespace gridtopo::topology {

const OptionSchema<TopologyOptions>& topologyOptionSchema() {
  using O = TopologyOptions;
  using R = OptionRange;
  static const OptionSchema<O> schema =
      OptionSchema<O>("gridtopo::topology::TopologyOptions")
          .add("threads", &O::threads, R::closed(1, 256), "", "worker threads (results do not depend on it)")
          .add("resolution", &O::resolution, R::above(0), "m", "pixel size of plain images without a ROS .yaml")
          .add("free_threshold", &O::free_threshold, R::closed(1, 255), "grey", "plain images: grey >= this is free")
          .add("grid_free_threshold", &O::grid_free_threshold, R::closed(129, 255), "grey",
               "probabilistic grids (.gridmap, SLAM maps): grey = round(255 p_free) >= this is free")
          .add("free_opening_radius", &O::free_opening_radius, R::closed(0, 1), "m",
               "plain images: radius of the opening of the free space (0 = off)")
          .add("grid_free_opening_radius", &O::grid_free_opening_radius, R::closed(0, 1), "m",
               "ROS maps, probabilistic grids and the GUI's SLAM map: radius of the opening (0 = off)")
          .addWords<std::string>("places_prepare", field(&O::places_prepare),
                                 {{"maps", "maps"}, {"all", "all"}, {"off", "off"}},
                                 "map preparation (which free cells are places) for ROS maps and probabilistic grids "
                                 "(maps), every map (all) or none (off: every free cell is a place)")
          .add("places_robot_radius", field(&O::preparation, &MapPreparationOptions::robot_radius), R::closed(0, 2),
               "m", "a place lies in a free disc of this radius (0 = off)")
          .add("places_view_range", field(&O::preparation, &MapPreparationOptions::view_range), R::closed(0, 100),
               "m", "with the robot's path: a place was seen from at most this far (0 = off)")
          .add("places_min_area", field(&O::preparation, &MapPreparationOptions::min_area), R::closed(0, 1000), "m^2",
               "smaller connected groups of places (and, with the path, groups it does not enter) are none")
          .add("places_path_step", field(&O::preparation, &MapPreparationOptions::path_step), R::closed(0.01, 10), "m",
               "the path is sampled this far apart for the visibility test")
          .add("overlay_scale", &O::overlay_scale, R::closed(1, 8), "", "enlargement of overlay.png (lowered on maps so large that the image would exceed 16384 px a side or 128 Mpx)")
          .addWords<std::string>("segmentation", field(&O::segmentation), {{"regions", "regions"}, {"doorways", "doorways"}},
                                 "room segmentation: every room / corridor region (regions) or only doorways split")
          .add("merge_contact", field(&O::seg_rules, &SegmentationRules::merge_contact), R::closed(0, 100), "m",
               "S0: a room and a corridor touching along more than this are one place (0 = off)")
          .add("split_neck_width", field(&O::seg_rules, &SegmentationRules::neck_width), R::closed(0, 10), "m",
               "S1: split segments at passages narrower than this (0 = off)")
          .add("split_min_part_area", field(&O::seg_rules, &SegmentationRules::min_part_area), R::leftOpen(0, 1000),
               "m^2", "S1: each part keeps at least this area")
          .add("split_fill_obstacle_area", field(&O::seg_rules, &SegmentationRules::fill_obstacle_area),
               R::closed(0, 1000), "m^2", "S1: enclosed obstacles up to this area count as the segment's (0 = off)")
          .add("segment_vote", field(&O::seg_rules, &SegmentationRules::segment_vote), R::any(), "",
               "room and corridor cells take their segment's majority label")
          .add("doorways_from_geometry", field(&O::doorways, &DoorwayGeometryOptions::enabled), R::any(), "",
               "critical lines of the places' Voronoi diagram (narrow passages between wider spaces) become doorways")
          .add("doorway_min_width", field(&O::doorways, &DoorwayGeometryOptions::min_width), R::closed(0, 10), "m",
               "narrowest door")
          .add("doorway_max_width", field(&O::doorways, &DoorwayGeometryOptions::max_width), R::closed(0, 10), "m",
               "widest door")
          .add("doorway_wider_by", field(&O::doorways, &DoorwayGeometryOptions::wider_by), R::closed(0, 10), "m",
               "on both sides the clearance grows beyond the door's half width by this")
          .add("doorway_reach", field(&O::doorways, &DoorwayGeometryOptions::reach), R::leftOpen(0, 20), "m",
               "how far each side is looked at")
          .add("doorway_depth", field(&O::doorways, &DoorwayGeometryOptions::depth), R::leftOpen(0, 2), "m",
               "thickness of a geometric doorway across its line")
          .add("doorway_refuse_unsupported", field(&O::doorways, &DoorwayGeometryOptions::refuse_unsupported),
               R::any(), "", "classifier doorways no critical line reaches take the label around them")
          .add("door_passages", field(&O::door_passages, &DoorPassageOptions::enabled), R::any(), "",
               "with the robot's path (-t): where it went through a narrow opening, a doorway across the opening")
          .add("door_passage_min_width", field(&O::door_passages, &DoorPassageOptions::min_width), R::closed(0, 10),
               "m", "narrowest door passage")
          .add("door_passage_max_width", field(&O::door_passages, &DoorPassageOptions::max_width), R::leftOpen(0, 10),
               "m", "widest door passage")
          .add("door_passage_max_length", field(&O::door_passages, &DoorPassageOptions::max_length),
               R::leftOpen(0, 10), "m", "the narrow stretch along the path is at most this long")
          .add("door_passage_wider_by", field(&O::door_passages, &DoorPassageOptions::wider_by), R::closed(0, 10), "m",
               "before and after the stretch the width exceeds the door's by this")
          .add("door_passage_context", field(&O::door_passages, &DoorPassageOptions::context), R::leftOpen(0, 20), "m",
               "how far along the path before and after the stretch is looked at")
          .add("door_passage_max_angle", field(&O::door_passages, &DoorPassageOptions::max_angle), R::closed(0, 80),
               "deg", "the door's chord is the shortest within this angle of the normal to the travel direction")
          .add("door_passage_depth", field(&O::door_passages, &DoorPassageOptions::depth), R::leftOpen(0, 2), "m",
               "thickness of a door passage's doorway across its chord")
          .add("door_passage_room_entries", field(&O::door_passages, &DoorPassageOptions::room_entries), R::any(),
               "", "after the correction: where the path steps from a corridor straight into a room, a doorway")
          .add("door_passage_entry_depth", field(&O::door_passages, &DoorPassageOptions::entry_depth),
               R::closed(0, 20), "m", "a room entry: the path goes at least this far from the corridor into the room")
          .add("open_spaces", field(&O::open_spaces, &OpenSpaceOptions::enabled), R::any(), "",
               "with the robot's path (-t), after the correction: room / corridor pieces it crossed with no doorway "
               "and no constriction between them are one space, labelled by the larger area")
          .add("open_space_min_contact", field(&O::open_spaces, &OpenSpaceOptions::min_contact), R::closed(0, 100),
               "m", "two pieces are one space only where they share a border at least this long (no door between)")
          .add("open_space_min_through", field(&O::open_spaces, &OpenSpaceOptions::min_through), R::closed(0, 100),
               "m", "a piece changes its label only where the path entered and left it at points this far apart")
          .add("open_space_min_shared", field(&O::open_spaces, &OpenSpaceOptions::min_shared), R::closed(0, 1), "",
               "a piece changes its label only when this share of its border lies against the space's other pieces")
          .add("thoroughfares", field(&O::thoroughfares, &ThoroughfareOptions::enabled), R::any(), "",
               "with the robot's path (-t), after the open spaces: a room region it travelled through (came in at one "
               "place and went out at another, again and again) becomes corridor")
          .add("thoroughfare_min_crossings", field(&O::thoroughfares, &ThoroughfareOptions::min_crossings),
               R::closed(1, 1000), "", "a thoroughfare was crossed at least this often")
          .add("thoroughfare_min_span", field(&O::thoroughfares, &ThoroughfareOptions::min_span), R::closed(0, 100),
               "m", "a crossing entered and left the room at points at least this far apart")
          .add("thoroughfare_min_openings", field(&O::thoroughfares, &ThoroughfareOptions::min_openings),
               R::closed(1, 1000), "", "the path entered or left a thoroughfare at this many distinct places")
          .add("thoroughfare_opening_radius", field(&O::thoroughfares, &ThoroughfareOptions::opening_radius),
               R::leftOpen(0, 100), "m", "entries and exits closer than this are one opening")
          .add("thoroughfare_min_area", field(&O::thoroughfares, &ThoroughfareOptions::min_area), R::closed(0, 10000),
               "m^2", "smaller room regions are never thoroughfares")
          .add("thoroughfare_min_coverage", field(&O::thoroughfares, &ThoroughfareOptions::min_coverage),
               R::closed(0, 1), "", "at least this share of a thoroughfare's cells lies near the path inside it")
          .add("thoroughfare_cover_radius", field(&O::thoroughfares, &ThoroughfareOptions::cover_radius),
               R::leftOpen(0, 100), "m", "a cell within this distance of the path (inside the room) is near it")
          .rule("door_passage_max_width",
                [](const O& o) -> std::optional<std::string> {
                  if (o.door_passages.max_width >= o.door_passages.min_width) return std::nullopt;
                  return "must be at least door_passage_min_width (" + std::to_string(o.door_passages.min_width) +
                         "), got " + std::to_string(o.door_passages.max_width);
                })
          .add("blob_vote", field(&O::blob_vote, &BlobVoteOptions::enabled), R::any(), "",
               "step 7b: vote room / corridor labels in geometric blobs")
          .add("blob_vote_neck_width", field(&O::blob_vote, &BlobVoteOptions::neck_width), R::leftOpen(0, 20), "m",
               "blobs are separated by passages narrower than this")
          .add("blob_vote_min_core_area", field(&O::blob_vote, &BlobVoteOptions::min_core_area), R::leftOpen(0, 1000),
               "m^2", "smaller cores seed no blob")
          .add("blob_vote_grow_limit", field(&O::blob_vote, &BlobVoteOptions::grow_limit), R::closed(0, 100), "m",
               "a core grows back over at most this distance (0 = no limit)")
          .add("blob_vote_fill_obstacle_area", field(&O::blob_vote, &BlobVoteOptions::fill_obstacle_area),
               R::closed(0, 1000), "m^2", "enclosed obstacles up to this area count as free (0 = off)")
          .add("blob_vote_min_share", field(&O::blob_vote, &BlobVoteOptions::min_share), R::closed(0.5, 1), "",
               "a blob is voted only when the winner holds this share of its probability mass")
          .add("corridor_split", field(&O::corridor_split, &CorridorSplitOptions::enabled), R::any(), "",
               "one graph node per corridor junction and per branch")
          .add("corridor_min_branch", field(&O::corridor_split, &CorridorSplitOptions::min_branch), R::closed(0, 100),
               "m", "shorter side branches beyond the corridor's wall are pruned")
          .add("corridor_min_piece_area", field(&O::corridor_split, &CorridorSplitOptions::min_piece_area),
               R::closed(0, 1000), "m^2", "smaller corridor pieces join their longest-border neighbour")
          .add("graph_min_node_area", field(&O::graph_rules, &GraphRuleOptions::min_node_area), R::closed(0, 100),
               "m^2", "G1: smaller regions join a neighbour node (0 = off)")
          .add("graph_merge_doorways", field(&O::graph_rules, &GraphRuleOptions::merge_doorways), R::any(), "",
               "G2: doorways between the same two places become one")
          .add("graph_rooms_by_segment", field(&O::graph_rules, &GraphRuleOptions::rooms_by_segment), R::any(), "",
               "G3: a room region the segmentation splits is one node per segment");
  return schema;
}

std::vector<OptionSection> describeTopologyOptions(const TopologyOptions& o) {
  return {{"topology", topologyOptionSchema().describe(o)},
          {"relaxation", places::relaxationOptionSchema().describe(o.relaxation)},
          {"correction", correctionOptionSchema().describe(o.correction)}};
}

std::string topologyOptionsHelp() {
  std::string text;
  for (const auto& [section, keys] : describeTopologyOptions(TopologyOptions()))
    text += (text.empty() ? "" : "\n") + optionsHelp(section, keys);
  return text;
}

void TopologyOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& s, const std::string& sec) {
  topologyOptionSchema().load(*this, s, sec);
  relaxation.loadFromConfigFile(s, "relaxation");
  correction.loadFromConfigFile(s, "correction");
}

void TopologyOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t, const std::string& sec) const {
  topologyOptionSchema().save(*this, t, sec);
  relaxation.saveToConfigFile(t, "relaxation");
  correction.saveToConfigFile(t, "correction");
}

std::string topologyOptionsIni(const TopologyOptions& options) {
  mrpt::config::CConfigFileMemory ini;
  options.saveToConfigFile(ini, "topology");
  return ini.getContent();
}

void TopologyOptions::dumpToTextStream(std::ostream& out) const {
  topologyOptionSchema().dump(*this, out);
  relaxation.dumpToTextStream(out);
  correction.dumpToTextStream(out);
}

TopologyOptions loadTopologyOptions(const std::string& ini_path) {
  TopologyOptions opt;
  if (ini_path.empty()) return opt;
  if (!std::filesystem::is_regular_file(ini_path)) throw InputError(ini_path, "INI file not found");
  opt.loadFromConfigFile(mrpt::config::CConfigFile(ini_path), "topology");  // errors name the file and the key
  return opt;
}

int TopologyOptions::freeThresholdFor(MapKind kind) const {
  return kind == MapKind::ProbabilisticGrid ? grid_free_threshold : free_threshold;
}

double TopologyOptions::freeOpeningRadiusFor(MapKind kind) const {
  return kind == MapKind::PlainImage ? free_opening_radius : grid_free_opening_radius;
}

MapPreparationOptions TopologyOptions::preparationFor(MapKind kind) const {
  MapPreparationOptions p = preparation;
  p.enabled = places_prepare == "all" || (places_prepare == "maps" && kind != MapKind::PlainImage);
  return p;
}

places::OccupancyImage occupancyForTopology(MapImage map, const TopologyOptions& o, PreparedMap* prepared) {
  const double opening_radius = o.freeOpeningRadiusFor(map.kind);
  places::OccupancyImage occ = places::occupancyFromMap(map, o.freeThresholdFor(map.kind));
  map.grey.release();  // (freed here when the caller moved its map in)
  const std::string& source = map.source;
  if (places::countFree(occ) == 0) throw InputError(source, "the map has no free cell (nothing to label)");
  places::openFreeSpace(occ, opening_radius);
  if (places::countFree(occ) == 0)
    throw InputError(source, "no free cell is left after the free-space opening of radius " +
                                 std::to_string(opening_radius) + " m (free_opening_radius / grid_free_opening_radius)");
  PreparedMap p = prepareMap(occ, o.preparationFor(map.kind),
                             pathInCells(map.path, map.origin, occ.resolution, occ.rows()), o.threads);
  if (p.place_cells == 0)
    throw InputError(source, "no free cell is a place (places_robot_radius, places_view_range, places_min_area)");
  occ.cells.setTo(places::kSeen, p.seen_not_place);
  if (prepared) *prepared = std::move(p);
  return occ;
}

namespace {
// The box of the cells with a place label, widened by one cell (within the image); the whole image when none.
cv::Rect labelledBox(const cv::Mat& labels) {
  int x0 = labels.cols, y0 = labels.rows, x1 = -1, y1 = -1;
  for (int y = 0; y < labels.rows; ++y) {
    const unsigned char* row = labels.ptr<unsigned char>(y);
    int first = -1, last = -1;
    for (int x = 0; x < labels.cols; ++x)
      if (row[x] < places::kNumLabels) {
        if (first < 0) first = x;
        last = x;
      }
    if (first < 0) continue;
    x0 = std::min(x0, first), x1 = std::max(x1, last), y0 = std::min(y0, y), y1 = y;
  }
  const cv::Rect all(0, 0, labels.cols, labels.rows);
  if (x1 < 0) return all;
  // The box starts at even coordinates: the regions are numbered in the order of their first 2 x 2 block
  // (extractRegions), the same blocks as on the whole map.
  const int bx = std::max(0, x0 - 1) & ~1, by = std::max(0, y0 - 1) & ~1;
  return cv::Rect(bx, by, x1 + 2 - bx, y1 + 2 - by) & all;
}
}  // namespace

cv::Mat TopologyResult::inMap(const cv::Mat& image, double fill) const {
  if (image.empty() || map_size.empty() || (frame.tl() == cv::Point() && image.size() == map_size)) return image;
  cv::Mat out(map_size, image.type(), cv::Scalar::all(fill));
  image.copyTo(out(frame));
  return out;
}

TopologyResult buildTopology(cv::Mat labels, double resolution, const TopologyOptions& o,
                             const places::LabellingResult* labelling, cv::Point2d origin,
                             const std::vector<cv::Point2d>& map_path, bool crop) {
  TopologyResult r;
  r.map_size = labels.size();
  r.frame = cv::Rect(cv::Point(), labels.size());
  cv::Mat input = labels;
  if (o.blob_vote.enabled) {
    if (!labelling || labelling->probs.empty())
      throw std::invalid_argument("buildTopology: the blob vote needs the labelling (lattice, relaxed probabilities)");
    r.labels_blob_vote = voteInGeometricBlobs(labels, resolution, o.blob_vote, labelling->lattice, labelling->probs);
    input = r.labels_blob_vote;
  }
  // From here on the steps see the box of the labelled cells (a cell outside it has no label: every step's result
  // is the same, DoorPassages.CropToTheLabelledBoxGivesTheWholeMapsTopology), the path in its frame.
  if (crop) r.frame = labelledBox(input);
  const cv::Point off = r.frame.tl();
  const bool part = r.frame.size() != labels.size();
  if (part) {
    input = input(r.frame).clone();
    if (!r.labels_blob_vote.empty()) r.labels_blob_vote = input;
  }
  if (crop) {
    // The labels as they came, for labels_before_correction.png; a caller that moved its labels in lets them go.
    r.labels_classified = ByteRuns::of(labels, places::kNoLabel);
    labels.release();
  }
  std::vector<cv::Point2d> shifted;
  if (part) {
    shifted.reserve(map_path.size());
    for (const cv::Point2d& p : map_path) shifted.push_back(p - cv::Point2d(off));
  }
  const std::vector<cv::Point2d>& path = part ? shifted : map_path;
  if (o.doorways.enabled) input = addGeometricDoorways(input, resolution, o.doorways);
  if (o.door_passages.enabled && !path.empty())
    input = addDoorPassages(input, path, resolution, o.door_passages, &r.door_passages);
  r.labels = correctRegions(input, resolution, o.correction, &r.correction);
  input.release();  // on a large map, a full-map image the later steps do not read
  if (o.open_spaces.enabled && !path.empty())
    r.labels = mergeOpenSpaces(r.labels, path, resolution, o.open_spaces, &r.open_spaces);
  if (o.thoroughfares.enabled && !path.empty())
    r.labels = relabelThoroughfares(r.labels, path, resolution, o.thoroughfares, &r.thoroughfares);
  if (o.door_passages.enabled && o.door_passages.room_entries && !path.empty())
    r.labels = addRoomEntries(r.labels, path, resolution, o.door_passages, &r.room_entries);
  r.regions = extractRegions(r.labels, resolution);
  // On the box (gridtopo-topology's runs) the segmentation is made in 16 bits when its ids fit (the GUI and the
  // evaluation keep CV_32S; the segment vote reads CV_32S).
  r.segmentation = segmentRooms(r.regions, resolution, o, crop && !o.seg_rules.segment_vote);
  r.labels_corrected = r.labels;
  if (o.seg_rules.segment_vote) {
    r.labels = voteLabelsInSegments(r.labels, r.segmentation);
    r.regions = extractRegions(r.labels, resolution);
  }
  r.regions = graphRegions(std::move(r.regions), r.segmentation, resolution, o.corridor_split, o.graph_rules);
  r.graph = buildGraph(r.regions, resolution, origin, off, r.map_size);
  // The path's findings in the map's frame.
  if (part) {
    const cv::Point2d offd(off);
    for (DoorPassage& d : r.door_passages) d.a += offd, d.b += offd, d.centre += off;
    for (cv::Point& p : r.room_entries) p += off;
    for (OpenSpace& s : r.open_spaces) s.at += off;
    for (Thoroughfare& t : r.thoroughfares) t.at += off;
  }
  return r;
}

cv::Mat segmentRooms(const RegionMap& regions, double resolution, const TopologyOptions& o, bool sixteen_bits) {
  cv::Mat s = o.segmentation == "doorways"
                  ? doorwaySegmentation(regions, sixteen_bits)
                  : roomSegmentation(regions, o.seg_rules.merge_contact, resolution, sixteen_bits);
  if (o.seg_rules.neck_width > 0) splitAtNecksInPlace(s, resolution, o.seg_rules);
  return s;
}

RegionMap graphRegionsOfLabels(const cv::Mat& labels, double resolution, const TopologyOptions& o) {
  const RegionMap regions = extractRegions(labels, resolution);
  return graphRegions(regions, segmentRooms(regions, resolution, o), resolution, o.corridor_split, o.graph_rules);
}

MapTopology topologyOfMap(MapImage map, const places::PlacesModel& model, const TopologyOptions& o,
                          const std::function<void(const std::string&, std::size_t, std::size_t)>& progress,
                          bool keep_scans_and_features, bool outputs_only) {
  MapTopology t;
  const auto since = [](std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  auto t0 = std::chrono::steady_clock::now();
  {
    // The map goes in without keeping its grey image here: once the occupancy exists it is let go (freed when the
    // caller moved its map in); the later steps read the occupancy.
    MapImage grey_holder = map;
    map.grey.release();
    t.occ = occupancyForTopology(std::move(grey_holder), o, &t.prepared);
  }
  t.seconds_prepare = since(t0);
  const auto releaseLabellingGrids = [&] {
    for (cv::Mat* m : {&t.labelling.probs_initial, &t.labelling.probs, &t.labelling.valid,
                       &t.labelling.labels_initial, &t.labelling.lattice.block_sample})
      m->release();
  };
  if (outputs_only) t.prepared.places.release(), t.prepared.seen_not_place.release();
  // With outputs_only the lattice grids are kept only for the blob vote.
  t.labelling = places::labelPlaces(t.occ, model, o.relaxation, o.threads, map.source, progress,
                                    keep_scans_and_features, /*keep_initial=*/!outputs_only,
                                    /*keep_grids=*/!outputs_only || o.blob_vote.enabled);
  if (outputs_only && !o.blob_vote.enabled) releaseLabellingGrids();  // else the blob vote reads them
  if (progress) progress("regions", 0, 1);
  t0 = std::chrono::steady_clock::now();
  const std::vector<cv::Point2d> path = pathInCells(map.path, map.origin, t.occ.resolution, t.occ.rows());
  // With outputs_only the occupancy, which buildTopology does not read, waits as runs (unknown cells left out).
  ByteRuns occupancy;
  if (outputs_only) occupancy = ByteRuns::of(t.occ.cells, places::kUnknown), t.occ.cells.release();
  // With outputs_only the labelling's labels go into the topology, which keeps them as runs (labels_classified).
  t.topo = buildTopology(outputs_only ? std::move(t.labelling.labels) : t.labelling.labels, t.occ.resolution, o,
                         &t.labelling, map.origin,
                         path, /*crop=*/outputs_only);
  t.seconds_graph = since(t0);
  if (outputs_only) {
    t.occ.cells = occupancy.image();
    // The overlay needs only the regions' borders: an 8-bit image instead of the 32-bit ids.
    t.topo.region_borders = regionBorders(t.topo.regions.ids);
    t.topo.regions.ids.release();
    releaseLabellingGrids();
    t.topo.labels_corrected.release();
    t.topo.labels_blob_vote.release();
  }
  return t;
}

}  // namespace gridtopo::topology
