#include "gridtopo/topology/map_preparation.h"
#include "gridtopo/core/distance_transform.h"
#include "mask_ops.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <thread>

namespace gridtopo::topology {

namespace {

using places::kFree;
using places::kUnknown;

/// Step 1: the cells covered by a disc of `radius_cells` that lies wholly in `free`. The disc's centres are the
/// cells whose distance to the nearest non-free cell exceeds the radius; the covered cells lie within the radius
/// of a centre (two exact Euclidean distance transforms, no kernel rounding).
cv::Mat robotFits(const cv::Mat& free, double radius_cells) {
  if (radius_cells < 0.5) return free.clone();
  // A cell's centre is clearance away from the nearest non-free cell's centre: the disc stays inside the free
  // space when the clearance exceeds the radius by half a cell. Both tests are thresholds of exact distances
  // (withinDistance: no float image of the map).
  cv::Mat not_centre = withinDistance(free, radius_cells + 0.5);
  if (cv::countNonZero(not_centre) == static_cast<int>(not_centre.total())) return cv::Mat::zeros(free.size(), CV_8U);
  cv::Mat covered = withinDistance(not_centre, radius_cells);
  not_centre.release();
  covered &= free;
  return covered;
}

/// Step 2: the cells seen along a free line of sight from a path sample at most `range_cells` away. Rays are cast
/// from every sample over 360 degrees, close enough that neighbouring rays are a cell apart at the range, in steps
/// of half a cell; a ray stops at the first cell that is not free in the map (glass and open doors are free: seen
/// through them counts). One bit per cell (row-major, y * cols + x): an eighth of a byte image per thread.
using CellBits = std::vector<std::uint64_t>;
CellBits seenFromNear(const cv::Mat& free, const std::vector<cv::Point2d>& samples, double range_cells, int threads) {
  // The samples split over the threads, each marking its own bits; the union does not depend on the split.
  const int nt = std::max(1, std::min(threads, static_cast<int>(samples.size() / 16)));
  if (nt > 1) {
    std::vector<CellBits> part(static_cast<std::size_t>(nt));
    std::vector<std::thread> pool;
    auto run = [&](int t) {
      const auto a = samples.begin() + static_cast<long>(samples.size() * t / nt);
      const auto b = samples.begin() + static_cast<long>(samples.size() * (t + 1) / nt);
      part[static_cast<std::size_t>(t)] = seenFromNear(free, std::vector<cv::Point2d>(a, b), range_cells, 1);
    };
    for (int t = 1; t < nt; ++t) pool.emplace_back(run, t);
    run(0);
    for (auto& t : pool) t.join();
    for (int t = 1; t < nt; ++t)
      for (std::size_t w = 0; w < part[0].size(); ++w) part[0][w] |= part[static_cast<std::size_t>(t)][w];
    return std::move(part[0]);
  }
  const int cols = free.cols, rows = free.rows;
  CellBits seen((static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols) + 63) / 64, 0);
  const int n_rays = std::max(8, static_cast<int>(std::ceil(2.0 * M_PI * range_cells)));
  std::vector<cv::Point2d> dir(static_cast<std::size_t>(n_rays));
  for (int k = 0; k < n_rays; ++k) {
    const double a = 2.0 * M_PI * k / n_rays;
    dir[static_cast<std::size_t>(k)] = {0.5 * std::cos(a), 0.5 * std::sin(a)};
  }
  const int steps = static_cast<int>(std::ceil(2.0 * range_cells));
  const std::size_t free_step = free.step;
  const unsigned char* free_data = free.data;
  for (const cv::Point2d& p : samples) {
    const int px = static_cast<int>(std::floor(p.x)), py = static_cast<int>(std::floor(p.y));
    if (px < 0 || py < 0 || px >= free.cols || py >= free.rows) continue;
    for (const cv::Point2d& d : dir) {
      double x = p.x, y = p.y;
      int last_x = -1, last_y = -1;  // the cell of the previous step (free and marked)
      for (int s = 0; s <= steps; ++s, x += d.x, y += d.y) {
        // floor(v) < 0 exactly when v < 0; for v >= 0 the conversion truncates, as floor does.
        if (x < 0 || y < 0) break;
        const int cx = static_cast<int>(x), cy = static_cast<int>(y);
        if (cx == last_x && cy == last_y) continue;  // half-cell steps: the same cell again
        if (cx >= cols || cy >= rows) break;
        if (!free_data[static_cast<std::size_t>(cy) * free_step + static_cast<std::size_t>(cx)]) break;
        const std::size_t bit = static_cast<std::size_t>(cy) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(cx);
        seen[bit >> 6] |= std::uint64_t(1) << (bit & 63);
        last_x = cx, last_y = cy;
      }
    }
  }
  return seen;
}

/// `places` keeps only the cells whose bit is set in `seen` (seenFromNear's bits of an image of its size).
void keepSeen(cv::Mat& places, const CellBits& seen) {
  const auto cols = static_cast<std::size_t>(places.cols);
  for (int y = 0; y < places.rows; ++y) {
    unsigned char* row = places.ptr<unsigned char>(y);
    const std::size_t base = static_cast<std::size_t>(y) * cols;
    for (std::size_t x = 0; x < cols; ++x)
      if (row[x] && !((seen[(base + x) >> 6] >> ((base + x) & 63)) & 1)) row[x] = 0;
  }
}

/// Step 3: the 8-connected groups of `places` of at least `min_cells` that, when the path is known, the path enters
/// (a path position within `near_cells` of one of the group's cells).
cv::Mat reachable(const cv::Mat& places, int min_cells, const std::vector<cv::Point2d>& path, int near_cells) {
  // The groups from their runs (RunComponents: no image of group numbers, 4 bytes a cell of the whole map).
  const RunComponents groups(places, true, 8);
  std::vector<int> row_first(static_cast<std::size_t>(places.rows) + 1, 0);  // the first run of each row
  std::vector<std::pair<int, int>> extent;                                    // each run's [x0, x1]
  extent.reserve(groups.root.size());
  forEachRun(places, true, [&](int y, int x0, int x1) {
    extent.emplace_back(x0, x1);
    row_first[static_cast<std::size_t>(y) + 1] = static_cast<int>(extent.size());
  });
  for (std::size_t y = 1; y < row_first.size(); ++y) row_first[y] = std::max(row_first[y], row_first[y - 1]);
  std::vector<char> entered(groups.root.size(), path.empty() ? 1 : 0);
  for (const cv::Point2d& p : path) {
    const int px = static_cast<int>(std::floor(p.x)), py = static_cast<int>(std::floor(p.y));
    const int x0 = std::max(0, px - near_cells), x1 = std::min(places.cols - 1, px + near_cells);
    if (x0 > x1) continue;
    for (int y = std::max(0, py - near_cells); y <= std::min(places.rows - 1, py + near_cells); ++y)
      for (int i = row_first[static_cast<std::size_t>(y)]; i < row_first[static_cast<std::size_t>(y) + 1]; ++i) {
        const auto& [a, b] = extent[static_cast<std::size_t>(i)];
        if (b >= x0 && a <= x1) entered[static_cast<std::size_t>(groups.root[static_cast<std::size_t>(i)])] = 1;
      }
  }
  cv::Mat out = cv::Mat::zeros(places.size(), CV_8U);
  std::size_t i = 0;
  forEachRun(places, true, [&](int y, int x0, int x1) {
    const auto r = static_cast<std::size_t>(groups.root[i++]);
    if (entered[r] && groups.area[r] >= min_cells)
      std::fill(out.ptr<unsigned char>(y) + x0, out.ptr<unsigned char>(y) + x1 + 1, static_cast<unsigned char>(255));
  });
  return out;
}

std::size_t count(const cv::Mat& m) { return static_cast<std::size_t>(cv::countNonZero(m)); }

}  // namespace

