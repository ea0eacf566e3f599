#include "gridtopo/topology/doorway_geometry.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "gridtopo/places/place_label.h"
#include "gridtopo/core/distance_transform.h"
#include "mask_ops.h"

namespace gridtopo::topology {

namespace {
constexpr unsigned char kRoom = 0, kCorridor = 1, kDoorway = 2;
}  // namespace

std::vector<CriticalLine> findDoorways(const cv::Mat& places, double resolution, const DoorwayGeometryOptions& o) {
  std::vector<CriticalLine> lines;
  if (places.empty()) return lines;
  // The box of the places with one cell of obstacle around it (the image's border is an obstacle too). Every cell
  // outside the box is an obstacle, and none is nearer to a place than the frame: the same distances, nearest
  // obstacles and lines as over the whole image, at a fraction of its memory on a large map (three int or float
  // images of it: the distances, the nearest obstacles and OpenCV's own buffer).
  const cv::Rect box = cv::boundingRect(places);
  if (box.empty()) return lines;
  cv::Mat free(box.height + 2, box.width + 2, CV_8U, cv::Scalar(0));  // written in place: no unframed copy
  cv::compare(places(box), 0, free(cv::Rect(1, 1, box.width, box.height)), cv::CMP_NE);
  // Every cell's nearest obstacle cell by exact Euclidean distance (nearestZero: one 4-byte image; its distance is
  // the norm of the offset). The chamfer distance of a 5 x 5 mask with OpenCV's pixel labels, used before, took a
  // float distance, a label image and OpenCV's own buffer of the box, and a table of every obstacle cell.
  const cv::Mat near_obstacle = nearestZero(free);
  const int cols = free.cols;
  const auto nearest = [&](int x, int y) {
    const int i = near_obstacle.at<int>(y, x);
    return cv::Point(i % cols, i / cols);
  };
  const auto distAt = [&](int x, int y) {  // the cell's clearance (0 at an obstacle)
    const cv::Point o = nearest(x, y);
    return static_cast<float>(std::hypot(double(o.x - x), double(o.y - y)));
  };
  const auto far = [](cv::Point p, cv::Point q) { return std::hypot(double(p.x - q.x), double(p.y - q.y)); };
  // The generalized Voronoi diagram: free cells whose nearest obstacle is far from a 4-neighbour's nearest
  // obstacle (the two lie on opposite sides of the free space).
  cv::Mat gvd = cv::Mat::zeros(free.size(), CV_8U);
  static const int dx4[] = {1, -1, 0, 0}, dy4[] = {0, 0, 1, -1};
  for (int y = 1; y + 1 < free.rows; ++y)
    for (int x = 1; x + 1 < free.cols; ++x) {
      if (!free.at<unsigned char>(y, x)) continue;
      const double d = distAt(x, y);
      const cv::Point op = nearest(x, y);
      for (int k = 0; k < 4; ++k) {
        const int qx = x + dx4[k], qy = y + dy4[k];
        if (!free.at<unsigned char>(qy, qx)) continue;
        if (far(op, nearest(qx, qy)) >= std::max(3.0, 1.5 * d)) {
          gvd.at<unsigned char>(y, x) = 255;
          break;
        }
      }
    }
  // Candidates: diagram cells whose critical line has a door's width and whose clearance is a local minimum of the
  // diagram around them (within the clearance plus a cell).
  struct Candidate {
    float d;
    int y, x;
    cv::Point a, b;
  };
  std::vector<Candidate> cand;
  for (int y = 1; y + 1 < free.rows; ++y)
    for (int x = 1; x + 1 < free.cols; ++x) {
      if (!gvd.at<unsigned char>(y, x)) continue;
      const float d = distAt(x, y);
      // The critical line: the nearest obstacle and the farthest-apart nearest obstacle of the 8 neighbours.
      const cv::Point a = nearest(x, y);
      cv::Point b = a;
      for (int yy = y - 1; yy <= y + 1; ++yy)
        for (int xx = x - 1; xx <= x + 1; ++xx)
          if (free.at<unsigned char>(yy, xx) && far(a, nearest(xx, yy)) > far(a, b)) b = nearest(xx, yy);
      const double width = (far(a, b) - 1.0) * resolution;
      if (width < o.min_width || width > o.max_width) continue;
      const int k = static_cast<int>(std::ceil(d)) + 1;
      bool minimum = true;
      for (int yy = std::max(0, y - k); yy <= std::min(free.rows - 1, y + k) && minimum; ++yy)
        for (int xx = std::max(0, x - k); xx <= std::min(free.cols - 1, x + k); ++xx)
          if (gvd.at<unsigned char>(yy, xx) && distAt(xx, yy) < d - 1e-3f) {
            minimum = false;
            break;
          }
      if (minimum) cand.push_back({d, y, x, a, b});
    }
  std::sort(cand.begin(), cand.end(),
            [](const Candidate& p, const Candidate& q) { return std::tie(p.d, p.y, p.x) < std::tie(q.d, q.y, q.x); });
  const double wider = o.wider_by / resolution;
  const int reach = static_cast<int>(std::ceil(o.reach / resolution));
  std::vector<Candidate> kept;
  for (const Candidate& c : cand) {
    bool near_kept = false;
    for (const Candidate& k : kept)
      if (std::hypot(double(k.x - c.x), double(k.y - c.y)) < far(k.a, k.b)) near_kept = true;
    if (near_kept) continue;
    // Both sides, along the normal of the line: the clearance grows to the half width plus `wider`.
    const double len = far(c.a, c.b);
    const double nx = -(c.b.y - c.a.y) / len, ny = (c.b.x - c.a.x) / len;
    bool wide_both = true;
    for (int s : {1, -1}) {
      double best = 0;
      for (int t = 1; t <= reach; ++t) {
        const int px = static_cast<int>(std::lround(c.x + s * t * nx)), py = static_cast<int>(std::lround(c.y + s * t * ny));
        if (px < 0 || py < 0 || px >= free.cols || py >= free.rows || !free.at<unsigned char>(py, px)) break;
        best = std::max(best, static_cast<double>(distAt(px, py)));
      }
      if (best < c.d + wider) wide_both = false;
    }
    if (!wide_both) continue;
    kept.push_back(c);
  }
  std::sort(kept.begin(), kept.end(),
            [](const Candidate& p, const Candidate& q) { return std::tie(p.y, p.x) < std::tie(q.y, q.x); });
  for (const Candidate& c : kept)
    lines.push_back({cv::Point2d(c.a.x - 1 + box.x, c.a.y - 1 + box.y), cv::Point2d(c.b.x - 1 + box.x, c.b.y - 1 + box.y),
                     cv::Point(c.x - 1 + box.x, c.y - 1 + box.y), (far(c.a, c.b) - 1.0) * resolution});
  return lines;
}

cv::Mat addGeometricDoorways(const cv::Mat& labels, double resolution, const DoorwayGeometryOptions& o,
                             std::vector<CriticalLine>* found) {
  if (!o.enabled) return labels.clone();
  const cv::Mat places = labels < places::kNumLabels;
  const std::vector<CriticalLine> lines = findDoorways(places, resolution, o);
  cv::Mat out = labels.clone();  // after the lines: one image less while their distance images exist
  cv::Mat drawn = cv::Mat::zeros(labels.size(), CV_8U);
  const int thickness = std::max(1, static_cast<int>(std::lround(o.depth / resolution)));
  for (const CriticalLine& l : lines)
    cv::line(drawn, cv::Point(static_cast<int>(std::lround(l.a.x)), static_cast<int>(std::lround(l.a.y))),
             cv::Point(static_cast<int>(std::lround(l.b.x)), static_cast<int>(std::lround(l.b.y))), cv::Scalar(255),
             thickness, cv::LINE_8);
  drawn &= places;
  out.setTo(kDoorway, drawn);
  if (o.refuse_unsupported) {
    // Classifier doorway regions that no critical line reaches (within the doorway's depth) take the label of the
    // room and corridor cells around them (grown into them breadth-first).
    cv::Mat near_line;
    const int r = std::max(1, static_cast<int>(std::lround(o.depth / resolution)));
    cv::dilate(drawn, near_line, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
    cv::Mat comp;
    const int n = cv::connectedComponents(out == kDoorway, comp, 8, CV_32S);
    std::vector<char> supported(static_cast<std::size_t>(n), 0);
    for (int y = 0; y < comp.rows; ++y)
      for (int x = 0; x < comp.cols; ++x)
        if (const int c = comp.at<int>(y, x); c > 0 && near_line.at<unsigned char>(y, x)) supported[c] = 1;
    cv::Mat refuse = cv::Mat::zeros(labels.size(), CV_8U);
    for (int y = 0; y < comp.rows; ++y)
      for (int x = 0; x < comp.cols; ++x)
        if (const int c = comp.at<int>(y, x); c > 0 && !supported[c]) refuse.at<unsigned char>(y, x) = 255;
    comp.release();  // before the seed image: two box-sized int images less at once on a large map
    cv::Mat ids = cv::Mat::zeros(labels.size(), CV_32S);
    ids.setTo(1 + kRoom, out == kRoom);
    ids.setTo(1 + kCorridor, out == kCorridor);
    growSeeds(ids, refuse);
    for (int y = 0; y < ids.rows; ++y)
      for (int x = 0; x < ids.cols; ++x)
        if (refuse.at<unsigned char>(y, x) && ids.at<int>(y, x) > 0)
          out.at<unsigned char>(y, x) = static_cast<unsigned char>(ids.at<int>(y, x) - 1);
  }
  if (found) *found = lines;
  return out;
}

}  // namespace gridtopo::topology
