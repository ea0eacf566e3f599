// The library-internal mask operations (libs/topology/src/mask_ops.h): RunComponents finds OpenCV's connected
// components from runs, and fillSmallHoles built on it fills what the component-image version filled.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <map>
#include <vector>

#include "../../libs/topology/src/mask_ops.h"

using namespace gridtopo::topology;

namespace {
cv::Mat randomMask(cv::RNG& rng, int rows, int cols, double density) {
  cv::Mat m(rows, cols, CV_8U);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) m.at<unsigned char>(y, x) = rng.uniform(0.0, 1.0) < density ? 255 : 0;
  return m;
}

// The fillSmallHoles of before RunComponents: one cv::connectedComponentsWithStats of the zero cells.
cv::Mat fillSmallHolesWithComponentImage(const cv::Mat& mask, double max_cells, const cv::Mat& veto) {
  cv::Mat cc, stats, cent;
  const int n = cv::connectedComponentsWithStats(mask == 0, cc, stats, cent, 4, CV_32S);
  std::vector<unsigned char> fill(static_cast<std::size_t>(n), 0);
  for (int c = 1; c < n; ++c) fill[static_cast<std::size_t>(c)] = stats.at<int>(c, cv::CC_STAT_AREA) <= max_cells;
  for (int y = 0; y < cc.rows; ++y)
    for (int x = 0; x < cc.cols; ++x) {
      const int c = cc.at<int>(y, x);
      const bool border = y == 0 || x == 0 || y == cc.rows - 1 || x == cc.cols - 1;
      if (c && (border || (!veto.empty() && veto.at<unsigned char>(y, x)))) fill[static_cast<std::size_t>(c)] = 0;
    }
  cv::Mat out = mask.clone();
  for (int y = 0; y < cc.rows; ++y)
    for (int x = 0; x < cc.cols; ++x)
      if (fill[static_cast<std::size_t>(cc.at<int>(y, x))]) out.at<unsigned char>(y, x) = 255;
  return out;
}
}  // namespace

TEST(MaskOps, RunComponentsAreOpenCVsComponents) {
  cv::RNG rng(3);
  for (int trial = 0; trial < 40; ++trial) {
    const cv::Mat mask = randomMask(rng, 1 + rng.uniform(0, 70), 1 + rng.uniform(0, 90), 0.3 + 0.4 * rng.uniform(0.0, 1.0));
    for (const bool nonzero : {true, false})
      for (const int connectivity : {4, 8}) {
        const cv::Mat cells = nonzero ? mask != 0 : mask == 0;
        cv::Mat cc, stats, cent;
        const int n = cv::connectedComponentsWithStats(cells, cc, stats, cent, connectivity, CV_32S);
        const RunComponents runs(mask, nonzero, connectivity);
        EXPECT_EQ(runs.componentsOfAtLeast(1), static_cast<std::size_t>(n - 1));
        // Every run's cells lie in one OpenCV component, one per root, of the root's area.
        std::map<int, int> component_of_root;
        std::size_t i = 0;
        forEachRun(mask, nonzero, [&](int y, int x0, int x1) {
          const int root = runs.root[i++];
          for (int x = x0; x <= x1; ++x) {
            const int c = cc.at<int>(y, x);
            ASSERT_GT(c, 0);
            const auto [it, fresh] = component_of_root.emplace(root, c);
            ASSERT_EQ(it->second, c) << "trial " << trial;
            (void)fresh;
          }
          ASSERT_EQ(runs.area[static_cast<std::size_t>(root)], stats.at<int>(component_of_root[root], cv::CC_STAT_AREA));
        });
        EXPECT_EQ(component_of_root.size(), static_cast<std::size_t>(n - 1));
      }
  }
}

