#include <gtest/gtest.h>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>

#include "gridtopo/core/error.h"
#include "gridtopo/places/boost_classifier.h"
#include "gridtopo/places/model.h"
#include "gridtopo/places/training.h"

using namespace gridtopo::places;
namespace fs = std::filesystem;

namespace {
// Two noisy features; the class depends on feature 1 only (f1 > 0.6), feature 0 is noise.
void synthetic(int n, cv::Mat& X, std::vector<int>& y, int seed) {
  cv::RNG rng(static_cast<uint64_t>(seed));
  X.create(n, 2, CV_32F);
  y.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    X.at<float>(i, 0) = rng.uniform(0.f, 1.f);
    X.at<float>(i, 1) = rng.uniform(0.f, 1.f);
    y[static_cast<std::size_t>(i)] = X.at<float>(i, 1) > 0.6f;
  }
}
}  // namespace

TEST(BoostedClassifier, LearnsAThresholdOnTheRightFeature) {
  cv::Mat X;
  std::vector<int> y;
  synthetic(2000, X, y, 1);
  BoostOptions o;
  o.weak_count = 20;
  const auto clf = trainBoostedClassifier(X, y, o);
  ASSERT_EQ(clf.stumps.size(), 20u);
  EXPECT_EQ(clf.stumps[0].feature, 1);
  EXPECT_NEAR(clf.stumps[0].threshold, 0.6, 0.02);
  cv::Mat Xt;
  std::vector<int> yt;
  synthetic(1000, Xt, yt, 2);
  int correct = 0;
  for (int i = 0; i < Xt.rows; ++i) correct += (clf.probability(Xt.ptr<float>(i)) > 0.5) == (yt[static_cast<std::size_t>(i)] == 1);
  EXPECT_GT(correct, 980);
  const float hi[2] = {0.5f, 0.95f}, lo[2] = {0.5f, 0.1f};
  EXPECT_GT(clf.probability(hi), 0.9);
  EXPECT_LT(clf.probability(lo), 0.1);
}

TEST(BoostedClassifier, NeedsBothClasses) {
  cv::Mat X(10, 2, CV_32F, cv::Scalar(0));
  EXPECT_THROW(trainBoostedClassifier(X, std::vector<int>(10, 1), BoostOptions()), std::invalid_argument);
}

TEST(PlacesModel, DecisionListProbabilitiesSumToOne) {
  PlacesModel m;
  m.order = {2, 0, 1};
  m.first.stumps = {{0, 0.5f, -1.f, 1.f}};
  m.second.stumps = {{1, 0.5f, -0.5f, 0.5f}};
  const float f[2] = {0.9f, 0.1f};
  float p[3];
  m.probabilities(f, p);
  EXPECT_NEAR(p[0] + p[1] + p[2], 1.0, 1e-6);
  EXPECT_NEAR(p[2], 1 / (1 + std::exp(-2.0)), 1e-6);  // doorway first, H = 1
  EXPECT_GT(p[1], p[0]);                               // second: corridor (H = -0.5 for "room")
}

TEST(PlacesModel, SaveLoadRoundTripAndMismatch) {
  PlacesModel m;
  m.feature_names = featureNames(m.features);
  m.order = {1, 0, 2};
  m.first.stumps = {{3, 1.25f, -0.3f, 0.7f}, {5, 2.f, 0.1f, -0.1f}};
  m.first.bias = -0.4;
  m.second.stumps = {{7, 0.5f, -1.f, 1.f}};
  m.compatibility = {{{0.5, -0.2, 0.1}, {-0.2, 0.6, 0.0}, {0.1, 0.0, 0.3}}};
  const fs::path dir = gridtopo::test::scratchPath("places_model_test");
  fs::create_directories(dir);
  const std::string path = (dir / "model.yml").string();
  m.save(path);
  const PlacesModel r = PlacesModel::load(path);
  EXPECT_EQ(r.order, m.order);
  ASSERT_EQ(r.first.stumps.size(), 2u);
  EXPECT_EQ(r.first.stumps[1].feature, 5);
  EXPECT_FLOAT_EQ(r.first.stumps[0].threshold, 1.25f);
  EXPECT_DOUBLE_EQ(r.first.bias, -0.4);
  EXPECT_DOUBLE_EQ(r.compatibility[0][1], -0.2);
  // A model trained with other features is refused with a clear error.
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const auto pos = text.find("min_chord");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 9, "old_chord");
  const std::string bad = (dir / "bad.yml").string();
  std::ofstream(bad) << text;
  try {
    PlacesModel::load(bad);
    FAIL() << "mismatched model accepted";
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.field(), "feature_names");
  }
  // Capped feature copies round-trip; a version-1 file (base features, no capped_ranges key) still loads, a
  // newer version is refused naming the field.
  PlacesModel mc = m;
  mc.features.capped_ranges = {10.0};
  mc.feature_names = featureNames(mc.features);
  mc.save(path);
  const PlacesModel rc = PlacesModel::load(path);
  ASSERT_EQ(rc.features.capped_ranges.size(), 1u);
  EXPECT_DOUBLE_EQ(rc.features.capped_ranges[0], 10.0);
  EXPECT_EQ(rc.feature_names.size(), 2 * numFeatures());
  m.features.capped_ranges.clear();
  m.feature_names = featureNames(m.features);
  m.save(path);
  std::ifstream in2(path);
  std::string v1((std::istreambuf_iterator<char>(in2)), {});
  v1.replace(v1.find("version: 2"), 10, "version: 1");
  const std::string no_caps = "capped_ranges:\n   []\n";
  ASSERT_NE(v1.find(no_caps), std::string::npos);
  v1.replace(v1.find(no_caps), no_caps.size(), "");
  std::ofstream((dir / "v1.yml").string()) << v1;
  EXPECT_EQ(PlacesModel::load((dir / "v1.yml").string()).feature_names, featureNames());
  std::string v3 = v1;
  v3.replace(v3.find("version: 1"), 10, "version: 3");
  std::ofstream((dir / "v3.yml").string()) << v3;
  try {
    PlacesModel::load((dir / "v3.yml").string());
    FAIL() << "unknown model version accepted";
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.field(), "version");
  }
  std::ofstream(dir / "not_a_model.yml") << "%YAML:1.0\nfoo: 1\n";
  EXPECT_THROW(PlacesModel::load((dir / "not_a_model.yml").string()), gridtopo::InputError);
  EXPECT_THROW(PlacesModel::load((dir / "missing.yml").string()), gridtopo::InputError);
}

