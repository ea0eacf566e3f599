#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "gridtopo/core/error.h"
#include "gridtopo/places/features.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/occupancy.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/session/session.h"
#include "gridtopo/session/topology_state.h"
#include "gridtopo/topology/export.h"
#include "test_helpers.h"

using namespace gridtopo;

namespace {
struct Fixture {
  guitest::TempDir tmp;
  session::Session s;
  Fixture() {
    cv::imwrite(tmp / "plan.png", guitest::floorPlan());
    guitest::handMadeModel().save(tmp / "model.yml");
    s.openMap(tmp / "plan.png");
    s.openModel(tmp / "model.yml");
    s.runTopology();
  }
};
}  // namespace

TEST(TopologyState, SameLabelsAndGraphAsTheLibraryPipeline) {
  Fixture f;
  const auto* t = f.s.topology();
  ASSERT_NE(t, nullptr);
  // What gridtopo-topology computes: labelPlaces + buildTopology.
  const auto model = guitest::handMadeModel();
  const topology::TopologyOptions opt;
  const auto occ = places::occupancyFromGrey(guitest::floorPlan(), 0.05);
  const auto lab = places::labelPlaces(occ, model, opt.relaxation, opt.threads);
  const auto topo = topology::buildTopology(lab.labels, 0.05, opt, &lab);
  EXPECT_EQ(cv::countNonZero(t->labelling.labels_initial != lab.labels_initial), 0);
  EXPECT_EQ(cv::countNonZero(t->labelling.labels != lab.labels), 0);
  EXPECT_EQ(cv::countNonZero(t->topo.labels != topo.labels), 0);
  EXPECT_EQ(t->topo.graph.nodes.size(), topo.graph.nodes.size());
  EXPECT_EQ(t->topo.graph.edges.size(), topo.graph.edges.size());
  // The floor plan: 2 rooms, 1 corridor, 2 doorways; each door joins its room to the corridor.
  int counts[3] = {0, 0, 0};
  for (const auto& n : t->topo.graph.nodes) counts[n.label]++;
  EXPECT_EQ(counts[0], 2);
  EXPECT_EQ(counts[1], 1);
  EXPECT_EQ(counts[2], 2);
}

TEST(TopologyState, CellInspectionExplainsTheLabel) {
  Fixture f;
  const auto* t = f.s.topology();
  // Middle of room A (row 40, col 50), middle of the corridor (row 92, col 120), middle of door A (row 75, col 50).
  const auto room = session::inspectCell(*t, 40, 50);
  EXPECT_TRUE(room.free);
  ASSERT_TRUE(room.has_sample);
  EXPECT_EQ(room.label_corrected, 0);
  EXPECT_EQ(room.label_relaxed, 0);
  EXPECT_GT(room.p_relaxed[0], 0.5f);
  // The probabilities are the lattice block's, and the features those of the block's scan.
  ASSERT_EQ(room.features.size(), places::numFeatures());
  std::vector<float> beams(room.scan_world.size());
  const cv::Point2d o = t->map.cellCentre(room.sample_cell.y, room.sample_cell.x);
  for (std::size_t k = 0; k < beams.size(); ++k)
    beams[k] = static_cast<float>(std::hypot(room.scan_world[k].x - o.x, room.scan_world[k].y - o.y));
  std::vector<float> feats(places::numFeatures());
  places::extractFeatures(beams.data(), static_cast<int>(beams.size()), t->model->features, feats.data());
  for (std::size_t i = 0; i < feats.size(); ++i) EXPECT_NEAR(feats[i], room.features[i], 1e-3f + 1e-4f * std::abs(feats[i])) << i;
  // The simulated scan stays in the 4 m x 3 m room (corners 2.5 m away) except through the door below, whose
  // beams end on the corridor's far wall (3.3 m).
  float longest = 0;
  int beyond_room = 0;
  for (float b : beams) longest = std::max(longest, b), beyond_room += b > 2.6f;
  EXPECT_GT(longest, 3.0f);
  EXPECT_LT(longest, 3.5f);
  EXPECT_GT(beyond_room, 3);
  EXPECT_LT(beyond_room, 30);
  const std::string text = room.text();
  EXPECT_NE(text.find("label: room"), std::string::npos) << text;
  EXPECT_NE(text.find("min_chord"), std::string::npos);
  EXPECT_NE(text.find("[m]"), std::string::npos);

  const auto corridor = session::inspectCell(*t, 92, 120);
  EXPECT_EQ(corridor.label_corrected, 1);
  const auto door = session::inspectCell(*t, 75, 50);
  EXPECT_EQ(door.label_corrected, 2);
  const auto wall = session::inspectCell(*t, 8, 50);
  EXPECT_FALSE(wall.free);
  EXPECT_FALSE(wall.has_sample);
  EXPECT_EQ(wall.label_corrected, -1);
  EXPECT_THROW(session::inspectCell(*t, -1, 0), std::out_of_range);
}

