#include "gridtopo/topology/regions.h"

#include <opencv2/imgproc.hpp>

#include "gridtopo/places/place_label.h"

namespace gridtopo::topology {

RegionMap extractRegions(const cv::Mat& labels, double resolution) {
  CV_Assert(labels.type() == CV_8U);
  RegionMap rm;
  rm.ids = cv::Mat(labels.size(), CV_32S, cv::Scalar(0));
  for (int l = 0; l < places::kNumLabels; ++l) {
    const cv::Mat mask = labels == l;
    cv::Mat cc, stats, cents;
    const int n = cv::connectedComponentsWithStats(mask, cc, stats, cents, 8, CV_32S);
    const int base = static_cast<int>(rm.regions.size());
    for (int k = 1; k < n; ++k) {
      Region r;
      r.id = base + k;
      r.label = l;
      r.cells = stats.at<int>(k, cv::CC_STAT_AREA);
      r.area_m2 = r.cells * resolution * resolution;
      r.centroid = cv::Point2d(cents.at<double>(k, 0), cents.at<double>(k, 1));
      r.bbox = cv::Rect(stats.at<int>(k, cv::CC_STAT_LEFT), stats.at<int>(k, cv::CC_STAT_TOP),
                        stats.at<int>(k, cv::CC_STAT_WIDTH), stats.at<int>(k, cv::CC_STAT_HEIGHT));
      rm.regions.push_back(r);
    }
    for (int y = 0; y < labels.rows; ++y) {
      const int* c = cc.ptr<int>(y);
      int* o = rm.ids.ptr<int>(y);
      for (int x = 0; x < labels.cols; ++x)
        if (c[x] > 0) o[x] = base + c[x];
    }
  }
  return rm;
}

std::map<std::pair<int, int>, int> regionAdjacency(const cv::Mat& ids) {
  std::map<std::pair<int, int>, int> adj;
  static const int d[4][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};  // half of the 8-neighbourhood
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x) {
      const int a = ids.at<int>(y, x);
      if (a <= 0) continue;
      for (const auto& o : d) {
        const int yy = y + o[0], xx = x + o[1];
        if (yy < 0 || xx < 0 || yy >= ids.rows || xx >= ids.cols) continue;
        const int b = ids.at<int>(yy, xx);
        if (b <= 0 || b == a) continue;
        adj[{std::min(a, b), std::max(a, b)}]++;
      }
    }
  return adj;
}

}  // namespace gridtopo::topology
