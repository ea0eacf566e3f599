#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>

#include "gridtopo/places/features.h"
#include "synthetic.h"

using namespace gridtopo::places;

namespace {
std::vector<float> featuresAt(const OccupancyImage& occ, cv::Point p) {
  ScanSimulationOptions o;
  const auto scans = simulateScans(occ, {p}, o);
  const cv::Mat f = extractFeatures(scans, FeatureOptions(), 1);
  return std::vector<float>(f.ptr<float>(0), f.ptr<float>(0) + f.cols);
}
int idx(const std::string& name) {
  const auto n = featureNames();
  return static_cast<int>(std::find(n.begin(), n.end(), name) - n.begin());
}
}  // namespace

TEST(Features, EveryFeatureDocumented) {
  EXPECT_EQ(featureNames().size(), numFeatures());
  for (const auto& d : featureDescriptions()) EXPECT_NE(d.find(": "), std::string::npos) << d;
}

TEST(Features, SquareRoom) {
  const auto occ = test::rectangleRoom(4.0, 4.0, 0.05);
  const auto f = featuresAt(occ, {45, 45});
  EXPECT_NEAR(f[idx("area")], 16.0, 0.6);
  EXPECT_NEAR(f[idx("perimeter")], 16.0, 0.6);
  EXPECT_NEAR(f[idx("compactness")], 16.0, 0.5);
  EXPECT_NEAR(f[idx("min_chord")], 4.0, 0.1);
  EXPECT_NEAR(f[idx("max_chord")], 4.0 * std::sqrt(2.0), 0.15);
  EXPECT_NEAR(f[idx("ellipse_ratio")], 1.0, 0.03);
  // A uniform square of side 4 has second moment 4^2/12 per axis: ellipse semi-axis 2 sqrt(16/12) = 2.31 m.
  EXPECT_NEAR(f[idx("ellipse_major")], 2.309, 0.08);
  EXPECT_NEAR(f[idx("min_beam")], 2.0, 0.06);
  EXPECT_NEAR(f[idx("centroid_offset")], 0.0, 0.1);
  EXPECT_NEAR(f[idx("hu1")], 1.0 / 6.0, 0.01);  // Hu1 of a square
  EXPECT_EQ(f[idx("gaps_large")], 0.0f);
}

TEST(Features, LongCorridor) {
  const auto occ = test::rectangleRoom(20.0, 2.0, 0.05);
  const auto f = featuresAt(occ, {205, 25});
  EXPECT_NEAR(f[idx("min_chord")], 2.0, 0.1);
  EXPECT_NEAR(f[idx("perp_chord")], 20.0, 0.3);
  EXPECT_NEAR(f[idx("area")], 40.0, 1.5);
  EXPECT_LT(f[idx("ellipse_ratio")], 0.15);
  EXPECT_NEAR(f[idx("chord_centering")], 0.5, 0.05);
  EXPECT_GT(f[idx("kurtosis")], 0.0);  // a few very long beams along the corridor
}

TEST(Features, IndependentOfResolution) {
  const auto a = featuresAt(test::rectangleRoom(6.0, 3.0, 0.05), {5 + 40, 5 + 20});
  const auto b = featuresAt(test::rectangleRoom(6.0, 3.0, 0.025), {5 + 80, 5 + 40});
  for (const char* n : {"area", "perimeter", "mean_beam", "min_chord", "max_chord", "ellipse_major", "ellipse_minor"})
    EXPECT_NEAR(a[idx(n)], b[idx(n)], 0.05 * std::max(1.0f, std::abs(a[idx(n)]))) << n;
}

