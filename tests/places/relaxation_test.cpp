#include <gtest/gtest.h>

#include <cstring>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "gridtopo/core/error.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/relaxation.h"

using namespace gridtopo::places;

TEST(Relaxation, CompatibilitiesFromBlockLabels) {
  cv::Mat lab(20, 20, CV_32S, cv::Scalar(0));
  lab(cv::Rect(0, 10, 20, 10)).setTo(1);
  lab.at<int>(10, 5) = 2;
  std::array<std::array<double, 3>, 3> counts{};
  accumulateNeighbourCounts(lab, counts);
  EXPECT_EQ(counts[0][1], counts[1][0]);
  const auto r = compatibilityFromCounts(counts);
  EXPECT_GT(r[0][0], 0.3);
  EXPECT_GT(r[1][1], 0.3);
  EXPECT_LT(r[0][1], 0.0);
  EXPECT_GT(r[2][0], -1.0);
  for (const auto& row : r)
    for (double v : row) EXPECT_TRUE(v >= -1 && v <= 1);
}

TEST(Relaxation, ConvergesAndRemovesANoisyCell) {
  // 10 x 10 lattice, all "room" with P = 0.7, except one cell the classifier thought "corridor".
  cv::Mat p(10, 10, CV_32FC3, cv::Scalar(0.7, 0.2, 0.1));
  p.at<cv::Vec3f>(5, 5) = cv::Vec3f(0.3f, 0.6f, 0.1f);
  cv::Mat valid(10, 10, CV_8U, cv::Scalar(1));
  Compatibility r{{{0.5, -0.5, 0.0}, {-0.5, 0.5, 0.0}, {0.0, 0.0, 0.5}}};
  RelaxationOptions o;
  o.max_iterations = 200;
  o.tolerance = 1e-4;
  const auto res = relaxLabels(p, valid, r, o, 2);
  EXPECT_TRUE(res.converged);
  EXPECT_LT(res.iterations, 200);
  EXPECT_GT(p.at<cv::Vec3f>(5, 5)[0], 0.9f);
  EXPECT_GT(p.at<cv::Vec3f>(0, 0)[0], 0.9f);
  const cv::Vec3f v = p.at<cv::Vec3f>(3, 7);
  EXPECT_NEAR(v[0] + v[1] + v[2], 1.0, 1e-5);
}

