#include "gridtopo/eval/reference_comparison.h"

#include <filesystem>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/eval/label_views.h"
#include "gridtopo/eval/lomo_report.h"
#include "gridtopo/eval/oracle_diagnostics.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/export.h"
#include "gridtopo/topology/map_preparation.h"

namespace gridtopo::eval {

namespace {

cv::Mat readImage(const std::string& path, int flags) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "file not found");
  cv::Mat m = cv::imread(path, flags);
  if (m.empty()) throw InputError(path, "cannot read the image (missing file or unknown format)");
  return m;
}

// The oracle region vote of our labels in the plan's place regions on the map, scored like the labels (one-hot
// probabilities: each region's room / corridor majority by cell count).
double regionVoteOracleAccuracy(const TopologyComparison& c) {
  cv::Mat codes = warpReferenceToMap(c.reference_codes, c.score.alignment, c.map_free.size());
  codes.setTo(0, c.map_free == 0);
  cv::Mat onehot(c.labels.size(), CV_32FC3, cv::Scalar::all(0));
  for (int y = 0; y < onehot.rows; ++y)
    for (int x = 0; x < onehot.cols; ++x) {
      const int l = c.labels.at<unsigned char>(y, x);
      if (l >= 0 && l < 3) onehot.at<cv::Vec3f>(y, x)[l] = 1.0f;
    }
  ConfusionMatrix m;
  m.add(codes, oracleRegionVote(codes, c.labels, onehot, true));
  return m.accuracy();
}

}  // namespace

