#pragma once
// A floor plan given as a grid of cells (a labelled plan's occupancy image) for the laser simulator: rays are cast
// exactly through the cells (Amanatides & Woo's traversal) and end where they enter the first blocked cell.
// Frame: cell (col, row) of the image, row 0 at the top, covers x in [col, col + 1) * resolution and
// y in [rows - 1 - row, rows - row) * resolution, so a map built from the simulated scans at the true poses in this
// frame is pixel-aligned with the plan (the map's cell (cx, cy) = floor(x / res), floor(y / res) is the plan's
// pixel (cx, rows - 1 - cy)).
#include <cstdint>
#include <vector>

namespace gridtopo::sim {

class GridPlan {
 public:
  GridPlan() = default;
  /// `blocked`: rows x cols, row-major, non-zero = obstacle. Throws std::invalid_argument on a size mismatch or a
  /// non-positive resolution.
  GridPlan(int rows, int cols, double resolution, std::vector<std::uint8_t> blocked);

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  double resolution() const { return res_; }
  bool blocked(int row, int col) const { return blocked_[static_cast<std::size_t>(row) * cols_ + col] != 0; }
  /// World coordinates of a cell's centre.
  double x(int col) const { return (col + 0.5) * res_; }
  double y(int row) const { return (rows_ - row - 0.5) * res_; }

  /// Distance from (x, y) along direction a (rad, counter-clockwise from +x) to the first blocked cell; 0 when
  /// (x, y) lies in one; +inf when the ray leaves the grid first (nothing there to reflect it).
  double rayCast(double x, double y, double a) const;

 private:
  int rows_ = 0, cols_ = 0;
  double res_ = 0.05;
  std::vector<std::uint8_t> blocked_;
};

}  // namespace gridtopo::sim