PreparedMap prepareMap(const places::OccupancyImage& occ, const MapPreparationOptions& o,
                       const std::vector<cv::Point2d>& path, int threads) {
  PreparedMap r;
  const cv::Mat free = occ.cells == kFree;
  r.free_cells = count(free);
  cv::Mat places = o.enabled ? robotFits(free, o.robot_radius / occ.resolution) : free.clone();
  if (o.enabled) {
    const double res = occ.resolution;
    r.removed_robot_fit = r.free_cells - count(places);
    if (!path.empty() && o.view_range > 0) {
      // The path sampled every path_step metres (the first position always).
      std::vector<cv::Point2d> samples;
      for (const cv::Point2d& p : path)
        if (samples.empty() || std::hypot(p.x - samples.back().x, p.y - samples.back().y) * res >= o.path_step)
          samples.push_back(p);
      const std::size_t before = count(places);
      keepSeen(places, seenFromNear(free, samples, o.view_range / res, threads));
      r.removed_far = before - count(places);
    }
    const std::size_t before = count(places);
    const int min_cells = static_cast<int>(std::ceil(o.min_area / (res * res)));
    places = reachable(places, min_cells, path, static_cast<int>(std::ceil(o.robot_radius / res)) + 1);
    r.removed_unreachable = before - count(places);
  }
  r.places = places;
  cv::subtract(free, places, r.seen_not_place);  // free & ~places (both 0 / 255; places within free), no temporary
  r.place_cells = count(places);
  return r;
}

places::OccupancyImage placesOnly(const places::OccupancyImage& occ, const PreparedMap& prepared) {
  places::OccupancyImage out = occ;
  out.cells = occ.cells.clone();
  out.cells.setTo(kUnknown, prepared.seen_not_place);
  return out;
}

std::vector<cv::Point2d> pathInCells(const std::vector<cv::Point2d>& world, cv::Point2d origin, double resolution,
                                     int rows) {
  std::vector<cv::Point2d> cells;
  cells.reserve(world.size());
  for (const cv::Point2d& w : world)
    cells.emplace_back((w.x - origin.x) / resolution, rows - (w.y - origin.y) / resolution);
  return cells;
}

}  // namespace gridtopo::topology
