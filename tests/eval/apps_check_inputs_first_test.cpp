// issue 36, the weak points left: gridtopo-topology-compare, gridtopo-topology-eval and gridtopo-train read their
// option INIs with the strict reader of gridtopo-slam / gridtopo-topology (unknown sections and keys refused with
// file, line and a "did you mean"; binary files refused); gridtopo-render, gridtopo-import, gridtopo-train,
// gridtopo-topology-compare and gridtopo-topology-eval check their outputs before any input is read (the inputs
// below do not exist: an error naming the output shows it was checked first), and write through the OutputSet
// transaction (no temporary left).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/run_app.h"
#include "common/scratch.h"

namespace fs = std::filesystem;
using gridtopo::testing_app::runApp;

namespace {
const std::string kPlaces = std::string(GRIDTOPO_DATA_DIR) + "/places";

fs::path dir(const std::string& name) {
  const fs::path d = gridtopo::test::scratch("apps_check_inputs_first") / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
void put(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// Runs `app args`, expects exit 1 and exactly one line "app: error: <message>".
void expectError(const std::string& app, const std::string& args, const std::string& message) {
  const auto r = runApp(app, args);
  EXPECT_EQ(r.status, 1) << app << " " << args << "\n" << r.output;
  EXPECT_EQ(r.output, app + ": error: " + message + "\n") << app << " " << args;
}

// Names in `d` that start with '.' (the transaction's temporaries and stages).
int hiddenEntries(const fs::path& d) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(d)) n += e.path().filename().string()[0] == '.';
  return n;
}
}  // namespace

TEST(AppsCheckInputsFirst, TopologyCompareAndEvalReadTheirIniStrictly) {
  const fs::path d = dir("topology_ini");
  const std::string typo = (d / "typo.ini").string(), section = (d / "section.ini").string(),
                    none = (d / "none.ini").string(), binary = (d / "binary.ini").string();
  put(typo, "[topology]\nthreads = 2\nthreadz = 2\n");
  put(section, "[topology]\n[relaxatoin]\nmax_iterations = 3\n");
  put(none, "[correction]\nenabled = true\n");
  put(binary, std::string("[topology]\n\0\x7f", 13));
  const std::string typo_msg = typo + ":3: [topology] threadz: unknown key (did you mean 'threads'? not an option of "
                                      "this section; see config-ini/topology.ini)";
  const std::string section_msg = section + ":2: [relaxatoin]: unknown section (did you mean [relaxation]? this app "
                                            "reads topology, relaxation, correction)";
  const std::string plan = " --reference-map nomap.png --reference-labels nolabels.png --reference-segmentation no.png";
  for (const auto& [ini, message] : {std::pair{typo, typo_msg}, std::pair{section, section_msg},
                                     std::pair{none, none + ": [topology]: section not found"},
                                     std::pair{binary, binary + ": not a text INI file (byte 11 is 0x00)"}}) {
    expectError("gridtopo-topology-compare", "nomap.png nodir -c " + ini + plan, message);
    expectError("gridtopo-topology-eval", "-d " + (d / "noplaces").string() + " -c " + ini, message);
  }
}

TEST(AppsCheckInputsFirst, TrainingIniTyposAreRefused) {
  const fs::path d = dir("training_ini");
  const std::string ini = (d / "train.ini").string();
  put(ini, "[scan_simulation]\nnum_beams = 120\n[training]\nweak_cuont = 6\n");
  const std::string message = ini + ":4: [training] weak_cuont: unknown key (did you mean 'weak_count'? not an option "
                                    "of this section; see config-ini/topology_train.ini)";
  expectError("gridtopo-topology-eval", "-d " + (d / "noplaces").string() + " -t " + ini, message);
  expectError("gridtopo-train", "-d " + (d / "noplaces").string() + " -c " + ini + " -o " + (d / "m.yml").string(),
              message);
  put(ini, "[scan_simulation]\nnum_beams = 120\n[featurse]\n");
  expectError("gridtopo-train", "-d " + (d / "noplaces").string() + " -c " + ini + " -o " + (d / "m.yml").string(),
              ini + ":3: [featurse]: unknown section (did you mean [features]? this app reads scan_simulation, "
                    "features, training)");
  EXPECT_FALSE(fs::exists(d / "m.yml"));
}

// An output below a regular file cannot be made: refused before the inputs (which do not exist) are read.
TEST(AppsCheckInputsFirst, AnUnusableOutputIsRefusedBeforeTheInputsAreRead) {
  const fs::path d = dir("outputs");
  const std::string file = (d / "afile").string();
  put(file, "");
  const std::string under = file + "/x", cannot = ": cannot create the output folder " + file + ": not a folder";
  expectError("gridtopo-render", "-i nolog.clf -t notraj.txt --whole -o " + under + ".png",
              under + ".png" + cannot);
  expectError("gridtopo-render", "-i nolog.clf -t notraj.txt --whole -o " + (d / "r.png").string() + " -j " + under +
                                     ".json",
              under + ".json" + cannot);
  expectError("gridtopo-import", "-i nolog.clf -o " + under + ".rawlog", under + ".rawlog" + cannot);
  expectError("gridtopo-import", "--simulate 10 --ground-truth " + under + ".txt", under + ".txt" + cannot);
  expectError("gridtopo-train", "-d " + (d / "noplaces").string() + " -o " + under + ".yml", under + ".yml" + cannot);
  expectError("gridtopo-topology-compare",
              "nomap.png nodir --reference-map a.png --reference-labels b.png --reference-segmentation c.png --json " +
                  under + ".json",
              under + ".json" + cannot);
  expectError("gridtopo-topology-eval", "-d " + (d / "noplaces").string() + " --markdown " + under + ".md",
              under + ".md" + cannot);
  expectError("gridtopo-topology-eval", "-d " + (d / "noplaces").string() + " --json " + d.string(),
              d.string() + ": cannot write the output file: it is a folder");
  EXPECT_EQ(hiddenEntries(d), 0);
  EXPECT_FALSE(fs::exists(d / "r.png"));
}

// gridtopo-train writes its model through the transaction: in a new folder, over an earlier model, in either
// format (picked by the extension, which the temporary keeps); nothing hidden is left. About a second per model.
TEST(AppsCheckInputsFirst, TrainWritesTheModelThroughTheTransaction) {
  const fs::path d = dir("train");
  const std::string ini = (d / "small.ini").string();
  put(ini, "[scan_simulation]\nnum_beams = 120\nlattice_spacing = 0.3\n[training]\nweak_count = 6\n"
           "max_samples_per_class = 1500\norder_samples_per_class = 800\norder_folds = 1\n");
  const std::string pair = kPlaces + "/labelled/training_intel.png:" + kPlaces + "/maps/lab_intel.png";
  const fs::path yml = d / "models" / "m.yml", json = d / "models" / "m.json";
  for (const fs::path& out : {yml, yml, json}) {
    const auto r = runApp("gridtopo-train", "-p " + pair + " -c " + ini + " -o " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("wrote " + out.string() + " (decision list "), std::string::npos) << r.output;
  }
  std::ifstream a(yml), b(json);
  std::string first, open;
  std::getline(a, first);
  std::getline(b, open);
  EXPECT_EQ(first, "%YAML:1.0");
  EXPECT_EQ(open, "{");
  EXPECT_EQ(hiddenEntries(d), 0);
}
