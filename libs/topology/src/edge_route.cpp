#include "gridtopo/topology/edge_route.h"
#include "gridtopo/core/distance_transform.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace gridtopo::topology {

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kUnreached = std::numeric_limits<int>::max();
constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};
constexpr double kSimplify = 1.0;        // cells
constexpr unsigned char kNoParent = 8;   // parent_ at an anchor and at unreached cells

// Every cell of the straight 8-connected line p -> q lies in region a or b.
bool lineInside(const cv::Mat& ids, cv::Point p, cv::Point q, int a, int b) {
  cv::LineIterator it(ids, p, q, 8);
  for (int i = 0; i < it.count; ++i, ++it) {
    const int v = ids.at<int>(it.pos());
    if (v != a && v != b) return false;
  }
  return true;
}

// Relative to a (differences of cells are exact): the same value wherever the cells lie in the image.
double distanceToSegment(cv::Point p, cv::Point a, cv::Point b) {
  const cv::Point2d d(b - a), q(p - a);
  const double l2 = d.dot(d);
  const double t = l2 > 0 ? std::clamp(q.dot(d) / l2, 0.0, 1.0) : 0.0;
  return std::hypot(q.x - t * d.x, q.y - t * d.y);
}

void simplify(const std::vector<cv::Point>& pts, std::size_t i, std::size_t j, const cv::Mat& ids, int a, int b,
              std::vector<cv::Point>& out) {
  // Appends pts[i + 1 .. j] (simplified); pts[i] is already in `out`.
  if (j <= i + 1) {
    if (j > i) out.push_back(pts[j]);
    return;
  }
  double worst = -1;
  std::size_t k = i + 1;
  for (std::size_t m = i + 1; m < j; ++m) {
    const double d = distanceToSegment(pts[m], pts[i], pts[j]);
    if (d > worst) worst = d, k = m;
  }
  if (worst <= kSimplify && lineInside(ids, pts[i], pts[j], a, b)) {
    out.push_back(pts[j]);
    return;
  }
  if (worst <= kSimplify) k = (i + j) / 2;  // close to straight but the chord touches a wall: split in the middle
  simplify(pts, i, k, ids, a, b, out);
  simplify(pts, k, j, ids, a, b, out);
}
}  // namespace

std::vector<cv::Point> regionAnchors(const RegionMap& rm, cv::Point offset, const std::vector<cv::Point2d>* centroids) {
  std::vector<cv::Point> anchors(rm.regions.size());
  for (const Region& r : rm.regions) {
    if (r.cells <= 0) continue;
    // Distances to the centroid in the map's frame (cell + offset), as on the whole map.
    const cv::Point2d centroid = centroids ? (*centroids)[static_cast<std::size_t>(r.id - 1)] : r.centroid;
    const cv::Rect roi = r.bbox;
    cv::Mat mask(roi.height + 2, roi.width + 2, CV_8U, cv::Scalar(0));
    cv::Mat(mask, cv::Rect(1, 1, roi.width, roi.height)).setTo(255, rm.ids(roi) == r.id);
    cv::Mat dist;
    dist = preciseDistance(mask);
    double deepest = 0;
    cv::minMaxLoc(dist, nullptr, &deepest);
    double best = kInf;
    cv::Point at;
    for (int y = 1; y <= roi.height; ++y)
      for (int x = 1; x <= roi.width; ++x) {
        if (!mask.at<unsigned char>(y, x) || dist.at<float>(y, x) < 0.5 * deepest) continue;
        const double dx = roi.x + x - 1 + offset.x - centroid.x, dy = roi.y + y - 1 + offset.y - centroid.y;
        const double d = dx * dx + dy * dy;
        if (d < best) best = d, at = cv::Point(roi.x + x - 1, roi.y + y - 1);
      }
    anchors[static_cast<std::size_t>(r.id - 1)] = at;
  }
  return anchors;
}