TEST(Features, PolygonMomentsEqualOpenCV) {
  std::vector<cv::Point2d> p;
  std::vector<cv::Point2f> pf;
  cv::RNG rng(5);
  for (int k = 0; k < 90; ++k) {
    const double r = rng.uniform(0.5, 6.0), th = 2 * M_PI * k / 90;
    p.emplace_back(r * std::cos(th) + 1.0, r * std::sin(th) - 2.0);
    pf.emplace_back(static_cast<float>(p.back().x), static_cast<float>(p.back().y));
  }
  const cv::Moments a = polygonMoments(p), b = cv::moments(pf);
  for (auto [x, y] : {std::pair{a.m00, b.m00}, {a.m10, b.m10}, {a.m01, b.m01}, {a.m20, b.m20}, {a.m11, b.m11},
                      {a.m02, b.m02}, {a.m30, b.m30}, {a.m21, b.m21}, {a.m12, b.m12}, {a.m03, b.m03}})
    EXPECT_NEAR(x, y, 1e-3 * std::max(1.0, std::abs(y)));
}

TEST(Features, ContextFeaturesAreWindowMeans) {
  const auto occ = test::rectangleRoom(2.0, 1.0, 0.1);  // 20 x 10 free cells, one block per cell
  const auto lat = buildLattice(occ, 0.1);
  ASSERT_EQ(lat.samples.size(), 200u);
  cv::Mat f(static_cast<int>(lat.samples.size()), 2, CV_32F, cv::Scalar(3.f));
  for (std::size_t i = 0; i < lat.samples.size(); ++i)
    f.at<float>(static_cast<int>(i), 1) = lat.samples[i] == cv::Point(12, 10) ? 9.f : 0.f;
  const cv::Mat c = addContextFeatures(lat, f, 0.1, 0.1);  // 3 x 3 window
  ASSERT_EQ(c.cols, 4);
  for (std::size_t i = 0; i < lat.samples.size(); ++i) {
    EXPECT_FLOAT_EQ(c.at<float>(static_cast<int>(i), 2), 3.f);  // constant stays constant, also at the walls
    const cv::Point p = lat.samples[i];
    const bool near = std::abs(p.x - 12) <= 1 && std::abs(p.y - 10) <= 1;
    if (!near) {
      EXPECT_FLOAT_EQ(c.at<float>(static_cast<int>(i), 3), 0.f);
    }
  }
  // At (11, 9) the window holds 9 samples (interior), one of them 9: mean 1. At the corner (5, 5): 4 samples.
  for (std::size_t i = 0; i < lat.samples.size(); ++i)
    if (lat.samples[i] == cv::Point(11, 9)) {
      EXPECT_FLOAT_EQ(c.at<float>(static_cast<int>(i), 3), 1.f);
    }
  FeatureOptions o;
  o.context_radius = 1.0;
  EXPECT_EQ(featureNames(o).size(), 4 * numFeatures());  // base, _cap10 copies, then the context of both
  o.capped_ranges.clear();
  EXPECT_EQ(featureNames(o).size(), 2 * numFeatures());
  EXPECT_EQ(featureNames(o).back(), featureNames().back() + "_ctx");
}

TEST(Features, CappedRangeCopies) {
  // In the middle of a 20 x 2 m corridor the beams along it reach 10 m: capped at 4 m, the scan is that of a
  // 8 x 2 m box (area 16 m^2 instead of 40), while a 3 x 3 m room has no beam longer than 2.2 m and keeps its
  // features unchanged.
  FeatureOptions o;
  o.capped_ranges = {4.0, 8.0};
  const auto names = featureNames(o);
  ASSERT_EQ(names.size(), 3 * numFeatures());
  EXPECT_EQ(names[numFeatures()], featureNames()[0] + "_cap4");
  EXPECT_EQ(names.back(), featureNames().back() + "_cap8");
  const ScanSimulationOptions so;
  const auto corridor = simulateScans(test::rectangleRoom(20.0, 2.0, 0.05), {{205, 25}}, so);
  const cv::Mat f = extractFeatures(corridor, o, 1);
  ASSERT_EQ(static_cast<std::size_t>(f.cols), names.size());
  const int F = static_cast<int>(numFeatures());
  EXPECT_NEAR(f.at<float>(0, idx("area")), 40.0, 1.5);
  EXPECT_NEAR(f.at<float>(0, F + idx("max_beam")), 4.0, 1e-5);
  EXPECT_NEAR(f.at<float>(0, F + idx("perp_chord")), 8.0, 1e-4);
  EXPECT_LT(f.at<float>(0, F + idx("area")), 18.0);
  EXPECT_GT(f.at<float>(0, F + idx("area")), 14.0);
  EXPECT_NEAR(f.at<float>(0, 2 * F + idx("perp_chord")), 16.0, 1e-4);
  const auto room = simulateScans(test::rectangleRoom(3.0, 3.0, 0.05), {{35, 35}}, so);
  const cv::Mat g = extractFeatures(room, o, 1);
  for (int k = 0; k < F; ++k) {
    EXPECT_EQ(g.at<float>(0, k), g.at<float>(0, F + k)) << names[static_cast<std::size_t>(k)];
    EXPECT_EQ(g.at<float>(0, k), g.at<float>(0, 2 * F + k)) << names[static_cast<std::size_t>(k)];
  }
}