TopologyComparison compareWithReference(const std::string& map, const std::string& dir, const ReferencePlan& plan,
                                        const topology::TopologyOptions& opt, const std::string& trajectory) {
  TopologyComparison c;
  c.map = map;
  const MapImage m = io::readMap(map, io::MapReadOptions{});
  // The map's free cells as thresholded, without the free-space opening: the scored area does not depend on it.
  c.occ = places::occupancyFromMap(m, opt.freeThresholdFor(m.kind));
  c.map_free = c.occ.cells == places::kFree;

  const cv::Mat codes = readImage(dir + "/labels.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat seg16 = readImage(dir + "/segmentation.png", cv::IMREAD_UNCHANGED);
  if (codes.size() != c.map_free.size() || seg16.size() != c.map_free.size())
    throw InputError(dir, "labels.png / segmentation.png are not the size of the map (" +
                              std::to_string(c.map_free.cols) + "x" + std::to_string(c.map_free.rows) + ")");
  c.labels = places::labelsFromCodes(codes);
  seg16.convertTo(c.segmentation, CV_32S);

  const cv::Mat rmap = readImage(plan.map, cv::IMREAD_GRAYSCALE);
  c.reference_codes = readImage(plan.labels, cv::IMREAD_GRAYSCALE);
  c.reference_rooms = groundTruthRooms(readImage(plan.segmentation, cv::IMREAD_UNCHANGED));
  if (c.reference_codes.size() != rmap.size() || c.reference_rooms.size() != rmap.size())
    throw InputError(plan.labels, "reference map, labels and segmentation differ in size");
  const cv::Mat ref_free = rmap > 250;

  if (plan.same_frame) {
    if (rmap.size() != c.map_free.size())
      throw InputError(plan.map, "the reference plan is " + std::to_string(rmap.cols) + "x" +
                                     std::to_string(rmap.rows) + " but the map " + map + " is " +
                                     std::to_string(c.map_free.cols) + "x" + std::to_string(c.map_free.rows) +
                                     " (the same frame needs the same size)");
    c.score = scoreAligned(c.map_free, c.labels, c.segmentation, c.reference_codes, c.reference_rooms,
                           identityAlignment(c.map_free, ref_free), 100);
  } else {
    c.score = scoreAgainstReference(c.map_free, c.labels, c.segmentation, ref_free, c.reference_codes,
                                    c.reference_rooms, 100, plan.map);
  }
  // The graph as gridtopo-topology built it from labels.png (the same INI is needed: checked on topology.json).
  c.graph = compareGraphWithPlan(c.map_free, c.labels, m.resolution, opt, ref_free, c.reference_codes,
                                 c.reference_rooms, c.score.alignment);
  c.segmentation_of_plan_labels =
      scoreAligned(c.map_free, c.graph.plan_labels_labels, c.graph.plan_labels_segmentation, c.reference_codes,
                   c.reference_rooms, c.score.alignment)
          .segmentation;
  c.region_vote_oracle_accuracy = regionVoteOracleAccuracy(c);
  if (!trajectory.empty()) {
    std::vector<cv::Point2d> world;
    for (const TimedPose& p : io::readTrajectory(trajectory)) world.emplace_back(p.pose.x, p.pose.y);
    if (world.empty()) throw InputError(trajectory, "the trajectory has no pose");
    c.along_path = scoreGraphAlongPath(c.graph.graph, c.graph.regions, c.graph.plan,
                                       topology::pathInCells(world, m.origin, m.resolution, c.map_free.rows),
                                       m.resolution);
  }
  if (std::filesystem::is_regular_file(dir + "/topology.json")) {
    const auto written = topology::graphFromJson(dir + "/topology.json");
    const auto& g = c.graph.graph;
    if (written.nodes.size() != g.nodes.size() || written.edges.size() != g.edges.size())
      throw InputError(dir + "/topology.json", 0, "nodes",
                       std::to_string(written.nodes.size()) + " nodes, " + std::to_string(written.edges.size()) +
                           " edges, but labels.png with this INI gives " + std::to_string(g.nodes.size()) + " and " +
                           std::to_string(g.edges.size()) + ": use the INI gridtopo-topology ran with");
  }
  return c;
}

std::string comparisonJson(const TopologyComparison& c) {
  const auto& s = c.score;
  const auto& a = s.alignment;
  std::ostringstream js;
  js << std::setprecision(6) << "{\n  \"format\": \"gridtopo-topology-compare\",\n  \"map\": \"" << c.map
     << "\",\n  \"alignment\": {\"correlation\": " << a.correlation << ", \"start\": " << a.start
     << ", \"map_to_reference\": [" << a.map_to_reference(0, 0) << ", " << a.map_to_reference(0, 1) << ", "
     << a.map_to_reference(0, 2) << ", " << a.map_to_reference(1, 0) << ", " << a.map_to_reference(1, 1) << ", "
     << a.map_to_reference(1, 2) << "]},\n  \"cell_accuracy\": " << s.labels.accuracy()
     << ",\n  \"labels\": " << s.labels.toJson(2) << ",\n  \"segmentation\": " << s.segmentation.toJson()
     << ",\n  \"graph\": " << c.graph.score.toJson() << ",\n  \"graph_of_plan_labels\": "
     << c.graph.plan_labels.toJson() << ",\n  \"segmentation_of_plan_labels\": "
     << c.segmentation_of_plan_labels.toJson() << ",\n  \"region_vote_oracle_accuracy\": "
     << c.region_vote_oracle_accuracy << ",\n  \"trajectory\": " << c.along_path.toJson() << "\n}\n";
  return js.str();
}

std::string comparisonSummary(const TopologyComparison& c) {
  const auto& s = c.score;
  const auto &gs = c.graph.score, &ceiling = c.graph.plan_labels;
  std::ostringstream o;
  o << "alignment correlation " << std::setprecision(3) << s.alignment.correlation << "; cell accuracy "
    << percent(s.labels.accuracy()) << " % (room / corridor / doorway recall " << percent(s.labels.recall(0))
    << " / " << percent(s.labels.recall(1)) << " / " << percent(s.labels.recall(2)) << " %); segmentation: "
    << s.segmentation.segments << " segments, " << s.segmentation.rooms << " rooms, recall "
    << percent(s.segmentation.recall) << " %, precision " << percent(s.segmentation.precision)
    << " % (with the plan's labels: " << percent(c.segmentation_of_plan_labels.recall) << " / "
    << percent(c.segmentation_of_plan_labels.precision) << " %); graph: "
    << gs.attached << " of " << gs.plan_rooms << " plan rooms one room node attached through a doorway ("
    << percent(gs.attachedFraction()) << " %), " << gs.loops_closed << " of " << gs.plan_loops
    << " plan corridor loops a cycle of corridor nodes (with the plan's labels: "
    << percent(ceiling.attachedFraction()) << " %, " << ceiling.loops_closed << " of " << ceiling.plan_loops << ")";
  if (const auto& t = c.along_path; t.has_trajectory)
    o << "; trajectory: " << t.doors_found << " of " << t.doors_crossed
      << " plan doors crossed are doorway nodes between the right spaces (" << percent(t.doorsFoundFraction())
      << " %; a doorway node at " << t.doors_with_doorway_node << "), " << t.spurious_splits << " of "
      << t.node_changes_scored << " node changes where the plan has none (" << t.spurious_label_changes
      << " room / corridor; " << t.spurious_boundaries << " boundaries)";
  return o.str();
}

cv::Mat comparisonOverlay(const TopologyComparison& c) {
  cv::Mat img = topology::colourSegmentation(c.segmentation);
  const cv::Mat r = warpReferenceToMap(c.reference_rooms, c.score.alignment, c.map_free.size());
  for (int y = 1; y < r.rows; ++y)
    for (int x = 1; x < r.cols; ++x)
      if (r.at<int>(y, x) != r.at<int>(y - 1, x) || r.at<int>(y, x) != r.at<int>(y, x - 1))
        img.at<cv::Vec3b>(y, x) = cv::Vec3b(0, 0, 255);
  return img;
}

cv::Mat comparisonLabelErrors(const TopologyComparison& c) {
  const cv::Mat truth = warpReferenceToMap(c.reference_codes, c.score.alignment, c.map_free.size());
  return labelErrorOverlay(c.occ, truth, c.labels);
}

}  // namespace gridtopo::eval
