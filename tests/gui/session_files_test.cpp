#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "gridtopo/core/error.h"
#include "gridtopo/session/recent_files.h"
#include "gridtopo/session/session.h"
#include "test_helpers.h"

using namespace gridtopo;
using session::FileKind;

namespace {
void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
const std::string kLabIntel = GRIDTOPO_DATA_DIR "/places/maps/lab_intel.png";
}  // namespace

TEST(FileKinds, ByNameAndContent) {
  guitest::TempDir tmp;
  EXPECT_EQ(session::classifyFile("a/intel.clf.gz"), FileKind::Log);
  EXPECT_EQ(session::classifyFile("a/x.LOG"), FileKind::Log);
  EXPECT_EQ(session::classifyFile("a/x.rawlog"), FileKind::Log);
  EXPECT_EQ(session::classifyFile("a/intel.relations.gz"), FileKind::Relations);
  EXPECT_EQ(session::classifyFile("a/map.gridmap.gz"), FileKind::Map);
  EXPECT_EQ(session::classifyFile("a/map.png"), FileKind::Map);
  EXPECT_EQ(session::classifyFile("a/topology.graphml"), FileKind::Topology);
  EXPECT_EQ(session::classifyFile("a/trajectory.txt"), FileKind::Trajectory);
  write(tmp / "map.yaml", "image: map.pgm\nresolution: 0.05\n");
  write(tmp / "model.yml", "%YAML:1.0\n---\nformat: gridtopo-places-model\n");
  write(tmp / "slam.ini", "# c\n[slam]\nparticles = 3\n");
  write(tmp / "topo.ini", "[topology]\nthreads = 1\n");
  EXPECT_EQ(session::classifyFile(tmp / "map.yaml"), FileKind::Map);
  EXPECT_EQ(session::classifyFile(tmp / "model.yml"), FileKind::Model);
  EXPECT_EQ(session::classifyFile(tmp / "slam.ini"), FileKind::SlamIni);
  EXPECT_EQ(session::classifyFile(tmp / "topo.ini"), FileKind::TopologyIni);
  EXPECT_EQ(session::classifyFile("a/b.xyz"), FileKind::Unknown);
  EXPECT_TRUE(session::mapNeedsResolution(kLabIntel));
  cv::imwrite(tmp / "map.pgm", cv::Mat(4, 4, CV_8U, cv::Scalar(255)));
  EXPECT_FALSE(session::mapNeedsResolution(tmp / "map.pgm"));  // has map.yaml beside it
}

TEST(SessionFiles, OpensAPlainImageMapWithTheGivenResolution) {
  session::Session s;
  io::MapReadOptions o;
  o.resolution = 0.1;
  EXPECT_EQ(s.open(kLabIntel, o), FileKind::Map);
  const cv::Mat img = cv::imread(kLabIntel, cv::IMREAD_GRAYSCALE);
  EXPECT_EQ(s.map().cols(), img.cols);
  EXPECT_EQ(s.map().rows(), img.rows);
  EXPECT_NEAR(s.map().resolution, 0.1, 1e-6);  // MRPT stores it as a float
  // Pixel-aligned with the image: a free pixel is free and a black one occupied.
  int free_r = -1, free_c = -1, occ_r = -1, occ_c = -1;
  for (int r = 0; r < img.rows && (free_r < 0 || occ_r < 0); ++r)
    for (int c = 0; c < img.cols; ++c) {
      if (img.at<unsigned char>(r, c) == 255 && free_r < 0) free_r = r, free_c = c;
      if (img.at<unsigned char>(r, c) == 0 && occ_r < 0) occ_r = r, occ_c = c;
    }
  EXPECT_LT(s.map().occupancy(free_r, free_c), 0.02);
  EXPECT_GT(s.map().occupancy(occ_r, occ_c), 0.98);
  // World <-> cell round trip.
  const cv::Point2d w = s.map().cellCentre(free_r, free_c);
  int r, c;
  ASSERT_TRUE(s.map().worldToCell(w.x, w.y, r, c));
  EXPECT_EQ(r, free_r);
  EXPECT_EQ(c, free_c);
}