// rootsInBlockOrder numbers the components as cv::connectedComponents does (8-connected): the neck split and the
// corridor pieces number their parts by it instead of an image of component numbers. Small random masks, and large
// ones where OpenCV labels stripes on several threads.
TEST(MaskOps, RootsInBlockOrderNumberTheComponentsAsOpenCV) {
  cv::RNG rng(11);
  for (int trial = 0; trial < 44; ++trial) {
    const bool large = trial >= 40;
    const int rows = large ? 1500 + rng.uniform(0, 300) : 1 + rng.uniform(0, 70);
    const int cols = large ? 1200 + rng.uniform(0, 300) : 1 + rng.uniform(0, 90);
    const cv::Mat mask = randomMask(rng, rows, cols, 0.3 + 0.4 * rng.uniform(0.0, 1.0)) != 0;
    {
      cv::Mat cc;
      const int n = cv::connectedComponents(mask, cc, 8, CV_32S);
      const RunComponents comps(mask, true, 8);
      const std::vector<int> roots = rootsInBlockOrder(mask, comps);
      ASSERT_EQ(roots.size(), static_cast<std::size_t>(n - 1));
      std::vector<int> number(comps.root.size(), 0);
      for (std::size_t k = 0; k < roots.size(); ++k) number[static_cast<std::size_t>(roots[k])] = static_cast<int>(k) + 1;
      std::size_t i = 0;
      forEachRun(mask, true, [&](int y, int x0, int x1) {
        const int id = number[static_cast<std::size_t>(comps.root[i++])];
        for (int x = x0; x <= x1; ++x) ASSERT_EQ(cc.at<int>(y, x), id) << "trial " << trial << " at " << x << "," << y;
      });
    }
  }
}

// The fill in place with a veto of another type covering a part of the mask (S1's enclosed obstacles: the
// segmentation inside the mask's one-cell frame) fills what fillSmallHoles fills with the same veto as a mask.
TEST(MaskOps, FillSmallHolesInPlaceTakesAVetoOfAnyTypeAtAnOffset) {
  cv::RNG rng(9);
  for (int trial = 0; trial < 30; ++trial) {
    const int rows = 3 + rng.uniform(0, 60), cols = 3 + rng.uniform(0, 80);
    const cv::Mat mask = randomMask(rng, rows, cols, 0.6 + 0.3 * rng.uniform(0.0, 1.0));
    cv::Mat veto_ids(rows - 2, cols - 2, trial % 2 ? CV_16U : CV_32S, cv::Scalar(0));
    for (int k = 0; k < 3; ++k)  // a few cells of other segments
      veto_ids(cv::Rect(rng.uniform(0, cols - 2), rng.uniform(0, rows - 2), 1, 1)).setTo(cv::Scalar(1 + rng.uniform(0, 65535)));
    cv::Mat veto(mask.size(), CV_8U, cv::Scalar(0));
    cv::compare(veto_ids, 0, veto(cv::Rect(1, 1, cols - 2, rows - 2)), cv::CMP_NE);
    const double max_cells = rng.uniform(1, 40);
    const cv::Mat expected = fillSmallHoles(mask, max_cells, veto);
    cv::Mat in_place = mask.clone();
    fillSmallHolesInPlace(in_place, max_cells, veto_ids, {1, 1});
    EXPECT_EQ(cv::countNonZero(in_place != expected), 0) << "trial " << trial;
    cv::Mat plain = mask.clone();
    fillSmallHolesInPlace(plain, max_cells);
    EXPECT_EQ(cv::countNonZero(plain != fillSmallHoles(mask, max_cells)), 0) << "trial " << trial;
  }
}

TEST(MaskOps, FillSmallHolesFillsWhatTheComponentImageFilled) {
  cv::RNG rng(8);
  for (int trial = 0; trial < 40; ++trial) {
    const int rows = 2 + rng.uniform(0, 80), cols = 2 + rng.uniform(0, 80);
    const cv::Mat mask = randomMask(rng, rows, cols, 0.55 + 0.3 * rng.uniform(0.0, 1.0));
    const cv::Mat veto = trial % 2 ? randomMask(rng, rows, cols, 0.02) : cv::Mat();
    for (const double max_cells : {0.0, 1.0, 3.0, 12.5, 1e9}) {
      const cv::Mat got = fillSmallHoles(mask, max_cells, veto);
      const cv::Mat expected = fillSmallHolesWithComponentImage(mask, max_cells, veto);
      ASSERT_EQ(cv::countNonZero(got != expected), 0) << "trial " << trial << ", max " << max_cells;
    }
  }
  // A hole touching the border is none; a closed one is filled up to its size.
  cv::Mat ring(7, 7, CV_8U, cv::Scalar(255));
  ring(cv::Rect(2, 2, 3, 3)).setTo(0);
  ring.at<unsigned char>(0, 0) = 0;
  const cv::Mat filled = fillSmallHoles(ring, 9);
  EXPECT_EQ(cv::countNonZero(filled), 48);
  EXPECT_EQ(cv::countNonZero(fillSmallHoles(ring, 8)), 39);
}
