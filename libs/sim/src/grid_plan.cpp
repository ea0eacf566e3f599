#include "gridtopo/sim/grid_plan.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace gridtopo::sim {

GridPlan::GridPlan(int rows, int cols, double resolution, std::vector<std::uint8_t> blocked)
    : rows_(rows), cols_(cols), res_(resolution), blocked_(std::move(blocked)) {
  if (rows < 1 || cols < 1 || blocked_.size() != static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols))
    throw std::invalid_argument("GridPlan: the cell array must hold rows x cols cells");
  if (!(resolution > 0) || !std::isfinite(resolution)) throw std::invalid_argument("GridPlan: resolution must be > 0");
}

double GridPlan::rayCast(double x, double y, double a) const {
  const double inf = std::numeric_limits<double>::infinity();
  // In cell units, with cy counted upwards (cy = rows - 1 - row).
  const double px = x / res_, py = y / res_;
  int cx = static_cast<int>(std::floor(px)), cy = static_cast<int>(std::floor(py));
  auto inside = [&](int c, int r) { return c >= 0 && r >= 0 && c < cols_ && r < rows_; };
  if (!inside(cx, cy)) return inf;  // rays start inside the plan
  if (blocked(rows_ - 1 - cy, cx)) return 0.0;
  const double dx = std::cos(a), dy = std::sin(a);
  const int sx = dx > 0 ? 1 : -1, sy = dy > 0 ? 1 : -1;
  // Ray parameter (in cells) to the first vertical / horizontal cell boundary and between two of them.
  const double tdx = dx != 0 ? std::abs(1.0 / dx) : inf, tdy = dy != 0 ? std::abs(1.0 / dy) : inf;
  double tx = dx > 0 ? (cx + 1 - px) * tdx : dx < 0 ? (px - cx) * tdx : inf;
  double ty = dy > 0 ? (cy + 1 - py) * tdy : dy < 0 ? (py - cy) * tdy : inf;
  for (;;) {
    double t;
    if (tx < ty) {
      t = tx, cx += sx, tx += tdx;
    } else {
      t = ty, cy += sy, ty += tdy;
    }
    if (!inside(cx, cy)) return inf;
    if (blocked(rows_ - 1 - cy, cx)) return t * res_;
  }
}

}  // namespace gridtopo::sim