TEST(SessionFiles, BadFilesLeaveTheSessionUntouchedAndNameFileAndLine) {
  guitest::TempDir tmp;
  session::Session s;
  s.openMap(kLabIntel);
  s.openTrajectory([&] {
    write(tmp / "good.txt", "0 0 0 0\n1 1 0 0\n");
    return tmp / "good.txt";
  }());
  const cv::Mat map_before = s.map().grey.clone();

  // A CARMEN log with a malformed third line.
  write(tmp / "bad.clf",
        "# a comment line\n"
        "ODOM 0.0 0.0 0.0 0 0 0 1.0 host 1.0\n"
        "FLASER 3 1.0 1.0 x 0 0 0 0 0 0 2.0 host 2.0\n");
  try {
    s.open(tmp / "bad.clf");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.clf:3"), std::string::npos) << e.what();
  }
  write(tmp / "bad.txt", "0 0 0 0\n1 1 nan? 0\n");
  try {
    s.open(tmp / "bad.txt");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.txt:2"), std::string::npos) << e.what();
  }
  write(tmp / "bad.ini", "[slam]\nparticles = 0\n");
  const int particles = s.slamOptions().particles;
  try {
    s.open(tmp / "bad.ini");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("particles"), std::string::npos) << e.what();
  }
  write(tmp / "broken.png", "not a png at all");
  EXPECT_THROW(s.open(tmp / "broken.png"), InputError);
  write(tmp / "broken.graphml", "<graphml>\n<node id=\"n1\"><data key=\"label\">room</data><data key=\"area_m2\">x</data></node>\n");
  try {
    s.open(tmp / "broken.graphml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.graphml:2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(s.open(tmp / "missing.clf"), InputError);
  EXPECT_THROW(s.open(tmp / "what.xyz"), InputError);

  EXPECT_FALSE(s.hasLog());
  EXPECT_EQ(s.trajectories().size(), 1u);
  EXPECT_EQ(s.slamOptions().particles, particles);
  EXPECT_EQ(cv::countNonZero(s.map().grey != map_before), 0);
}

TEST(SessionFiles, SlamOptionTableEditsGoThroughTheOptionStruct) {
  session::Session s;
  auto t = s.slamOptionTable();
  const auto* p = t.find("slam", "particles");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->type, session::OptionEntry::Type::Int);
  EXPECT_EQ(p->value, "30");
  EXPECT_EQ(p->default_value, "30");
  // Help and range from the key table (slam::slamOptionSchema), no INI file read.
  EXPECT_EQ(p->help, "number of particles");
  EXPECT_EQ(p->range, "[1, 100000]");
  EXPECT_EQ(t.find("slam", "linear_update")->unit, "m");
  EXPECT_EQ(t.find("slam", "proposal")->type, session::OptionEntry::Type::Choice);
  EXPECT_EQ(t.find("slam", "proposal")->words,
            (std::vector<std::string>{"informed", "mode-only", "hahnel", "odometry"}));
  EXPECT_EQ(t.entries().size(), slam::slamOptionSchema().keys().size() + slam::loopClosureOptionSchema().keys().size());
  for (const auto& e : t.entries()) EXPECT_FALSE(e.help.empty()) << e.key << " has no help in its key table";
  ASSERT_TRUE(t.set("slam", "particles", "12"));
  ASSERT_TRUE(t.set("slam", "proposal", "odometry"));
  s.setSlamOptions(t);
  EXPECT_EQ(s.slamOptions().particles, 12);
  EXPECT_EQ(s.slamOptions().proposal.type, slam::ProposalType::Odometry);
  // A bad value is refused with the key's name and changes nothing.
  t.set("slam", "particles", "-3");
  try {
    s.setSlamOptions(t);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("particles"), std::string::npos);
  }
  EXPECT_EQ(s.slamOptions().particles, 12);
  // Saved as INI and loaded like the CLI loads it.
  guitest::TempDir tmp;
  t.set("slam", "particles", "12");
  { std::ofstream(tmp / "saved.ini") << t.toIni(); }
  session::Session s2;
  s2.openSlamIni(tmp / "saved.ini");
  EXPECT_EQ(s2.slamOptions().particles, 12);
  EXPECT_EQ(s2.slamOptions().proposal.type, slam::ProposalType::Odometry);
}

TEST(RecentFiles, MostRecentFirstWithoutDuplicatesAndPersisted) {
  guitest::TempDir tmp;
  session::RecentFiles r(3);
  r.add("/a");
  r.add("/b");
  r.add("/a");
  r.add("/c");
  r.add("/d");
  ASSERT_EQ(r.paths(), (std::vector<std::string>{"/d", "/c", "/a"}));
  r.save(tmp / "cfg/recent");
  session::RecentFiles q(3);
  q.load(tmp / "cfg/recent");
  EXPECT_EQ(q.paths(), r.paths());
  q.load(tmp / "none");
  EXPECT_TRUE(q.paths().empty());
}