TEST(Features, CappedCopiesEqualFeaturesOfTheCappedScan) {
  // The whole-map extraction copies the base features into a capped column when no beam exceeds the cap and
  // computes them otherwise; either way each capped column must equal the features of the capped scan itself.
  // Scans: a room (all beams short), a corridor (long beams) and one whose longest beam equals the cap exactly.
  FeatureOptions o;
  o.capped_ranges = {2.0, 10.0};
  const ScanSimulationOptions so;
  SimulatedScans scans = simulateScans(test::rectangleRoom(20.0, 2.0, 0.05), {{205, 25}, {30, 20}}, so);
  const auto room = simulateScans(test::rectangleRoom(3.0, 3.0, 0.05), {{35, 35}}, so);
  scans.ranges_mm.insert(scans.ranges_mm.end(), room.ranges_mm.begin(), room.ranges_mm.end());
  std::vector<std::uint16_t> at_cap(room.ranges_mm.begin(), room.ranges_mm.end());
  at_cap[7] = 2000;  // longest beam exactly 2 m = the first cap
  for (auto& r : at_cap) r = std::min<std::uint16_t>(r, 2000);
  scans.ranges_mm.insert(scans.ranges_mm.end(), at_cap.begin(), at_cap.end());
  ASSERT_EQ(scans.size(), 4u);
  const cv::Mat f = extractFeatures(scans, o, 2);
  const int F = static_cast<int>(numFeatures()), M = scans.num_beams;
  std::vector<float> capped(static_cast<std::size_t>(M)), expected(numFeatures());
  for (std::size_t i = 0; i < scans.size(); ++i)
    for (std::size_t c = 0; c < o.capped_ranges.size(); ++c) {
      for (int k = 0; k < M; ++k)
        capped[static_cast<std::size_t>(k)] =
            std::min(scans.scan(i)[k] * 0.001f, static_cast<float>(o.capped_ranges[c]));
      extractFeatures(capped.data(), M, o, expected.data());
      for (int k = 0; k < F; ++k)
        EXPECT_EQ(f.at<float>(static_cast<int>(i), F * static_cast<int>(c + 1) + k), expected[static_cast<std::size_t>(k)])
            << "scan " << i << " cap " << o.capped_ranges[c] << " feature " << featureNames()[static_cast<std::size_t>(k)];
    }
  // The corridor's capped copy at 2 m differs from its base features (the cap is in effect there).
  EXPECT_NE(f.at<float>(0, idx("max_beam")), f.at<float>(0, F + idx("max_beam")));
}