EdgeRouter::EdgeRouter(const RegionMap& rm, const std::vector<cv::Point>& anchors, double resolution)
    : rm_(rm) {
  // The box of the cells of every region, and each region's own box (from the image: a region's stored box is not
  // trusted here).
  const int n_ids = static_cast<int>(rm.regions.size());
  std::vector<cv::Rect> region_box(static_cast<std::size_t>(n_ids) + 1);
  int x0 = rm.ids.cols, y0 = rm.ids.rows, x1 = -1, y1 = -1;
  for (int y = 0; y < rm.ids.rows; ++y) {
    const int* row = rm.ids.ptr<int>(y);
    int first = -1, last = -1;
    for (int x = 0; x < rm.ids.cols; ++x)
      if (row[x] > 0) {
        if (first < 0) first = x;
        last = x;
        if (row[x] <= n_ids) {
          cv::Rect& b = region_box[static_cast<std::size_t>(row[x])];
          b = b.empty() ? cv::Rect(x, y, 1, 1) : (b | cv::Rect(x, y, 1, 1));
        }
      }
    if (first < 0) continue;
    x0 = std::min(x0, first), x1 = std::max(x1, last), y0 = std::min(y0, y), y1 = y;
  }
  if (x1 < 0) return;  // no region: no route
  box_ = cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
  const cv::Mat ids = rm.ids(box_);
  const cv::Point off = box_.tl();
  const double scale = kPathClearanceScale / resolution;  // cells
  // Step costs in 1/16 cell units (integers, so a bucket queue, Dial's algorithm, replaces the heap): a step into
  // a cell costs 16 (1 + (scale / clearance)^2), times sqrt(2) for a diagonal step.
  const auto costAt = [&](float clearance, bool diagonal) {
    const double q = scale / std::max(1.0f, clearance);
    return static_cast<int>(std::lround(16.0 * (diagonal ? M_SQRT2 : 1.0) * (1.0 + q * q)));
  };
  // Beyond `far` cells of clearance both costs are those of an infinite clearance (they only fall with it), so a
  // cell's clearance is only needed up to `far`: each region's is computed in its box widened by `far` cells.
  int far = 1;
  while (costAt(static_cast<float>(far), false) != costAt(std::numeric_limits<float>::max(), false) ||
         costAt(static_cast<float>(far), true) != costAt(std::numeric_limits<float>::max(), true))
    ++far;
  // The clearance is the distance to the nearest cell outside every region; outside the box no cell is in a region
  // (the original frame of empty cells around it). A cell whose nearest such cell is nearer than `far` finds it in
  // the widened box (or, beyond the box, a frame cell at least as near); one further away gets a clearance of at
  // least `far` there too, so its costs are the same.
  const cv::Rect framed(-1, -1, ids.cols + 2, ids.rows + 2);  // box coordinates
  parent_ = cv::Mat(ids.size(), CV_8U, cv::Scalar(kNoParent));
  // Each region's least-cost tree from its anchor (a cell is only entered from a cell of its own region, so the
  // trees are independent), in its own box; the costs of the cells at a border with another region are kept for
  // the joins. Buckets by cost modulo max_step + 1; within a bucket, first in first out, so results are fixed.
  std::unordered_map<long long, int> border_cost;  // box cell index -> cost (1/16 cells) from its region's anchor
  const auto index = [&](int y, int x) { return static_cast<long long>(y) * ids.cols + x; };
  std::vector<std::vector<int>> bucket;
  for (const Region& r : rm.regions) {
    if (r.cells <= 0 || r.id > n_ids) continue;
    const cv::Rect rb = region_box[static_cast<std::size_t>(r.id)] - off;  // box coordinates
    if (rb.empty()) continue;  // a region listed without cells in the image
    const cv::Point s = anchors[static_cast<std::size_t>(r.id - 1)] - off;
    if (!rb.contains(s)) continue;
    const cv::Rect wide = cv::Rect(rb.x - far, rb.y - far, rb.width + 2 * far, rb.height + 2 * far) & framed;
    cv::Mat clearance;
    {
      cv::Mat inside(wide.size(), CV_8U, cv::Scalar(0));
      const cv::Rect in_box = wide & cv::Rect(0, 0, ids.cols, ids.rows);
      cv::compare(ids(in_box), 0, inside(in_box - wide.tl()), cv::CMP_GT);
      clearance = preciseDistance(inside);
    }
    clearance = clearance(rb - wide.tl());  // the region's box
    const cv::Mat own = ids(rb);
    int max_step = 1;
    for (int y = 0; y < rb.height; ++y)
      for (int x = 0; x < rb.width; ++x)
        if (own.at<int>(y, x) == r.id) max_step = std::max(max_step, costAt(clearance.at<float>(y, x), true));
    // A cell is tried from up to eight neighbours: when both of its costs fit in 16 bits (always at 5 cm: at most
    // 16 sqrt(2) (1 + 14^2) = 4458), they are computed once and written over the cell's clearance.
    const bool packed = max_step <= 0xffff;
    if (packed)
      for (int y = 0; y < rb.height; ++y)
        for (int x = 0; x < rb.width; ++x)
          if (own.at<int>(y, x) == r.id) {
            const float c = clearance.at<float>(y, x);
            const std::uint32_t both = static_cast<std::uint32_t>(costAt(c, false)) |
                                       (static_cast<std::uint32_t>(costAt(c, true)) << 16);
            std::memcpy(clearance.ptr<float>(y) + x, &both, sizeof both);
          }
    const auto step = [&](int y, int x, bool diagonal) {
      if (!packed) return costAt(clearance.at<float>(y, x), diagonal);
      std::uint32_t both;
      std::memcpy(&both, clearance.ptr<float>(y) + x, sizeof both);
      return static_cast<int>(diagonal ? both >> 16 : both & 0xffff);
    };
    cv::Mat cost(rb.size(), CV_32S, cv::Scalar(kUnreached));  // region box coordinates
    cv::Mat parent = parent_(rb);
    bucket.assign(static_cast<std::size_t>(max_step) + 1, {});
    const cv::Point s_local = s - rb.tl();
    cost.at<int>(s_local) = 0;
    bucket[0].push_back(s_local.y * rb.width + s_local.x);
    std::size_t queued = 1;
    for (long long c = 0; queued > 0; ++c) {
      auto& b = bucket[static_cast<std::size_t>(c % (max_step + 1))];
      for (std::size_t h = 0; h < b.size(); ++h) {  // steps cost 16..max_step: nothing is added to b meanwhile
        const int i = b[h];
        const int y = i / rb.width, x = i % rb.width;
        if (cost.at<int>(y, x) != c) continue;  // stale entry
        for (int k = 0; k < 8; ++k) {
          const int yy = y + kDy[k], xx = x + kDx[k];
          if (yy < 0 || xx < 0 || yy >= rb.height || xx >= rb.width || own.at<int>(yy, xx) != r.id) continue;
          const long long nc = c + step(yy, xx, k % 2 != 0);
          if (nc < cost.at<int>(yy, xx)) {
            cost.at<int>(yy, xx) = static_cast<int>(nc);
            parent.at<unsigned char>(yy, xx) = static_cast<unsigned char>((k + 4) % 8);  // the step back to (y, x)
            bucket[static_cast<std::size_t>(nc % (max_step + 1))].push_back(yy * rb.width + xx);
            ++queued;
          }
        }
      }
      queued -= b.size();
      b.clear();
    }
    // The reached cells of the region next to a cell of another region.
    for (int y = 0; y < rb.height; ++y)
      for (int x = 0; x < rb.width; ++x) {
        if (own.at<int>(y, x) != r.id || cost.at<int>(y, x) == kUnreached) continue;
        const int by = y + rb.y, bx = x + rb.x;
        bool border = false;
        for (int k = 0; k < 8 && !border; ++k) {
          const int yy = by + kDy[k], xx = bx + kDx[k];
          if (yy < 0 || xx < 0 || yy >= ids.rows || xx >= ids.cols) continue;
          const int v = ids.at<int>(yy, xx);
          border = v > 0 && v != r.id;
        }
        if (border) border_cost.emplace(index(by, bx), cost.at<int>(y, x));
      }
  }
  // For every pair of touching regions, the border cell pair with the least total cost (one pass over the image,
  // half of the 8-neighbourhood; the first such pair in row-major order wins ties).
  static const int half[4][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};  // (dy, dx)
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x) {
      const int a = ids.at<int>(y, x);
      if (a <= 0) continue;
      const int* cost_a = nullptr;
      for (const auto& o : half) {
        const int yy = y + o[0], xx = x + o[1];
        if (yy < 0 || xx < 0 || yy >= ids.rows || xx >= ids.cols) continue;
        const int b = ids.at<int>(yy, xx);
        if (b <= 0 || b == a) continue;
        if (!cost_a) {
          const auto found = border_cost.find(index(y, x));
          if (found == border_cost.end()) break;  // a unreached
          cost_a = &found->second;
        }
        const auto found_b = border_cost.find(index(yy, xx));
        if (found_b == border_cost.end()) continue;  // b unreached
        const double c = static_cast<double>(*cost_a) + found_b->second;
        const cv::Point p = cv::Point(x, y) + off, q = cv::Point(xx, yy) + off;
        const auto key = std::make_pair(std::min(a, b), std::max(a, b));
        auto it = joins_.find(key);
        if (it == joins_.end() || c < std::get<0>(it->second))
          joins_[key] = a < b ? std::make_tuple(c, p, q) : std::make_tuple(c, q, p);
      }
    }
}

std::vector<cv::Point> EdgeRouter::route(int a, int b) const {
  const cv::Mat& ids = rm_.ids;
  const auto found = joins_.find({std::min(a, b), std::max(a, b)});
  if (found == joins_.end()) return {};
  const cv::Point lo = std::get<1>(found->second), hi = std::get<2>(found->second);  // cells in min(a, b), max(a, b)
  const cv::Point bp = a < b ? lo : hi, bq = a < b ? hi : lo;
  std::vector<cv::Point> half_a, half_b;
  const cv::Point off = box_.tl();
  const auto walk = [&](cv::Point p, std::vector<cv::Point>& out) {
    for (;;) {
      out.push_back(p);
      const int k = parent_.at<unsigned char>(p - off);
      if (k == kNoParent) break;
      p += cv::Point(kDx[k], kDy[k]);
    }
  };
  walk(bp, half_a);
  walk(bq, half_b);
  std::vector<cv::Point> full(half_a.rbegin(), half_a.rend());
  full.insert(full.end(), half_b.begin(), half_b.end());
  std::vector<cv::Point> out{full.front()};
  simplify(full, 0, full.size() - 1, ids, a, b, out);
  return out;
}

}  // namespace gridtopo::topology