TEST(Training, SyntheticRoomsAndCorridors) {
  // Corridors (long 2 m wide) and rooms (5 x 5 m) as separate labelled maps; the trained model tells them apart.
  auto make = [](bool corridor) {
    OccupancyImage occ;
    occ.resolution = 0.1;
    occ.cells = cv::Mat(corridor ? 30 : 60, corridor ? 160 : 60, CV_8U, cv::Scalar(kOccupied));
    const cv::Rect r = corridor ? cv::Rect(5, 5, 150, 20) : cv::Rect(5, 5, 50, 50);
    occ.cells(r).setTo(kFree);
    cv::Mat codes(occ.cells.size(), CV_8U, cv::Scalar(0));
    codes(r).setTo(corridor ? 115 : 77);
    return std::make_pair(occ, codes);
  };
  ScanSimulationOptions scan;
  scan.num_beams = 120;
  scan.lattice_spacing = 0.2;
  TrainingOptions to;
  to.order = "corridor,room,doorway";
  to.boost.weak_count = 10;
  std::vector<MapSamples> s;
  for (bool c : {true, false, true, false}) {
    const auto [occ, codes] = make(c);
    s.push_back(computeSamples(occ, &codes, scan, FeatureOptions()));
  }
  // A doorway class is needed for the second classifier: label the corridor ends as doorway in one map.
  for (std::size_t i = 0; i < s[2].labels.size(); ++i)
    if (s[2].lattice.samples[i].x < 12) s[2].labels[i] = 2;
  const PlacesModel m = trainModel({&s[0], &s[1], &s[2], &s[3]}, scan, FeatureOptions(), to);
  int correct = 0, total = 0;
  for (int k : {1, 3})
    for (int i = 0; i < s[static_cast<std::size_t>(k)].features.rows; ++i) {
      float p[3];
      m.probabilities(s[static_cast<std::size_t>(k)].features.ptr<float>(i), p);
      correct += (std::max_element(p, p + 3) - p) == s[static_cast<std::size_t>(k)].labels[static_cast<std::size_t>(i)];
      ++total;
    }
  EXPECT_GT(correct, 0.9 * total);
  EXPECT_GT(m.compatibility[0][0], 0.0);
  EXPECT_LT(m.compatibility[0][1], 0.0);  // rooms and corridors never neighbours here
}

TEST(BoostedClassifier, DeterministicForAFixedSeed) {
  cv::Mat X;
  std::vector<int> y;
  synthetic(3000, X, y, 9);
  BoostOptions o;
  o.weak_count = 15;
  const auto a = trainBoostedClassifier(X, y, o), b = trainBoostedClassifier(X, y, o);
  ASSERT_EQ(a.stumps.size(), b.stumps.size());
  for (std::size_t i = 0; i < a.stumps.size(); ++i) {
    EXPECT_EQ(a.stumps[i].feature, b.stumps[i].feature);
    EXPECT_EQ(a.stumps[i].threshold, b.stumps[i].threshold);
    EXPECT_EQ(a.stumps[i].left, b.stumps[i].left);
    EXPECT_EQ(a.stumps[i].right, b.stumps[i].right);
  }
}