TEST(Relaxation, ThreadsDoNotChangeResults) {
  cv::Mat p(17, 13, CV_32FC3);
  cv::RNG rng(3);
  for (int y = 0; y < p.rows; ++y)
    for (int x = 0; x < p.cols; ++x) {
      cv::Vec3f v(rng.uniform(0.1f, 1.f), rng.uniform(0.1f, 1.f), rng.uniform(0.1f, 1.f));
      p.at<cv::Vec3f>(y, x) = v / (v[0] + v[1] + v[2]);
    }
  cv::Mat valid(p.size(), CV_8U, cv::Scalar(1));
  Compatibility r{{{0.4, -0.3, 0.1}, {-0.3, 0.4, 0.1}, {0.1, 0.1, 0.2}}};
  cv::Mat a = p.clone(), b = p.clone();
  relaxLabels(a, valid, r, RelaxationOptions(), 1);
  relaxLabels(b, valid, r, RelaxationOptions(), 3);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(Labelling, BadInputs) {
  EXPECT_THROW(occupancyFromGrey(cv::Mat(), 0.05, "x.png"), gridtopo::InputError);
  EXPECT_THROW(occupancyFromGrey(cv::Mat(5, 5, CV_8U, cv::Scalar(255)), -1, "x.png"), gridtopo::InputError);
  EXPECT_THROW(occupancyFromGrey(cv::Mat(5, 5, CV_16U, cv::Scalar(255)), 0.05, "x.png"), gridtopo::InputError);
  const auto occ = occupancyFromGrey(cv::Mat(20, 20, CV_8U, cv::Scalar(0)), 0.05, "black.png");
  PlacesModel m;
  try {
    labelPlaces(occ, m, RelaxationOptions(), 1, "black.png");
    FAIL() << "map without free space accepted";
  } catch (const gridtopo::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no free cell"), std::string::npos);
  }
}

TEST(Relaxation, NeighbourhoodRadius) {
  // A 3 x 3 block of "corridor" (0.4, 0.6) in a room (0.6, 0.4). One iteration at the block's centre: its 8
  // neighbours are all corridor, q = (-0.1, +0.1), P(corridor) = 0.66 / 1.02; in the 5 x 5 window 16 of its 24
  // neighbours are room, q = (+1/30, -1/30), P(corridor) = 0.58 / (0.4 (31/30) + 0.58).
  cv::Mat p(15, 15, CV_32FC3, cv::Scalar(0.6, 0.4, 0.0));
  p(cv::Rect(6, 6, 3, 3)).setTo(cv::Scalar(0.4, 0.6, 0.0));
  cv::Mat valid(p.size(), CV_8U, cv::Scalar(1));
  const Compatibility r{{{0.5, -0.5, 0.0}, {-0.5, 0.5, 0.0}, {0.0, 0.0, 0.5}}};
  RelaxationOptions o;
  o.max_iterations = 1;
  cv::Mat a = p.clone(), a2 = p.clone(), b = p.clone(), c = p.clone();
  relaxLabels(a, valid, r, o, 1);
  EXPECT_NEAR(a.at<cv::Vec3f>(7, 7)[1], 0.66 / 1.02, 1e-5);
  o.neighbourhood_radius = 2;
  relaxLabels(a2, valid, r, o, 1);
  EXPECT_NEAR(a2.at<cv::Vec3f>(7, 7)[1], 0.58 / (0.4 * 31.0 / 30.0 + 0.58), 1e-5);
  o.max_iterations = 50;
  relaxLabels(b, valid, r, o, 1);
  for (int y = 6; y < 9; ++y)
    for (int x = 6; x < 9; ++x) EXPECT_GT(b.at<cv::Vec3f>(y, x)[0], 0.9f) << y << "," << x;
  relaxLabels(c, valid, r, o, 3);
  EXPECT_EQ(cv::norm(b, c, cv::NORM_INF), 0.0);
  o.neighbourhood_radius = 0;
  EXPECT_THROW(relaxLabels(c, valid, r, o, 1), gridtopo::InputError);
}

namespace {
// Reference: one whole integral image per iteration (rows + 1 x cols + 1, label sums and the count), the window
// sums and the update exactly as relaxLabels defines them.
void relaxWithWholeIntegral(cv::Mat& probs, const cv::Mat& valid, const Compatibility& r, int R, int iterations) {
  const int rows = probs.rows, cols = probs.cols;
  std::vector<double> integ(static_cast<std::size_t>((rows + 1) * (cols + 1) * 4), 0.0);
  const auto at = [&](int y, int x) { return integ.data() + (static_cast<std::size_t>(y) * (cols + 1) + x) * 4; };
  cv::Mat next = probs.clone();
  for (int it = 0; it < iterations; ++it) {
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < cols; ++x) {
        double v[4] = {0, 0, 0, 0};
        if (valid.at<unsigned char>(y, x))
          for (int l = 0; l < 3; ++l) v[l] = probs.at<cv::Vec3f>(y, x)[l], v[3] = 1;
        double* o = at(y + 1, x + 1);
        const double *a = at(y, x + 1), *b = at(y + 1, x), *c = at(y, x);
        for (int l = 0; l < 4; ++l) o[l] = v[l] + a[l] + b[l] - c[l];
      }
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < cols; ++x) {
        if (!valid.at<unsigned char>(y, x)) continue;
        const int y0 = std::max(0, y - R), y1 = std::min(rows, y + R + 1);
        const int x0 = std::max(0, x - R), x1 = std::min(cols, x + R + 1);
        const double *a = at(y1, x1), *b = at(y0, x1), *c = at(y1, x0), *d = at(y0, x0);
        const cv::Vec3f& pi = probs.at<cv::Vec3f>(y, x);
        double s[3];
        for (int l = 0; l < 3; ++l) s[l] = a[l] - b[l] - c[l] + d[l] - pi[l];
        const double n = std::round(a[3] - b[3] - c[3] + d[3]) - 1;
        cv::Vec3f& out = next.at<cv::Vec3f>(y, x);
        if (n < 0.5) { out = pi; continue; }
        double u[3], z = 0;
        for (int l = 0; l < 3; ++l) {
          double q = 0;
          for (int m = 0; m < 3; ++m) q += r[l][m] * s[m] / n;
          u[l] = pi[l] * (1.0 + q);
          z += u[l];
        }
        for (int l = 0; l < 3; ++l) out[l] = z > 0 ? static_cast<float>(u[l] / z) : pi[l];
      }
    std::swap(probs, next);
  }
}

