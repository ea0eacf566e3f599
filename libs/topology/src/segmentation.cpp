#include "gridtopo/topology/segmentation.h"

#include <opencv2/imgproc.hpp>
#include <algorithm>
#include <functional>
#include <vector>

#include "gridtopo/places/place_label.h"
#include "gridtopo/core/distance_transform.h"
#include "mask_ops.h"

namespace gridtopo::topology {

namespace {
// Seeds: seg_of[region id - 1] > 0; grows them into the remaining labelled cells. Ids of type T.
template <class T>
void growSegmentsInto(cv::Mat& seg, const RegionMap& rm, const std::vector<int>& seg_of, int next) {
  for (int y = 0; y < seg.rows; ++y) {
    const int* ids = rm.ids.ptr<int>(y);
    T* out = seg.ptr<T>(y);
    for (int x = 0; x < seg.cols; ++x) {
      const int id = ids[x];
      if (id > 0 && seg_of[static_cast<std::size_t>(id - 1)] > 0)
        out[x] = static_cast<T>(seg_of[static_cast<std::size_t>(id - 1)]);
    }
  }
  // Grow into doorway cells; only seeds that border a doorway cell ever expand.
  growSeeds(seg, rm.ids > 0);
  // Isolated doorway regions.
  std::vector<int> own(rm.regions.size(), 0);
  for (int y = 0; y < seg.rows; ++y) {
    const int* ids = rm.ids.ptr<int>(y);
    T* out = seg.ptr<T>(y);
    for (int x = 0; x < seg.cols; ++x) {
      const int id = ids[x];
      if (id <= 0 || out[x] != 0) continue;
      int& o = own[static_cast<std::size_t>(id - 1)];
      if (!o) o = ++next;
      out[x] = static_cast<T>(o);
    }
  }
}

// The segmentation image: CV_16U when asked and every id fits (the `next` seeded segments and at most one per
// region for the isolated doorways), else CV_32S.
cv::Mat growSegments(const RegionMap& rm, const std::vector<int>& seg_of, int next, bool sixteen_bits) {
  const bool narrow = sixteen_bits && static_cast<long long>(next) + static_cast<long long>(rm.regions.size()) <= 65535;
  cv::Mat seg(rm.ids.size(), narrow ? CV_16U : CV_32S, cv::Scalar(0));
  if (narrow) growSegmentsInto<unsigned short>(seg, rm, seg_of, next);
  else growSegmentsInto<int>(seg, rm, seg_of, next);
  return seg;
}

// `mask`: a segment's cells in a crop with a one-cell empty frame; `seg_crop`: the segmentation in the crop
// (without the frame). Adds to the mask every 4-connected component of non-segment cells that does not reach the
// frame, holds no cell of another segment (only non-free or unlabelled cells) and is at most `max_px` cells:
// obstacles enclosed by the segment.
void addEnclosedObstacles(cv::Mat& mask, const cv::Mat& seg_crop, double max_px) {
  fillSmallHolesInPlace(mask, max_px, seg_crop, {1, 1});  // cells of other segments veto a hole
}
}  // namespace

cv::Mat roomSegmentation(const RegionMap& rm) { return roomSegmentation(rm, 0.0, 1.0); }

cv::Mat roomSegmentation(const RegionMap& rm, double merge_contact_m, double resolution, bool sixteen_bits) {
  const int door = static_cast<int>(places::PlaceLabel::Doorway);
  std::vector<int> parent(rm.regions.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  std::function<int(int)> find = [&](int i) { return parent[static_cast<std::size_t>(i)] == i ? i : parent[static_cast<std::size_t>(i)] = find(parent[static_cast<std::size_t>(i)]); };
  if (merge_contact_m > 0) {
    const double min_pairs = 3.0 * merge_contact_m / resolution;
    for (const auto& [k, len] : regionAdjacency(rm.ids)) {
      const int la = rm.region(k.first).label, lb = rm.region(k.second).label;
      if (la == door || lb == door || la == lb || len <= min_pairs) continue;
      const int a = find(k.first - 1), b = find(k.second - 1);
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  }
  std::vector<int> seg_of(rm.regions.size(), 0), root_seg(rm.regions.size(), 0);
  int next = 0;
  for (const Region& r : rm.regions) {
    if (r.label == door) continue;
    int& s = root_seg[static_cast<std::size_t>(find(r.id - 1))];
    if (!s) s = ++next;
    seg_of[static_cast<std::size_t>(r.id - 1)] = s;
  }
  return growSegments(rm, seg_of, next, sixteen_bits);
}

cv::Mat doorwaySegmentation(const RegionMap& rm, bool sixteen_bits) {
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
  return growSegments(rm, seg_of, next, sixteen_bits);
}

cv::Mat splitAtNecks(const cv::Mat& seg_in, double resolution, const SegmentationRules& o) {
  CV_Assert(seg_in.type() == CV_32S || seg_in.type() == CV_16U);
  cv::Mat seg = seg_in.clone();
  splitAtNecksInPlace(seg, resolution, o);
  return seg;
}

void splitAtNecksInPlace(cv::Mat& seg, double resolution, const SegmentationRules& o) {
  CV_Assert(seg.type() == CV_32S || seg.type() == CV_16U);
  if (o.neck_width <= 0) return;
  const int K = segmentCount(seg);
  // Bounding boxes of the segments.
  std::vector<cv::Rect> box(static_cast<std::size_t>(K) + 1);
  std::vector<int> x0(box.size(), seg.cols), y0(box.size(), seg.rows), x1(box.size(), -1), y1(box.size(), -1);
  for (int y = 0; y < seg.rows; ++y)
    for (int x = 0; x < seg.cols; ++x) {
      const int s = idAt(seg, y, x);
      if (s <= 0) continue;
      const auto i = static_cast<std::size_t>(s);
      x0[i] = std::min(x0[i], x), y0[i] = std::min(y0[i], y), x1[i] = std::max(x1[i], x), y1[i] = std::max(y1[i], y);
    }
  const double half_px = 0.5 * o.neck_width / resolution;
  const double min_part_px = o.min_part_area / (resolution * resolution);
  const double fill_px = o.fill_obstacle_area / (resolution * resolution);
  int next = K;
  for (int s = 1; s <= K; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (x1[i] < 0) continue;
    const cv::Rect r(x0[i], y0[i], x1[i] - x0[i] + 1, y1[i] - y0[i] + 1);
    // Mask of the segment with a one-cell empty frame, so the border of the crop counts as outside.
    cv::Mat mask(r.height + 2, r.width + 2, CV_8U, cv::Scalar(0));
    cv::Mat inner = mask(cv::Rect(1, 1, r.width, r.height));
    cv::compare(seg(r), s, inner, cv::CMP_EQ);
    if (cv::countNonZero(inner) < 2 * min_part_px) continue;
    // `area`: the segment plus the obstacles it encloses (furniture standing in the room), so that the distance
    // transform measures the room's walls, not the gaps between chairs.
    inner.release();  // (the segment's cells are read from `seg` again at the end)
    if (fill_px > 0) addEnclosedObstacles(mask, seg(r), fill_px);
    cv::Mat area = std::move(mask);
    // One segment can span most of a large map (the hospital's corridors: a box of 8 000 × 4 500 cells), so its
    // crop-sized images are let go as soon as they are used, and the parts are found from the core's runs
    // (RunComponents) rather than as an image of component numbers.
    cv::Mat core = withinDistance(area, half_px);  // preciseDistance(area) > half_px, without its floats:
    cv::bitwise_not(core, core);
    const RunComponents comps(core, true, 8);
    // Fewer than two large parts (most segments): nothing to split.
    if (comps.componentsOfAtLeast(min_part_px) < 2) continue;
    // The large parts in the order of their first 2 x 2 block: the numbering of cv::connectedComponents, which
    // orders the new segments. The first keeps the segment's id.
    std::vector<int> part_id(comps.root.size(), 0);
    int parts = 0;
    for (const int c : rootsInBlockOrder(core, comps))
      if (comps.area[static_cast<std::size_t>(c)] >= min_part_px)
        part_id[static_cast<std::size_t>(c)] = parts++ == 0 ? s : ++next;
    // Seeds: the large parts; grow them over the segment's cells in the crop (label image `own`, 0 = not yet), in
    // 16 bits while the ids fit.
    if (next > 65535 && seg.type() == CV_16U) seg.convertTo(seg, CV_32S);  // the new ids no longer fit 16 bits
    cv::Mat own(core.size(), next <= 65535 ? CV_16U : CV_32S, cv::Scalar(0));
    std::size_t run = 0;
    forEachRun(core, true, [&](int y, int x0, int x1) {
      const int id = part_id[static_cast<std::size_t>(comps.root[run++])];
      if (id) setIds(own, y, x0, x1, id);
    });
    core.release();
    growSeeds(own, area);
    area.release();
    for (int y = 0; y < r.height; ++y)
      for (int x = 0; x < r.width; ++x) {
        const int id = idAt(own, y + 1, x + 1);
        if (id && idAt(seg, r.y + y, r.x + x) == s) setIds(seg, r.y + y, r.x + x, r.x + x, id);
      }
  }
}

cv::Mat voteLabelsInSegments(const cv::Mat& labels, const cv::Mat& seg) {
  CV_Assert(labels.type() == CV_8U && seg.type() == CV_32S && labels.size() == seg.size());
  const int room = static_cast<int>(places::PlaceLabel::Room), corr = static_cast<int>(places::PlaceLabel::Corridor);
  std::vector<long long> n_room(static_cast<std::size_t>(segmentCount(seg)) + 1, 0), n_corr(n_room.size(), 0);
  for (int y = 0; y < seg.rows; ++y)
    for (int x = 0; x < seg.cols; ++x) {
      const int s = seg.at<int>(y, x), l = labels.at<unsigned char>(y, x);
      if (s <= 0) continue;
      if (l == room) ++n_room[static_cast<std::size_t>(s)];
      else if (l == corr) ++n_corr[static_cast<std::size_t>(s)];
    }
  cv::Mat out = labels.clone();
  for (int y = 0; y < seg.rows; ++y)
    for (int x = 0; x < seg.cols; ++x) {
      const int s = seg.at<int>(y, x);
      unsigned char& l = out.at<unsigned char>(y, x);
      if (s <= 0 || (l != room && l != corr)) continue;
      const auto i = static_cast<std::size_t>(s);
      l = static_cast<unsigned char>(n_corr[i] > n_room[i] ? corr : room);
    }
  return out;
}

int segmentCount(const cv::Mat& seg) {
  double mx = 0;
  cv::minMaxLoc(seg, nullptr, &mx);
  return static_cast<int>(mx);
}

}  // namespace gridtopo::topology