// The topology tools start with the shipped place model (datasets/models/places_model.yml), found through
// GRIDTOPO_DATA_DIR, beside the executable, or the build-time data dir as the last resort; the session says which
// model is loaded.
TEST(SessionFiles, OpensTheShippedPlaceModelByDefault) {
  const std::string shipped = GRIDTOPO_DATA_DIR "/models/places_model.yml";
  guitest::TempDir tmp;
  unsetenv("GRIDTOPO_DATA_DIR");
  {
    session::Session s;
    EXPECT_FALSE(s.model());
    EXPECT_EQ(s.modelDescription(), "no place model");
    // Nothing beside the test binary: the build-time data dir.
    EXPECT_EQ(s.openDefaultModel(GRIDTOPO_DATA_DIR), shipped);
    ASSERT_TRUE(s.model());
    EXPECT_EQ(s.modelPath(), shipped);
    EXPECT_EQ(s.modelDescription(), "place model: " + shipped + " (default)");
    // A model the user opens replaces it and is shown as such.
    guitest::handMadeModel().save(tmp / "mine.yml");
    s.openModel(tmp / "mine.yml");
    EXPECT_EQ(s.modelDescription(), "place model: " + (tmp / "mine.yml"));
  }
  {
    // The environment variable comes first.
    std::filesystem::create_directories(tmp / "data/models");
    guitest::handMadeModel().save(tmp / "data/models/places_model.yml");
    setenv("GRIDTOPO_DATA_DIR", (tmp / "data").c_str(), 1);
    session::Session s;
    EXPECT_EQ(s.openDefaultModel(GRIDTOPO_DATA_DIR), tmp / "data/models/places_model.yml");
    ASSERT_TRUE(s.model());
    EXPECT_EQ(s.model()->notes, "hand-made test model");
    EXPECT_EQ(s.modelPath(), tmp / "data/models/places_model.yml");
  }
  {
    // No model anywhere: none is loaded, and nothing else changes.
    setenv("GRIDTOPO_DATA_DIR", (tmp / "nothing").c_str(), 1);
    session::Session s;
    EXPECT_EQ(s.openDefaultModel(tmp / "nothing either"), "");
    EXPECT_FALSE(s.model());
    EXPECT_EQ(s.modelPath(), "");
  }
  unsetenv("GRIDTOPO_DATA_DIR");
}

// The reader's warnings about an opened log are kept for the GUI to show (it puts them in the status bar).
TEST(SessionFiles, KeepsTheReadersWarningsAboutALog) {
  guitest::TempDir tmp;
  std::string log = "PARAM laser_front_laser_fov 3.14159 nohost 0\n";
  for (int i = 0; i < 3; ++i) {
    log += "FLASER 181";
    for (int k = 0; k < 181; ++k) log += " 3.0";
    log += " 0 0 0 0 0 0 " + std::to_string(100 + i) + " nohost " + std::to_string(100 + i) + "\n";
  }
  write(tmp / "fov.clf", log);
  session::Session s;
  ASSERT_EQ(s.open(tmp / "fov.clf"), FileKind::Log);
  ASSERT_EQ(s.logWarnings().size(), 1u);
  EXPECT_NE(s.logWarnings()[0].find("laser_front_laser_fov 3.14159 read as radians"), std::string::npos);
  s.open(GRIDTOPO_DATA_DIR "/slam/intel.clf.gz");
  EXPECT_TRUE(s.logWarnings().empty());  // a log the reader takes at its word
}

TEST(SessionFiles, TopologyOptionTableEditsGoThroughTheOptionStruct) {
  session::Session s;
  auto t = s.topologyOptionTable();
  // The three sections of a topology run, every key of their tables.
  std::size_t keys = 0;
  for (const char* section : {"topology", "relaxation", "correction"}) {
    std::size_t n = 0;
    for (const auto& e : t.entries()) n += e.section == section;
    EXPECT_GT(n, 0u) << section;
    keys += n;
  }
  EXPECT_EQ(keys, t.entries().size());
  EXPECT_EQ(t.find("topology", "segmentation")->type, session::OptionEntry::Type::Choice);
  EXPECT_EQ(t.find("topology", "threads")->range, "[1, 256]");
  EXPECT_EQ(t.find("relaxation", "max_iterations")->value, "30");
  EXPECT_EQ(t.find("correction", "enabled")->type, session::OptionEntry::Type::Bool);
  ASSERT_TRUE(t.set("topology", "segmentation", "doorways"));
  ASSERT_TRUE(t.set("relaxation", "max_iterations", "7"));
  ASSERT_TRUE(t.set("correction", "min_room_area", "2.5"));
  s.setTopologyOptions(t);
  EXPECT_EQ(s.topologyOptions().segmentation, "doorways");
  EXPECT_EQ(s.topologyOptions().relaxation.max_iterations, 7);
  EXPECT_EQ(s.topologyOptions().correction.min_room_area, 2.5);
  EXPECT_EQ(s.topologyOptionTable().find("correction", "min_room_area")->value, "2.5");
  // A value out of range is refused with its section and key, and changes nothing.
  t.set("relaxation", "max_iterations", "-1");
  try {
    s.setTopologyOptions(t);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "[relaxation] max_iterations");
  }
  EXPECT_EQ(s.topologyOptions().relaxation.max_iterations, 7);
  // The table's INI is what gridtopo-topology -c loads.
  t.set("relaxation", "max_iterations", "7");
  guitest::TempDir tmp;
  { std::ofstream(tmp / "topology.ini") << t.toIni(); }
  const auto loaded = topology::loadTopologyOptions(tmp / "topology.ini");
  EXPECT_EQ(topology::topologyOptionsIni(loaded), topology::topologyOptionsIni(s.topologyOptions()));
}