TEST(TopologyState, NodeSelectionShowsRegionAndNeighbours) {
  Fixture f;
  const auto* t = f.s.topology();
  const topology::GraphNode* corridor = nullptr;
  for (const auto& n : t->topo.graph.nodes)
    if (n.label == 1) corridor = &n;
  ASSERT_NE(corridor, nullptr);
  const cv::Point2d w = session::nodeWorld(*t, *corridor);
  const auto& sel = f.s.select(session::ViewMode::Topology, w.x + 0.05, w.y, 0.3);
  ASSERT_EQ(sel.kind, session::Selection::Kind::Node);
  EXPECT_EQ(sel.node->id, corridor->id);
  EXPECT_EQ(sel.node->neighbours.size(), 2u);  // the two doorways
  EXPECT_NEAR(sel.node->area_m2, corridor->area_m2, 1e-9);
  EXPECT_NE(sel.text.find("corridor"), std::string::npos);
  // Away from nodes: the cell under the click.
  const cv::Point2d c = t->map.cellCentre(40, 20);
  const auto& cell = f.s.select(session::ViewMode::Topology, c.x, c.y, 0.3);
  ASSERT_EQ(cell.kind, session::Selection::Kind::Cell);
  EXPECT_EQ(cell.cell->row, 40);
  EXPECT_EQ(cell.cell->col, 20);
}

