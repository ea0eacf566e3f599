#include "gridtopo/topology/segmentation.h"

#include <deque>
#include <functional>

#include "gridtopo/places/place_label.h"

namespace gridtopo::topology {

namespace {
// Seeds: seg_of[region id - 1] > 0; grows them into the remaining labelled cells.
cv::Mat growSegments(const RegionMap& rm, const std::vector<int>& seg_of, int next) {
  cv::Mat seg(rm.ids.size(), CV_32S, cv::Scalar(0));
  std::deque<cv::Point> q;
  for (int y = 0; y < seg.rows; ++y)
    for (int x = 0; x < seg.cols; ++x) {
      const int id = rm.ids.at<int>(y, x);
      if (id > 0 && seg_of[static_cast<std::size_t>(id - 1)] > 0) {
        seg.at<int>(y, x) = seg_of[static_cast<std::size_t>(id - 1)];
        q.emplace_back(x, y);
      }
    }
  // Grow into doorway cells; only seeds that border a doorway cell ever expand.
  while (!q.empty()) {
    const cv::Point p = q.front();
    q.pop_front();
    const int s = seg.at<int>(p);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int yy = p.y + dy, xx = p.x + dx;
        if ((!dy && !dx) || yy < 0 || xx < 0 || yy >= seg.rows || xx >= seg.cols) continue;
        if (seg.at<int>(yy, xx) != 0) continue;
        const int id = rm.ids.at<int>(yy, xx);
        if (id <= 0) continue;
        seg.at<int>(yy, xx) = s;
        q.emplace_back(xx, yy);
      }
  }
  // Isolated doorway regions.
  std::vector<int> own(rm.regions.size(), 0);
  for (int y = 0; y < seg.rows; ++y)
    for (int x = 0; x < seg.cols; ++x) {
      const int id = rm.ids.at<int>(y, x);
      if (id <= 0 || seg.at<int>(y, x) != 0) continue;
      int& o = own[static_cast<std::size_t>(id - 1)];
      if (!o) o = ++next;
      seg.at<int>(y, x) = o;
    }
  return seg;
}
}  // namespace

cv::Mat roomSegmentation(const RegionMap& rm) {
  const int door = static_cast<int>(places::PlaceLabel::Doorway);
  std::vector<int> seg_of(rm.regions.size(), 0);
  int next = 0;
  for (const Region& r : rm.regions)
    if (r.label != door) seg_of[static_cast<std::size_t>(r.id - 1)] = ++next;
  return growSegments(rm, seg_of, next);
}

cv::Mat doorwaySegmentation(const RegionMap& rm) {
  const int door = static_cast<int>(places::PlaceLabel::Doorway);
  // Union of touching non-doorway regions.
  std::vector<int> parent(rm.regions.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  std::function<int(int)> find = [&](int i) { return parent[static_cast<std::size_t>(i)] == i ? i : parent[static_cast<std::size_t>(i)] = find(parent[static_cast<std::size_t>(i)]); };
  for (const auto& [k, len] : regionAdjacency(rm.ids)) {
    (void)len;
    if (rm.region(k.first).label == door || rm.region(k.second).label == door) continue;
    const int a = find(k.first - 1), b = find(k.second - 1);
    if (a != b) parent[static_cast<std::size_t>(a)] = b;
  }
  std::vector<int> seg_of(rm.regions.size(), 0), root_seg(rm.regions.size(), 0);
  int next = 0;
  for (const Region& r : rm.regions) {
    if (r.label == door) continue;
    int& s = root_seg[static_cast<std::size_t>(find(r.id - 1))];
    if (!s) s = ++next;
    seg_of[static_cast<std::size_t>(r.id - 1)] = s;
  }
  return growSegments(rm, seg_of, next);
}

int segmentCount(const cv::Mat& seg) {
  double mx = 0;
  cv::minMaxLoc(seg, nullptr, &mx);
  return static_cast<int>(mx);
}

}  // namespace gridtopo::topology