// `rows` x `cols` lattice blocks of random label distributions, a fifth of them invalid (all zero), drawn from `seed`.
std::pair<cv::Mat, cv::Mat> randomLattice(int rows, int cols, int seed) {
  cv::Mat p(rows, cols, CV_32FC3);
  cv::Mat valid(p.size(), CV_8U, cv::Scalar(1));
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  for (int y = 0; y < p.rows; ++y)
    for (int x = 0; x < p.cols; ++x) {
      cv::Vec3f v(rng.uniform(0.05f, 1.f), rng.uniform(0.05f, 1.f), rng.uniform(0.05f, 1.f));
      p.at<cv::Vec3f>(y, x) = v / (v[0] + v[1] + v[2]);
      if (rng.uniform(0.0, 1.0) < 0.2) valid.at<unsigned char>(y, x) = 0, p.at<cv::Vec3f>(y, x) = cv::Vec3f(0, 0, 0);
    }
  return {p, valid};
}

// Room and corridor repel, each attracts itself, doorways mildly attract both.
const Compatibility kMixedCompatibility{{{0.4, -0.3, 0.1}, {-0.3, 0.4, 0.1}, {0.1, 0.1, 0.2}}};
}  // namespace

TEST(Relaxation, RingOfIntegralRowsEqualsTheWholeIntegralImage) {
  // relaxLabels keeps only a band's integral rows; on a lattice many bands tall, with holes (invalid blocks), its
  // probabilities equal those of the whole integral image bit for bit, for the 8-neighbourhood and a wider window.
  const auto [p, valid] = randomLattice(700, 37, 9);
  const Compatibility r = kMixedCompatibility;
  for (const int R : {1, 3}) {
    RelaxationOptions o;
    o.max_iterations = 6;
    o.tolerance = 1e-12;
    o.neighbourhood_radius = R;
    cv::Mat a = p.clone(), b = p.clone();
    const auto res = relaxLabels(a, valid, r, o, 2);
    EXPECT_EQ(res.iterations, 6);
    relaxWithWholeIntegral(b, valid, r, R, 6);
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << "R = " << R;
    EXPECT_GT(cv::norm(a, p, cv::NORM_INF), 0.05) << "the relaxation must change the probabilities";
  }
}

namespace {
// A 240 x 160 cell building drawn over `cells` (its top-left 240 x 160 cells): a corridor along the top, two rooms
// below it with a door each onto it, a piece of furniture in the left room; walls elsewhere.
void drawRoomsAndCorridor(cv::Mat cells) {
  cells(cv::Rect(0, 0, 240, 160)).setTo(kOccupied);
  cells(cv::Rect(5, 5, 230, 30)).setTo(kFree);    // corridor
  cells(cv::Rect(5, 40, 110, 110)).setTo(kFree);  // two rooms below it, doors onto it
  cells(cv::Rect(120, 40, 115, 110)).setTo(kFree);
  cells(cv::Rect(40, 35, 18, 5)).setTo(kFree);
  cells(cv::Rect(160, 35, 18, 5)).setTo(kFree);
  cells(cv::Rect(60, 80, 10, 25)).setTo(kOccupied);
}
}  // namespace

TEST(Labelling, StripesOfTheLatticeGiveTheWholeLatticesProbabilities) {
  // classifyLattice takes the lattice a stripe of block rows at a time (labelPlaces: at most kStripeSamples): the
  // classifier's output is the same bits for stripes of one block row, of a few hundred samples and of the whole
  // lattice, with the shipped model, on rooms and a corridor with clutter.
  OccupancyImage occ;
  occ.resolution = 0.05;
  occ.cells = cv::Mat(160, 240, CV_8U);
  drawRoomsAndCorridor(occ.cells);
  occ.cells(cv::Rect(150, 60, 30, 4)).setTo(kUnknown);
  const PlacesModel model = PlacesModel::load(std::string(GRIDTOPO_DATA_DIR) + "/models/places_model.yml");
  const Lattice lat = buildLattice(occ, model.scan.lattice_spacing);
  const cv::Mat whole = classifyLattice(occ, lat, model, 2, lat.samples.size());
  ASSERT_EQ(whole.rows, static_cast<int>(lat.samples.size()));
  ASSERT_GT(latticeStripes(lat, 300).size(), 10u);
  for (const std::size_t stripe : {std::size_t(1), std::size_t(300)}) {
    const cv::Mat parts = classifyLattice(occ, lat, model, 2, stripe);
    ASSERT_EQ(parts.size(), whole.size());
    EXPECT_EQ(std::memcmp(parts.data, whole.data, whole.total() * whole.elemSize()), 0) << stripe;
  }
  // And the corridor is told from the rooms (the output is a classification, not noise).
  const cv::Vec3f corridor = whole.at<cv::Vec3f>(lat.block_sample.at<int>(10, 60));
  EXPECT_GT(corridor[1], corridor[0]);
}