TEST(TopologyState, SavedOutputsLoadBackAsJsonAndGraphML) {
  Fixture f;
  const auto* t = f.s.topology();
  topology::TopologyOptions options = f.s.topologyOptions();
  options.correction.min_room_area = 1.0 / 3.0;  // a value that six digits do not keep
  session::saveTopologyOutputs(*t, f.tmp / "out", options);
  for (const char* n : {"topology.graphml", "topology.json", "topology.dot", "topology_posegraph.graph", "overlay.png",
                        "labels.png", "labels_before_correction.png", "segmentation.png", "segmentation_colour.png",
                        "options.ini"})
    EXPECT_TRUE(std::filesystem::is_regular_file(f.tmp / ("out/" + std::string(n)))) << n;
  // options.ini is the loadable INI of the options (gridtopo-topology -c reads it back to the same options).
  const topology::TopologyOptions loaded = topology::loadTopologyOptions(f.tmp / "out/options.ini");
  EXPECT_EQ(loaded.correction.min_room_area, 1.0 / 3.0);
  EXPECT_EQ(topology::topologyOptionsIni(loaded), topology::topologyOptionsIni(options));
  const cv::Mat codes = cv::imread(f.tmp / "out/labels.png", cv::IMREAD_GRAYSCALE);
  EXPECT_EQ(cv::countNonZero(codes != places::labelsToCodes(t->topo.labels)), 0);
  for (const char* g : {"out/topology.json", "out/topology.graphml"}) {
    session::Session s;
    s.openMap(f.tmp / "plan.png");
    s.openTopology(f.tmp / g);
    ASSERT_NE(s.topology(), nullptr);
    EXPECT_FALSE(s.topology()->has_labelling);
    EXPECT_EQ(s.topology()->topo.graph.nodes.size(), t->topo.graph.nodes.size()) << g;
    EXPECT_EQ(s.topology()->topo.graph.edges.size(), t->topo.graph.edges.size()) << g;
    for (std::size_t i = 0; i < t->topo.graph.nodes.size(); ++i) {
      EXPECT_EQ(s.topology()->topo.graph.nodes[i].label, t->topo.graph.nodes[i].label);
      EXPECT_NEAR(s.topology()->topo.graph.nodes[i].area_m2, t->topo.graph.nodes[i].area_m2, 1e-6);  // 9 digits
      EXPECT_EQ(s.topology()->topo.graph.nodes[i].anchor_px, t->topo.graph.nodes[i].anchor_px) << g;
    }
    for (std::size_t i = 0; i < t->topo.graph.edges.size(); ++i) {  // the routed paths come back from both files
      EXPECT_GE(t->topo.graph.edges[i].path_px.size(), 2u);
      EXPECT_EQ(s.topology()->topo.graph.edges[i].path_px, t->topo.graph.edges[i].path_px) << g;
    }
    EXPECT_EQ(cv::countNonZero(s.topology()->topo.labels != t->topo.labels), 0) << g;
    // Inspecting a loaded output: the label is known, the probabilities are not.
    const auto ci = session::inspectCell(*s.topology(), 40, 50);
    EXPECT_EQ(ci.label_corrected, 0);
    EXPECT_FALSE(ci.has_sample);
  }
  // A probabilistic grid (a SLAM map: free cells at p_free 0.9, grey 230) keeps its free space when an output is
  // loaded on it: the free threshold of its kind (204), not the plain images' 250 (which left no free cell).
  {
    session::MapLayer grid = t->map;
    grid.kind = MapKind::ProbabilisticGrid;
    grid.grey = t->map.grey.clone();
    grid.grey.setTo(cv::Scalar(230), grid.grey >= 250);
    const auto loaded = session::loadTopologyOutput(f.tmp / "out/topology.json", grid, f.s.topologyOptions());
    topology::TopologyOptions o = f.s.topologyOptions();
    o.grid_free_threshold = 204;
    const auto direct = topology::occupancyForTopology(grid.image(), o);
    EXPECT_GT(places::countFree(loaded.occ), 1000u);
    EXPECT_EQ(places::countFree(loaded.occ), places::countFree(direct));
  }
  // Without the map it was computed on, labels cannot be aligned: a clear error, nothing changes.
  session::Session s;
  EXPECT_THROW(s.openTopology(f.tmp / "out/topology.json"), InputError);
  EXPECT_EQ(s.topology(), nullptr);
}

TEST(TopologyState, RenderShowsLabelsGraphAndInspectedScan) {
  Fixture f;
  session::ViewTransform v;
  double x0, y0, x1, y1;
  ASSERT_TRUE(f.s.bounds(session::ViewMode::Topology, x0, y0, x1, y1));
  v.fit(x0, y0, x1, y1, 400, 240);
  cv::Mat screen(240, 400, CV_8UC3);
  session::Layers layers;
  f.s.render(screen, session::ViewMode::Topology, v, layers);
  // Room colour (blue dominant) in room A's middle, corridor colour (green dominant) in the corridor.
  auto at = [&](int row, int col) {
    const cv::Point2d w = f.s.topology()->map.cellCentre(row, col);
    const cv::Point2d p = v.toScreen(w.x, w.y);
    return screen.at<cv::Vec3b>(static_cast<int>(p.y), static_cast<int>(p.x));
  };
  const cv::Vec3b room = at(30, 30), corr = at(85, 100);
  EXPECT_GT(room[0], room[1] + 30);
  EXPECT_GT(corr[1], corr[0] + 30);
  // Stage toggle: before relaxation the overlay is computed from the other label set (may be identical here);
  // without labels the map is grey.
  layers.labels = false;
  f.s.render(screen, session::ViewMode::Topology, v, layers);
  const cv::Vec3b grey = at(30, 30);
  EXPECT_EQ(grey[0], grey[1]);
  EXPECT_EQ(grey[1], grey[2]);
}
