#pragma once
// Exhaustive scan-to-submap matching in a search window: the branch-and-bound search over a multi-resolution
// grid of Hess, Kohler, Rapp, Andor, "Real-time loop closure in 2D LIDAR SLAM", ICRA 2016, sec. V-C (after the
// correlative matching of Olson, "Real-time correlative scan matching", ICRA 2009). The submap's points become a
// correlation grid (value exp(−d²/2σ²) at distance d from the nearest point, in [0, 1]); level h of its
// precomputation stack holds, per cell, the maximum of the finest level over the 2^h × 2^h cells starting there,
// so a candidate's score at level h bounds the scores of the 4^h finer candidates it covers. The result is the
// best-scoring pose of the whole window on the finest level, then refined by hill climbing on the interpolated
// grid.
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "gridtopo/slam/pose2.h"

namespace gridtopo::slam {

struct Point2 {
  double x = 0.0, y = 0.0;
};

/// t ⊕ p: the point p, given in the frame of t, in t's parent frame.
inline Point2 transform(const Pose2& t, const Point2& p) {
  const double c = std::cos(t.theta), s = std::sin(t.theta);
  return {t.x + c * p.x - s * p.y, t.y + s * p.x + c * p.y};
}

class CorrelationGrid {
 public:
  /// The grid of `points` (in the submap's frame) with cell `resolution`, value width `sigma` and `depth` + 1
  /// levels; the refinement's sharper value has width `refine_sigma` (0 = sigma).
  CorrelationGrid(const std::vector<Point2>& points, double resolution, double sigma, int depth,
                  double refine_sigma = 0.0);

  double resolution() const { return res_; }
  int depth() const { return depth_; }
  /// Value in [0, 255] of level `h` at cell (cx, cy) of the finest lattice; 0 outside.
  int value(int h, int cx, int cy) const {
    const Level& l = levels_[static_cast<std::size_t>(h)];
    const int x = cx + l.pad, y = cy + l.pad;
    if (static_cast<unsigned>(x) >= static_cast<unsigned>(l.w) || static_cast<unsigned>(y) >= static_cast<unsigned>(l.h))
      return 0;
    return l.v[static_cast<std::size_t>(y) * l.w + x];
  }
  /// Level `h`'s storage, for loops that read many of its cells: value(h, cx, cy) is data[(cy + pad) * w + cx + pad]
  /// where 0 <= cx + pad < w and 0 <= cy + pad < rows, else 0.
  struct LevelView {
    const std::uint8_t* data;
    int pad, w, rows;
  };
  LevelView level(int h) const {
    const Level& l = levels_[static_cast<std::size_t>(h)];
    return {l.v.data(), l.pad, l.w, l.h};
  }
  /// The finest level interpolated bilinearly at a point of the submap's frame, in [0, 1].
  double interpolated(double x, double y) const;
  /// The refinement's value at a point: exp(−d²/2·refine_sigma²) of the exact distance d to the submap point
  /// nearest to its cell, in [0, 1] (continuous within a cell, unlike the quantised search value). A wide search value finds a match from far; the sharp one places it precisely.
  double refined(double x, double y) const;
  /// Cell of a coordinate on the finest lattice.
  int cellX(double x) const { return floorInt((x - x0_) / res_); }
  int cellY(double y) const { return floorInt((y - y0_) / res_); }
  std::size_t bytes() const;

 private:
  static int floorInt(double v) {
    const int i = static_cast<int>(v);
    return i - (v < static_cast<double>(i));
  }
  /// One level of the precomputation stack. Level h at cell cx holds the maximum over cells [cx, cx + 2^h) of
  /// level 0, so it is non-zero only from cx = −(2^h − 1) to the lattice's last cell: it stores those cells (a
  /// margin of 2^h − 1 on the low sides only; everything else is 0).
  struct Level {
    int pad = 0, w = 0, h = 0;
    std::vector<std::uint8_t> v;
  };
  double res_;
  int depth_;
  double x0_ = 0.0, y0_ = 0.0;  ///< submap-frame coordinates of the corner of finest cell (0, 0)
  std::vector<Level> levels_;
  int w0_ = 0, h0_ = 0;        ///< the finest lattice
  double refine_k_ = 0.0;      ///< −1 / (2 refine_sigma²), in 1/m²
  /// Per finest cell, the index in means_ of the cell holding submap points nearest to it; means_ holds each such
  /// cell's mean point.
  std::vector<std::uint32_t> nearest_;
  std::vector<std::pair<float, float>> means_;
};

struct SearchWindow {
  Pose2 center;        ///< the query's estimated pose in the grid's frame
  double xy = 1.0;     ///< m, half-width in x and y
  double theta = 0.1;  ///< rad, half-width in heading
};

struct CorrelativeMatch {
  Pose2 pose;          ///< of the query in the grid's frame
  double score = 0.0;  ///< mean value over the query's points, in [0, 1]
};

/// The best pose of `query` (points in its own frame) in `window` whose score is at least `min_score`, or
/// nothing. With `exclude_center`, poses within `exclude_radius` (m) of it are not considered (the search for a
/// second, distinct match). The angular step follows from the query's extent (Hess et al., eq. 7).
std::optional<CorrelativeMatch> branchAndBoundSearch(const CorrelationGrid& grid, const std::vector<Point2>& query,
                                                     const SearchWindow& window, double min_score,
                                                     const Point2* exclude_center = nullptr,
                                                     double exclude_radius = 0.0);

/// refineMatch's most steps at each step size: with steps of half a cell (half `theta_step`) halved at each level,
/// a refinement moves its start by less than kRefineStepsPerLevel cells (angular steps) in all.
constexpr int kRefineStepsPerLevel = 50;

/// Local refinement of a match: hill climbing on the grid's refinement value (CorrelationGrid::refined) from
/// `start` (steps of half a cell and the given angular step, halved `refinements` times, at most
/// kRefineStepsPerLevel steps each); the score returned is the mean of the search value (correlationScore) at the
/// refined pose, comparable with the search's.
CorrelativeMatch refineMatch(const CorrelationGrid& grid, const std::vector<Point2>& query, const Pose2& start,
                             double theta_step, int refinements = 5);

/// The mean interpolated grid value of `query` at pose `x`.
double correlationScore(const CorrelationGrid& grid, const std::vector<Point2>& query, const Pose2& x);
/// The mean refinement value of `query` at pose `x`.
double refinementScore(const CorrelationGrid& grid, const std::vector<Point2>& query, const Pose2& x);

}  // namespace gridtopo::slam
