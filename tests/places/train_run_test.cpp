// gridtopo-train's run (places/train_run.h): the labelled maps it reads, its errors, and a small model trained on
// one labelled pair.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/scratch.h"
#include "gridtopo/core/error.h"
#include "gridtopo/places/train_run.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
const std::string kPlaces = std::string(GRIDTOPO_DATA_DIR) + "/places";
const std::string kPair = kPlaces + "/labelled/training_intel.png:" + kPlaces + "/maps/lab_intel.png";

std::string smallIni(const fs::path& dir, const std::string& extra = "") {
  const std::string path = (dir / "train.ini").string();
  std::ofstream(path) << "[scan_simulation]\nnum_beams = 120\nlattice_spacing = 0.3\n"
                      << "[training]\nweak_count = 6\nmax_samples_per_class = 1500\norder_samples_per_class = 800\n"
                      << "order_folds = 1\n" << extra;
  return path;
}
}  // namespace

TEST(TrainRun, AModelFromOnePairWithItsNotes) {
  const fs::path dir = test::scratch("train");
  places::TrainRunSpec spec;
  spec.pairs = {kPair};
  spec.ini = smallIni(dir);
  spec.threads = 2;
  std::size_t messages = 0;
  const places::PlacesModel m = places::trainPlacesModel(spec, [&](const std::string&) { ++messages; });
  EXPECT_GT(messages, 0u);
  EXPECT_EQ(m.scan.num_beams, 120);
  EXPECT_EQ(m.scan.threads, 2);
  EXPECT_LE(m.first.stumps.size(), 6u);
  EXPECT_GT(m.first.stumps.size(), 0u);
  EXPECT_EQ(m.notes.rfind("trained by gridtopo-train on: training_intel.png; decision list " + places::orderName(m.order),
                          0),
            0u)
      << m.notes;
  EXPECT_NE(m.notes.find("; validation "), std::string::npos);
  // The same inputs give the same model.
  const places::PlacesModel again = places::trainPlacesModel(spec);
  EXPECT_EQ(again.notes, m.notes);
  EXPECT_EQ(again.first.stumps.size(), m.first.stumps.size());
}

TEST(TrainRun, BadSpecsNameWhatIsWrong) {
  const fs::path dir = test::scratch("train_bad");
  places::TrainRunSpec spec;
  spec.pairs = {kPair};
  spec.threads = 0;
  try {
    places::trainPlacesModel(spec);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "--threads");
  }
  spec.threads = 1;
  spec.pairs = {"labels-without-map.png"};
  try {
    places::trainPlacesModel(spec);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "labels-without-map.png");
  }
  spec.pairs = {kPair};
  spec.ini = smallIni(dir, "simulated_maps = " + kPlaces + "/derived\n");
  try {
    places::trainPlacesModel(spec);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "[training] simulated_maps");
  }
}
