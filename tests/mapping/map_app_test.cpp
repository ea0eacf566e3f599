// End-to-end: gridtopo-map on a short Intel slice (log -> SLAM -> topology through the two builders), its outputs
// against gridtopo-slam's and gridtopo-topology's, its RUN.ini, and its errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "common/run_app.h"
#include "common/same_outputs.h"

namespace fs = std::filesystem;
using gridtopo::testing_app::runApp;
using gridtopo::testing_outputs::slurp;
using gridtopo::testing_outputs::withoutLine;

namespace {
const std::string kData = GRIDTOPO_DATA_DIR;
const std::string kLog = kData + "/slam/intel.clf.gz";
const std::string kModel = kData + "/models/places_model.yml";

fs::path fresh(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("gridtopo_map_app_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }
}  // namespace

TEST(MapApp, IntelSliceMatchesGridtopoSlamAndGridtopoTopology) {
  const fs::path d = fresh("intel");
  const std::string out = (d / "out").string();
  const auto r = runApp("gridtopo-map", "-i " + kLog + " -o " + out + " -m " + kModel + " -p 8 -s 1 -t 2 --max-scans 1500 -q");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("1500 scans, 275 processed, 1 topology updates"), std::string::npos) << r.output;
  for (const char* f : {"options.ini", "slam/map.png", "slam/map_trajectory.png", "slam/map.pgm", "slam/map.yaml",
                        "slam/map.gridmap.gz", "slam/map.simplemap", "slam/trajectory.txt", "slam/stats.txt",
                        "slam/options.ini", "topology/topology.graphml", "topology/topology.json",
                        "topology/topology.dot", "topology/topology_posegraph.graph", "topology/overlay.png",
                        "topology/labels.png", "topology/labels_before_correction.png", "topology/segmentation.png",
                        "topology/segmentation_colour.png", "topology/options.ini"})
    EXPECT_TRUE(fs::exists(d / "out" / f)) << f;

  // The SLAM map is gridtopo-slam's on the same slice.
  const auto slam = runApp("gridtopo-slam", "-i " + kLog + " -o " + (d / "slam").string() +
                                                " -p 8 -s 1 -t 2 --max-scans 1500 -q");
  ASSERT_EQ(slam.status, 0) << slam.output;
  for (const char* f : {"map.gridmap.gz", "map.pgm", "map.yaml", "map.png"})
    EXPECT_EQ(slurp(d / "out/slam" / f), slurp(d / "slam" / f)) << f;

  // The topology is gridtopo-topology's on the written map: its options.ini is that run's RUN.ini.
  const auto topo = runApp("gridtopo-topology", (d / "out/topology/options.ini").string() + " -o " +
                                                    (d / "topo").string() + " -q");
  ASSERT_EQ(topo.status, 0) << topo.output;
  EXPECT_NE(topo.output.find("5 rooms, 1 corridors, 8 doorways, 16 edges"), std::string::npos) << topo.output;
  for (const char* f : {"labels.png", "labels_before_correction.png", "topology.json", "topology.graphml",
                        "topology_posegraph.graph", "segmentation.png", "overlay.png"})
    EXPECT_EQ(slurp(d / "out/topology" / f), slurp(d / "topo" / f)) << f;
  EXPECT_EQ(withoutLine(slurp(d / "out/topology/options.ini"), "output"), withoutLine(slurp(d / "topo/options.ini"), "output"));
  fs::remove_all(d);
}

// With the loop closure on, the MRPT builder path (gridtopo-map) finds the same closures as gridtopo-slam and
// gives the same optimised trajectory and map, bit for bit: both read the scans in the geometry MRPT's
// observation holds (useMrptScanGeometry), and the closure search's discrete decisions see the same numbers.
TEST(MapApp, LoopClosureRunMatchesGridtopoSlam) {
  const fs::path d = fresh("lc");
  write(d / "run.ini", "[map_run]\ninput = " + kLog + "\noutput = " + (d / "out").string() + "\nmodel = " + kModel +
                           "\nmax_scans = 1500\n[slam]\nparticles = 8\nseed = 1\nthreads = 2\n"
                           "[loop_closure]\nenabled = true\n");
  const auto r = runApp("gridtopo-map", (d / "run.ini").string() + " -q");
  ASSERT_EQ(r.status, 0) << r.output;
  write(d / "slam.ini", "[slam]\n[loop_closure]\nenabled = true\n");
  const auto slam = runApp("gridtopo-slam", "-i " + kLog + " -c " + (d / "slam.ini").string() + " -o " +
                                                (d / "slam").string() + " -p 8 -s 1 -t 2 --max-scans 1500 -q");
  ASSERT_EQ(slam.status, 0) << slam.output;
  const std::string stats = slurp(d / "slam/stats.txt");
  EXPECT_NE(stats.find("closures 2 rejected 0"), std::string::npos) << stats;
  auto closureLines = [](const std::string& text) {
    std::string out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      if (line.rfind("# closure", 0) == 0 || line.rfind("# loop_closure:", 0) == 0) out += line + "\n";
    return out;
  };
  EXPECT_EQ(closureLines(slurp(d / "out/slam/stats.txt")), closureLines(stats));
  auto poses = [](const std::string& text) { return text.substr(text.find("\n# one pose")); };  // not the app's name
  EXPECT_EQ(poses(slurp(d / "out/slam/trajectory.txt")), poses(slurp(d / "slam/trajectory.txt")));
  for (const char* f : {"map.gridmap.gz", "map.pgm"}) EXPECT_EQ(slurp(d / "out/slam" / f), slurp(d / "slam" / f)) << f;
  fs::remove_all(d);
}

TEST(MapApp, RunIniAndItsOptionsIniReproduceTheRun) {
  const fs::path d = fresh("ini");
  write(d / "run.ini", "[map_run]\ninput = " + kLog + "\noutput = " + (d / "a").string() + "\nmodel = " + kModel +
                           "\nmax_scans = 600\n[slam]\nparticles = 4\nseed = 3\nthreads = 2\n[topology_builder]\n"
                           "update_every = 20\n[relaxation]\nmax_iterations = 20\n");
  const auto a = runApp("gridtopo-map", (d / "run.ini").string());
  ASSERT_EQ(a.status, 0) << a.output;
  // Not quiet: each scheduled recomputation is reported (every 20 processed scans), and the final map's.
  EXPECT_NE(a.output.find("topology at 20 processed scans"), std::string::npos) << a.output;
  EXPECT_NE(a.output.find("topology at 40 processed scans"), std::string::npos) << a.output;
  const std::string options = slurp(d / "a/options.ini");
  EXPECT_NE(options.find("max_scans = 600"), std::string::npos) << options;
  EXPECT_NE(options.find("particles = 4"), std::string::npos) << options;
  EXPECT_NE(options.find("max_iterations = 20"), std::string::npos) << options;
  EXPECT_NE(options.find("[topology_builder]\nupdate_every = 20"), std::string::npos) << options;
  const auto b = runApp("gridtopo-map", (d / "a/options.ini").string() + " -o " + (d / "b").string() + " -q");
  ASSERT_EQ(b.status, 0) << b.output;
  for (const char* f : {"slam/map.gridmap.gz", "slam/trajectory.txt", "topology/labels.png", "topology/topology.json"})
    EXPECT_EQ(slurp(d / "a" / f), slurp(d / "b" / f)) << f;
  EXPECT_EQ(withoutLine(options, "output"), withoutLine(slurp(d / "b/options.ini"), "output"));
  fs::remove_all(d);
}

TEST(MapApp, BadInputNamesFileLineAndKeyAndWritesNothing) {
  const fs::path d = fresh("bad");
  auto expectError = [&](const std::string& ini, const std::string& message) {
    write(d / "bad.ini", ini);
    const auto r = runApp("gridtopo-map", (d / "bad.ini").string() + " -q");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  };
  const std::string run = "[map_run]\ninput = " + kLog + "\noutput = " + (d / "out").string() + "\n";
  expectError(run + "[mapping]\nx = 1\n", "bad.ini:4: [mapping]: unknown section");
  expectError(run + "colour = red\n", "bad.ini:4: [map_run] colour: unknown key");
  expectError(run + "[slam]\nparticles = many\n", "bad.ini:5: [slam] particles");
  expectError(run + "[topology_builder]\nupdate_every = -2\n", "bad.ini:5: [topology_builder] update_every");
  expectError(run + "[correction]\nmin_room_aera = 2\n", "bad.ini:5: [correction] min_room_aera");
  expectError(run + "model = no/such/model.yml\n", "bad.ini:4: [map_run] model: no such file");
  expectError("[map_run]\ninput = no/such.clf\noutput = x\n", "bad.ini:2: [map_run] input: no such file");
  // A model that cannot be read: exit 1, nothing written.
  write(d / "broken.yml", "%YAML:1.0\nnot a model\n");
  auto r = runApp("gridtopo-map", "-i " + kLog + " -o " + (d / "out").string() + " -m " + (d / "broken.yml").string() +
                                      " --max-scans 50 -p 2 -q");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_FALSE(fs::exists(d / "out")) << r.output;
  // One topology output cannot land (its name is taken by a directory): the SLAM set, computed and staged, does not
  // land either.
  fs::create_directories(d / "out2/topology/labels.png");
  r = runApp("gridtopo-map", "-i " + kLog + " -o " + (d / "out2").string() + " -m " + kModel + " --max-scans 300 -p 2 -q");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("labels.png is a directory"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(d / "out2/slam")) << r.output;
  EXPECT_FALSE(fs::exists(d / "out2/options.ini"));
  EXPECT_EQ(std::distance(fs::directory_iterator(d / "out2/topology"), fs::directory_iterator()), 1);
  // Usage.
  EXPECT_EQ(runApp("gridtopo-map", "-o " + (d / "out").string()).status, 2);
  EXPECT_EQ(runApp("gridtopo-map", "--frobnicate").status, 2);
  fs::remove_all(d);
}
