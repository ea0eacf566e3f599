#include "gridtopo/topology/corridor_split.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "gridtopo/places/place_label.h"
#include "gridtopo/core/distance_transform.h"
#include "mask_ops.h"
#include "region_merge.h"

namespace gridtopo::topology {

namespace {
constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};

// Crossing number: 0 -> 1 transitions around the 8-neighbourhood in circular order (1 = dead end, >= 3 = junction).
int crossings(const cv::Mat& sk, int y, int x) {
  int c = 0;
  for (int k = 0; k < 8; ++k)
    c += sk.at<unsigned char>(y + kDy[k], x + kDx[k]) == 0 && sk.at<unsigned char>(y + kDy[(k + 1) % 8], x + kDx[(k + 1) % 8]) != 0;
  return c;
}

// Splits one corridor region (mask with a one-cell zero border) into pieces: CV_16U or CV_32S, 1..K inside the mask,
// 0 outside.
// Returns K (1 when the region has no junction).
// `pieces` stays empty when the region is one piece (no image of it).
int splitOne(const cv::Mat& mask, double resolution, const CorridorSplitOptions& o, cv::Mat& pieces) {
  pieces.release();
  // The skeleton is traced on a lattice of about 0.1 m (thinning costs grow with area and width), then carried
  // back to the map's cells.
  const int f = std::max(1, static_cast<int>(std::lround(0.1 / resolution)));
  // Small holes (pillars, furniture, islands of another label) would make loops in the skeleton, and every loop
  // two junctions: they are filled for tracing the skeleton (the pieces still cover only the region's cells). The
  // coarse lattice is filled again: thin parts of the region can open new holes there.
  cv::Mat filled = fillSmallHoles(mask, o.max_hole_area / (resolution * resolution));
  cv::Mat small_mask = filled;
  if (f > 1) {
    cv::resize(filled, small_mask, cv::Size((mask.cols + f - 1) / f, (mask.rows + f - 1) / f), 0, 0, cv::INTER_AREA);
    small_mask = fillSmallHoles(small_mask > 127, o.max_hole_area / (resolution * resolution * f * f));
    cv::copyMakeBorder(small_mask, small_mask, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  }
  const int pad = f > 1 ? 1 : 0;  // the small lattice has its own one-cell zero border
  auto toFull = [&](int x, int y) { return cv::Point((x - pad) * f + f / 2, (y - pad) * f + f / 2); };
  cv::Mat sk;
  sk = thinZhangSuen(small_mask);
  // The distance to the wall is read at the skeleton's points only (preciseDistanceAt: no float image of the
  // region's box, which for a corridor spanning a large map is hundreds of MB).
  const auto dist = [&](cv::Point p) { return preciseDistanceAt(filled, p); };
  // Prune: remove dead-end pixels (min_branch + the corridor's half-width) times, the half-width being the median
  // distance to the wall along the skeleton: a side branch must reach min_branch beyond the corridor's wall to
  // survive (a recess or a bump of the wall makes a skeleton spur as long as the half-width plus its depth). Longer
  // branches lose that much length, which does not move the junctions. Dead ends are found once; afterwards only the
  // neighbours of removed pixels can become dead ends.
  std::vector<float> half_widths;
  for (int y = 1; y < sk.rows - 1; ++y)
    for (int x = 1; x < sk.cols - 1; ++x)
      if (sk.at<unsigned char>(y, x)) {
        const cv::Point p = toFull(x, y);
        if (p.x < mask.cols && p.y < mask.rows) half_widths.push_back(dist(p));
      }
  float half_width = 0;
  if (!half_widths.empty()) {
    std::nth_element(half_widths.begin(), half_widths.begin() + half_widths.size() / 2, half_widths.end());
    half_width = half_widths[half_widths.size() / 2];
  }
  const int prune = static_cast<int>(std::lround((o.min_branch / resolution + half_width) / f));
  std::vector<cv::Point> ends, next;
  for (int y = 1; y < sk.rows - 1; ++y)
    for (int x = 1; x < sk.cols - 1; ++x)
      if (sk.at<unsigned char>(y, x) && crossings(sk, y, x) <= 1) ends.emplace_back(x, y);
  for (int it = 0; it < prune && !ends.empty(); ++it) {
    for (const auto& p : ends) sk.at<unsigned char>(p) = 0;
    next.clear();
    for (const auto& p : ends)
      for (int k = 0; k < 8; ++k) {
        const cv::Point q(p.x + kDx[k], p.y + kDy[k]);
        if (sk.at<unsigned char>(q) == 255 && crossings(sk, q.y, q.x) <= 1) {
          sk.at<unsigned char>(q) = 254;  // queued once
          next.push_back(q);
        }
      }
    ends.swap(next);
  }
  // Junction zones: a disc of the local half-width (+1 cell) around every skeleton point with >= 3 branches.
  cv::Mat zone(mask.size(), CV_8U, cv::Scalar(0)), small_zone(sk.size(), CV_8U, cv::Scalar(0));
  int junctions = 0;
  for (int y = 1; y < sk.rows - 1; ++y)
    for (int x = 1; x < sk.cols - 1; ++x)
      if (sk.at<unsigned char>(y, x) && crossings(sk, y, x) >= 3) {
        cv::Point p = toFull(x, y);
        p.x = std::min(p.x, mask.cols - 1), p.y = std::min(p.y, mask.rows - 1);
        const double r = dist(p) + f;
        cv::circle(zone, p, static_cast<int>(std::ceil(r)), cv::Scalar(255), cv::FILLED);
        cv::circle(small_zone, {x, y}, static_cast<int>(std::ceil(r / f)), cv::Scalar(255), cv::FILLED);
        ++junctions;
      }
  filled.release();  // on a corridor spanning a large map each of these ROI images is tens of MB: let go early
  if (!junctions) return 1;
  zone &= mask;
  // Seeds: the skeleton's branches outside the junction zones (on the coarse lattice), and the junction zones
  // (8-connected components) numbered straight into the pieces' image: 16-bit labels when every piece fits (half
  // the memory of a region's box; zones are at most as many as junction points), else 32-bit. Both are found from
  // their runs (RunComponents) and numbered as cv::connectedComponents would (rootsInBlockOrder): no image of
  // component numbers.
  const cv::Mat branches = sk & ~small_zone;
  const RunComponents branch_comps(branches, true, 8);
  int nb = 0;
  const std::vector<int> branch_id = numbersInBlockOrder(branches, branch_comps, nb);
  const bool narrow = static_cast<long long>(junctions) + nb < 0xffff;
  // The zones' runs with their numbers are kept and the zone image let go before the pieces' image exists.
  int nz = 0;
  struct ZoneRun {
    int y, x0, x1, id;
  };
  std::vector<ZoneRun> zone_runs;
  {
    const RunComponents zone_comps(zone, true, 8);
    const std::vector<int> zone_id = numbersInBlockOrder(zone, zone_comps, nz);
    zone_runs.reserve(zone_comps.root.size());
    std::size_t run = 0;
    forEachRun(zone, true, [&](int y, int x0, int x1) {
      zone_runs.push_back({y, x0, x1, zone_id[static_cast<std::size_t>(zone_comps.root[run++])]});
    });
  }
  zone.release();
  pieces = cv::Mat(mask.size(), narrow ? CV_16U : CV_32S, cv::Scalar(0));
  for (const ZoneRun& z : zone_runs) setIds(pieces, z.y, z.x0, z.x1, z.id);
  const auto pieceAt = [&](cv::Point p) { return idAt(pieces, p.y, p.x); };
  std::size_t run = 0;
  forEachRun(branches, true, [&](int y, int x0, int x1) {
    const int b = branch_id[static_cast<std::size_t>(branch_comps.root[run++])];
    for (int x = x0; x <= x1; ++x) {
      const cv::Point p = toFull(x, y);
      if (p.x >= mask.cols || p.y >= mask.rows || !mask.at<unsigned char>(p) || pieceAt(p)) continue;
      setIds(pieces, p.y, p.x, p.x, nz + b);
    }
  });
  // Geodesic growth inside the region (breadth-first, 8-connected).
  growSeeds(pieces, mask);
  // Small pieces join the neighbour they share most border with, smallest first (sizes and borders are updated as
  // pieces merge; union-find maps every piece to the one it ended in).
  const int n = nz + nb;
  std::vector<long long> sizes(static_cast<std::size_t>(n) + 1, 0);
  for (int y = 0; y < pieces.rows; ++y)
    for (int x = 0; x < pieces.cols; ++x) sizes[static_cast<std::size_t>(pieceAt({x, y}))]++;
  RegionMerger merge(pieces, std::move(sizes));
  const std::vector<int>& parent = merge.parent;
  const std::vector<long long>& size = merge.size;
  const std::vector<std::map<int, long long>>& border = merge.border;
  const long long min_cells = static_cast<long long>(std::ceil(o.min_piece_area / (resolution * resolution)));
  for (;;) {
    int small = 0;
    for (int i = 1; i <= n; ++i) {
      const auto u = static_cast<std::size_t>(i);
      if (parent[u] == i && size[u] > 0 && size[u] < min_cells && !border[u].empty() &&
          (!small || size[u] < size[static_cast<std::size_t>(small)]))
        small = i;
    }
    if (!small) break;
    merge.absorbIntoLongestBorder(small);
  }
  // Renumber 1..K.
  std::map<int, int> renum;
  for (int y = 0; y < pieces.rows; ++y)
    for (int x = 0; x < pieces.cols; ++x) {
      const int v = pieceAt({x, y});
      if (!v) continue;
      const int k = renum.emplace(merge.root(v), static_cast<int>(renum.size()) + 1).first->second;
      setIds(pieces, y, x, x, k);  // k <= v: fits
    }
  return static_cast<int>(renum.size());
}
}  // namespace

cv::Mat thinZhangSuen(const cv::Mat& mask) {
  CV_Assert(mask.type() == CV_8U);
  const int rows = mask.rows, cols = mask.cols;
  // 0 / 1 cells, continuous (index y * cols + x).
  cv::Mat img(rows, cols, CV_8U);
  for (int y = 0; y < rows; ++y) {
    const unsigned char* m = mask.ptr<unsigned char>(y);
    unsigned char* o = img.ptr<unsigned char>(y);
    for (int x = 0; x < cols; ++x) o[x] = m[x] >= 128;
  }
  if (rows >= 3 && cols >= 3) {
    unsigned char* p = img.data;
    const int offs[8] = {-cols, -cols + 1, 1, cols + 1, cols, cols - 1, -1, -cols - 1};  // N NE E SE S SW W NW
    // dirty[k]: the cell is queued for the next sub-iteration of parity k (its neighbourhood changed since it was
    // last looked at with that parity, or it was never looked at). A cell not queued would give the answer it
    // gave last time: kept.
    std::vector<std::uint8_t> dirty(static_cast<std::size_t>(rows) * cols, 0);
    std::vector<int> queue[2], removed;
    for (int y = 1; y < rows - 1; ++y)
      for (int x = 1; x < cols - 1; ++x)
        if (p[y * cols + x]) {
          dirty[static_cast<std::size_t>(y) * cols + x] = 3;
          queue[0].push_back(y * cols + x);
          queue[1].push_back(y * cols + x);
        }
    const auto interior = [&](int i) {
      const int y = i / cols, x = i % cols;
      return y > 0 && x > 0 && y < rows - 1 && x < cols - 1;
    };
    std::vector<int> current;
    for (int k = 0, idle = 0; idle < 2; k ^= 1) {
      current.swap(queue[k]);
      queue[k].clear();
      removed.clear();
      for (const int i : current) {
        dirty[static_cast<std::size_t>(i)] &= static_cast<std::uint8_t>(~(1u << k));
        if (!p[i]) continue;
        int n[8];
        for (int d = 0; d < 8; ++d) n[d] = p[i + offs[d]];
        const int b = n[0] + n[1] + n[2] + n[3] + n[4] + n[5] + n[6] + n[7];
        if (b < 2 || b > 6) continue;
        int a = 0;
        for (int d = 0; d < 8; ++d) a += n[d] == 0 && n[(d + 1) % 8] == 1;
        if (a != 1) continue;
        // n: 0 = p2 (N), 2 = p4 (E), 4 = p6 (S), 6 = p8 (W)
        const bool m1 = k == 0 ? n[0] && n[2] && n[4] : n[0] && n[2] && n[6];
        const bool m2 = k == 0 ? n[2] && n[4] && n[6] : n[0] && n[4] && n[6];
        if (!m1 && !m2) removed.push_back(i);
      }
      current.clear();
      for (const int i : removed) p[i] = 0;
      for (const int i : removed)
        for (int d = 0; d < 8; ++d) {
          const int j = i + offs[d];
          if (!p[j] || !interior(j)) continue;
          for (int q = 0; q < 2; ++q)
            if (!(dirty[static_cast<std::size_t>(j)] & (1u << q))) {
              dirty[static_cast<std::size_t>(j)] |= static_cast<std::uint8_t>(1u << q);
              queue[q].push_back(j);
            }
        }
      idle = removed.empty() ? idle + 1 : 0;
    }
  }
  img *= 255;
  return img;
}

RegionMap splitCorridors(const RegionMap& rm, double resolution, const CorridorSplitOptions& o) {
  if (!o.enabled) return rm;
  RegionMap copy;
  copy.ids = rm.ids.clone();
  copy.regions = rm.regions;
  return splitCorridors(std::move(copy), resolution, o);
}

RegionMap splitCorridors(RegionMap&& rm, double resolution, const CorridorSplitOptions& o) {
  if (!o.enabled) return std::move(rm);
  // In place: a region's new ids are written negated, so that the cells of the regions still to come keep their
  // (positive) old ids and no new id is mistaken for an old one; the signs are turned at the end.
  // An id image someone else also holds (a shallow copy of the caller's) is copied first.
  RegionMap out;
  out.ids = rm.ids.u && rm.ids.u->refcount > 1 ? rm.ids.clone() : rm.ids;
  rm.ids.release();
  cv::Mat& ids = out.ids;
  for (const Region& r : rm.regions) {
    // ROI with a one-cell margin (thinning and the neighbour tests read one cell around every pixel).
    const cv::Rect roi = (r.bbox + cv::Size(2, 2) - cv::Point(1, 1)) & cv::Rect(0, 0, ids.cols, ids.rows);
    cv::Mat mask(r.bbox.height + 2, r.bbox.width + 2, CV_8U, cv::Scalar(0));
    const cv::Point off = r.bbox.tl() - cv::Point(1, 1);  // mask (0, 0) in image coordinates
    cv::Mat(mask, cv::Rect(roi.tl() - off, roi.size())).setTo(255, ids(roi) == r.id);
    cv::Mat pieces;  // empty: the region is one piece, its mask's cells
    const int k = r.label == static_cast<int>(places::PlaceLabel::Corridor) ? splitOne(mask, resolution, o, pieces) : 1;
    const int base = static_cast<int>(out.regions.size());
    std::vector<long long> n(static_cast<std::size_t>(k), 0), sx(n), sy(n);
    std::vector<cv::Rect> box(static_cast<std::size_t>(k));
    for (int y = 0; y < mask.rows; ++y)
      for (int x = 0; x < mask.cols; ++x) {
        const int p = pieces.empty() ? (mask.at<unsigned char>(y, x) ? 1 : 0) : idAt(pieces, y, x);
        if (!p) continue;
        const int gx = x + off.x, gy = y + off.y;
        ids.at<int>(gy, gx) = -(base + p);  // pieces lie inside the mask: only this region's cells are written
        const std::size_t i = static_cast<std::size_t>(p - 1);
        ++n[i], sx[i] += gx, sy[i] += gy;
        box[i] = n[i] == 1 ? cv::Rect(gx, gy, 1, 1) : (box[i] | cv::Rect(gx, gy, 1, 1));
      }
    for (int i = 0; i < k; ++i) {
      const std::size_t u = static_cast<std::size_t>(i);
      Region q;
      q.id = base + i + 1;
      q.label = r.label;
      q.cells = static_cast<int>(n[u]);
      q.area_m2 = q.cells * resolution * resolution;
      q.centroid = n[u] ? cv::Point2d(double(sx[u]) / n[u], double(sy[u]) / n[u]) : r.centroid;
      q.bbox = box[u];
      out.regions.push_back(q);
    }
  }
  // New ids positive; a cell still holding an old id (in no piece, or of a region not listed) is in no region, as
  // in a fresh image.
  for (int y = 0; y < ids.rows; ++y) {
    int* row = ids.ptr<int>(y);
    for (int x = 0; x < ids.cols; ++x) row[x] = row[x] < 0 ? -row[x] : 0;
  }
  return out;
}

}  // namespace gridtopo::topology