TEST(Features, LanesEqualScalarBitForBit) {
  // The whole-map extraction runs several scans at once in SIMD lanes (SSE2: 2, AVX: 4, AVX-512F: 8); each lane must give
  // the bits of the one-scan function, for both kernels. Scans: every lattice sample of a cluttered room (with a
  // long corridor, so the 10 m cap applies) and random scans (zeros, ties, 30 m beams); 3 + the lattice count
  // is odd, so the last batch is partial.
  OccupancyImage occ = test::rectangleRoom(24.0, 6.0, 0.05);
  cv::RNG rng(3);
  for (int i = 0; i < 60; ++i)
    occ.cells(cv::Rect(rng.uniform(10, 470), rng.uniform(10, 120), rng.uniform(1, 8), rng.uniform(1, 8))).setTo(kOccupied);
  const auto lat = buildLattice(occ, 0.5);
  ScanSimulationOptions so;
  SimulatedScans scans = simulateScans(occ, lat.samples, so);
  const int M = scans.num_beams;
  // Extra scans: all zero, a few 30 m beams, random, and nearly constant ones (20 m +- a few mm: the standard
  // deviations then cancel to a few digits, so a sum taken in another order would show in the floats).
  for (int extra = 0; extra < 9 + (scans.size() % 2 == 0); ++extra)
    for (int k = 0; k < M; ++k)
      scans.ranges_mm.push_back(static_cast<std::uint16_t>(extra == 0   ? 0
                                                           : extra == 1 ? 30000 * (k % 7 == 0)
                                                           : extra < 5  ? rng.uniform(0, 30001)
                                                                        : 20000 + (k * extra) % 5));
  ASSERT_EQ(scans.size() % 2, 1u);
  ASSERT_GT(scans.size(), 100u);
  FeatureOptions o;
  o.capped_ranges = {2.0, 10.0};
  const std::size_t F = numFeatures();
  std::vector<float> beams(static_cast<std::size_t>(M)), expected(F * 3);
  for (const int max_lanes : {2, 4, 8}) {
    const int lanes = featureLanesUpTo(max_lanes);
    EXPECT_LE(lanes, max_lanes);
    const cv::Mat f = extractFeatures(scans, o, 2);
    ASSERT_EQ(static_cast<std::size_t>(f.cols), 3 * F);
    int mismatches = 0, capped_differ = 0;
    for (std::size_t i = 0; i < scans.size(); ++i) {
      for (std::size_t c = 0; c < 3; ++c) {
        const float cap = c == 0 ? 1e9f : static_cast<float>(o.capped_ranges[c - 1]);
        for (int k = 0; k < M; ++k) beams[static_cast<std::size_t>(k)] = std::min(scans.scan(i)[k] * 0.001f, cap);
        extractFeatures(beams.data(), M, o, expected.data() + c * F);
      }
      const float* row = f.ptr<float>(static_cast<int>(i));
      mismatches += std::memcmp(row, expected.data(), 3 * F * sizeof(float)) != 0;
      capped_differ += std::memcmp(row, row + F, F * sizeof(float)) != 0;
    }
    EXPECT_EQ(mismatches, 0) << lanes << " lanes";
    EXPECT_GT(capped_differ, 20) << "the caps must be in effect for many scans";
  }
  featureLanes(true);
}

TEST(Features, BeamMajorScansGiveTheSameBits) {
  // extractFeaturesOfBeams reads the scans beam-major (as simulateBeams gives them): every feature, capped copies
  // included, equals extractFeatures' of the same scans sample-major.
  OccupancyImage occ = test::rectangleRoom(24.0, 6.0, 0.05);
  cv::RNG rng(4);
  for (int i = 0; i < 60; ++i)
    occ.cells(cv::Rect(rng.uniform(10, 470), rng.uniform(10, 120), rng.uniform(1, 8), rng.uniform(1, 8))).setTo(kOccupied);
  const auto lat = buildLattice(occ, 0.3);
  ScanSimulationOptions so;
  const SimulatedScans scans = simulateScans(occ, lat.samples, so);
  const cv::Mat beams = simulateBeams(occ, lat.samples, so);
  ASSERT_EQ(beams.cols, static_cast<int>(scans.size()));
  FeatureOptions o;
  o.capped_ranges = {2.0, 10.0};
  const cv::Mat a = extractFeatures(scans, o, 2), b = extractFeaturesOfBeams(beams, o, 2);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.rows, 500);
  EXPECT_EQ(std::memcmp(a.data, b.data, a.total() * a.elemSize()), 0);
  int capped_differ = 0;
  for (int i = 0; i < a.rows; ++i)
    capped_differ += std::memcmp(a.ptr<float>(i), a.ptr<float>(i) + numFeatures(), numFeatures() * sizeof(float)) != 0;
  EXPECT_GT(capped_differ, 20);
}