TEST(Relaxation, ALatticeInALargeEmptyGridRelaxesAsAlone) {
  // relaxLabels works on the box of the valid blocks (widened by the neighbourhood): a lattice placed in a large
  // grid of invalid blocks relaxes bit for bit as the lattice alone (whole integral image), after an odd and an even
  // number of iterations (the last grid written is one or the other buffer), and the blocks outside stay as they are.
  const auto [p, valid] = randomLattice(90, 61, 21);
  const Compatibility r = kMixedCompatibility;
  const cv::Rect at(53, 301, p.cols, p.rows);
  for (const int R : {1, 3})
    for (const int iterations : {5, 6}) {
      RelaxationOptions o;
      o.max_iterations = iterations;
      o.tolerance = 1e-12;
      o.neighbourhood_radius = R;
      cv::Mat big(at.y + p.rows + 170, at.x + p.cols + 90, CV_32FC3, cv::Scalar(0.25f, 0.5f, 0.25f));
      cv::Mat big_valid(big.size(), CV_8U, cv::Scalar(0));
      p.copyTo(big(at));
      valid.copyTo(big_valid(at));
      const cv::Mat before = big.clone();
      const auto res = relaxLabels(big, big_valid, r, o, 2);
      EXPECT_EQ(res.iterations, iterations);
      cv::Mat alone = p.clone();
      relaxWithWholeIntegral(alone, valid, r, R, iterations);
      EXPECT_EQ(cv::norm(big(at), alone, cv::NORM_INF), 0.0) << "R = " << R << ", " << iterations << " iterations";
      big(at).setTo(cv::Scalar::all(0));
      cv::Mat outside = before.clone();
      outside(at).setTo(cv::Scalar::all(0));
      EXPECT_EQ(cv::norm(big, outside, cv::NORM_INF), 0.0);
      EXPECT_GT(cv::norm(alone, p, cv::NORM_INF), 0.05);
    }
}

TEST(Labelling, WithoutTheGridsTheLabelsAreTheSame) {
  // labelPlaces(…, keep_grids = false) (gridtopo-topology) relaxes a grid of only the part of the lattice that
  // relaxLabels relaxes (relaxationBox) and returns no grids: the cell labels are those of the whole grids', on a
  // building that fills a corner of a larger map (the part is then much smaller than the grid).
  OccupancyImage occ;
  occ.resolution = 0.05;
  occ.cells = cv::Mat(420, 530, CV_8U, cv::Scalar(kUnknown));
  drawRoomsAndCorridor(occ.cells(cv::Rect(263, 171, 240, 160)));
  const PlacesModel model = PlacesModel::load(std::string(GRIDTOPO_DATA_DIR) + "/models/places_model.yml");
  const LabellingResult with = labelPlaces(occ, model, RelaxationOptions(), 2, "<map>", {}, false, true, true);
  const LabellingResult without = labelPlaces(occ, model, RelaxationOptions(), 2, "<map>", {}, false, false, false);
  ASSERT_FALSE(with.probs.empty());
  EXPECT_TRUE(without.probs.empty() && without.valid.empty() && without.probs_initial.empty());
  const cv::Rect part = relaxationBox(cv::boundingRect(with.valid), with.valid.size(), RelaxationOptions());
  EXPECT_LT(part.area() * 3, with.valid.size().area());
  ASSERT_EQ(without.labels.size(), with.labels.size());
  EXPECT_EQ(cv::countNonZero(without.labels != with.labels), 0);
  EXPECT_EQ(without.relaxation.iterations, with.relaxation.iterations);
  EXPECT_GT(cv::countNonZero(with.labels == 1), 1000);  // a corridor was found: the labels are no constant
}