// The loop closure's section is in the grid: an INI that turns it on keeps it on through the grid's edits (the
// GUI applies the grid before every run), and it can be turned on from the grid.
TEST(SessionFiles, SlamOptionTableKeepsTheLoopClosureSection) {
  guitest::TempDir tmp;
  { std::ofstream(tmp / "lc.ini") << "[slam]\nparticles = 9\n[loop_closure]\nenabled = true\nsubmap_nodes = 15\n"; }
  session::Session s;
  s.openSlamIni(tmp / "lc.ini");
  ASSERT_TRUE(s.slamOptions().loop_closure.enabled);
  auto t = s.slamOptionTable();
  ASSERT_NE(t.find("loop_closure", "enabled"), nullptr);
  EXPECT_EQ(t.find("loop_closure", "enabled")->type, session::OptionEntry::Type::Bool);
  EXPECT_EQ(t.find("loop_closure", "submap_nodes")->value, "15");
  s.setSlamOptions(t);
  EXPECT_TRUE(s.slamOptions().loop_closure.enabled);
  EXPECT_EQ(s.slamOptions().loop_closure.submap_nodes, 15);
  EXPECT_EQ(s.slamOptions().particles, 9);
  t.set("loop_closure", "enabled", "false");
  s.setSlamOptions(t);
  EXPECT_FALSE(s.slamOptions().loop_closure.enabled);
  // Saved from the grid and loaded back like the CLI loads it.
  t.set("loop_closure", "enabled", "true");
  { std::ofstream(tmp / "saved.ini") << t.toIni(); }
  session::Session s2;
  s2.openSlamIni(tmp / "saved.ini");
  EXPECT_TRUE(s2.slamOptions().loop_closure.enabled);
  EXPECT_EQ(s2.slamOptions().loop_closure.submap_nodes, 15);
}

// The GUI reads option INIs as strictly as the apps' -c (issue 36): a typo in a key or a section is refused with
// the file, the line and a "did you mean", a binary file is refused, and the session keeps its options.
TEST(SessionFiles, OptionIniTyposAreRefusedWithFileLineAndDidYouMean) {
  guitest::TempDir tmp;
  session::Session s;
  const int particles = s.slamOptions().particles;
  const std::string threads = s.topologyOptionTable().find("topology", "threads")->value;
  const auto error = [&](const std::string& name, const std::string& text, bool topology) {
    const std::string path = tmp / name;
    write(path, text);
    try {
      if (topology)
        s.openTopologyIni(path);
      else
        s.open(path);
      ADD_FAILURE() << "no error for " << name;
    } catch (const InputError& e) {
      const std::string w = e.what();
      EXPECT_EQ(w.rfind(path, 0), 0u) << w;
      return w.substr(path.size());
    }
    return std::string();
  };
  EXPECT_EQ(error("typo.ini", "[slam]\nparticlez = 30\n", false),
            ":2: [slam] particlez: unknown key (did you mean 'particles'? not an option of the filter; see "
            "config-ini/slam.ini)");
  EXPECT_EQ(error("section.ini", "[slam]\nparticles = 30\n[loop_closre]\nenabled = true\n", false),
            ":3: [loop_closre]: unknown section (did you mean [loop_closure]? this app reads slam, loop_closure)");
  EXPECT_EQ(error("ttypo.ini", "[topology]\nthreadz = 2\n", true),
            ":2: [topology] threadz: unknown key (did you mean 'threads'? not an option of this section; see "
            "config-ini/topology.ini)");
  EXPECT_EQ(error("nosection.ini", "[relaxation]\nmax_iterations = 3\n", true), ": [topology]: section not found");
  EXPECT_EQ(error("binary.ini", std::string("[topology]\n\x01\x02", 13), true),
            ": not a text INI file (byte 11 is 0x01)");
  EXPECT_EQ(s.slamOptions().particles, particles);
  EXPECT_EQ(s.topologyOptionTable().find("topology", "threads")->value, threads);
  // A correct file still opens.
  write(tmp / "good.ini", "[slam]\nparticles = 30\n");
  s.open(tmp / "good.ini");
  EXPECT_EQ(s.slamOptions().particles, 30);
}
