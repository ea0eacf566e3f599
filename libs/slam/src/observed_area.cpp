#include "gridtopo/slam/observed_area.h"

#include <algorithm>
#include <cmath>

namespace gridtopo::slam {

ObservedArea::ObservedArea(const std::vector<ObservedScan>& scans, double cell, double free_margin,
                           double hit_clearance)
    : cell_(cell) {
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  const auto extend = [&](const Point2& p) {
    xmin = std::min(xmin, p.x);
    xmax = std::max(xmax, p.x);
    ymin = std::min(ymin, p.y);
    ymax = std::max(ymax, p.y);
  };
  for (const ObservedScan& s : scans) {
    extend(transform(s.pose, s.sensor));
    for (const Point2& p : *s.hits) extend(transform(s.pose, p));
  }
  if (xmin > xmax) return;
  const int margin = static_cast<int>(std::ceil(hit_clearance / cell)) + 2;
  x0_ = xmin - margin * cell;
  y0_ = ymin - margin * cell;
  w_ = static_cast<int>(std::ceil((xmax - x0_) / cell)) + margin + 1;
  h_ = static_cast<int>(std::ceil((ymax - y0_) / cell)) + margin + 1;
  const std::size_t n = static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_);
  std::vector<std::uint8_t> crossed(n, 0), passed(n, 0), hit(n, 0);
  const auto index = [&](double x, double y) {
    return static_cast<std::size_t>(static_cast<int>((y - y0_) / cell)) * static_cast<std::size_t>(w_) +
           static_cast<std::size_t>(static_cast<int>((x - x0_) / cell));
  };
  for (const ObservedScan& s : scans) {
    const Point2 from = transform(s.pose, s.sensor);
    for (const Point2& p : *s.hits) {
      const Point2 to = transform(s.pose, p);
      const double dx = to.x - from.x, dy = to.y - from.y, length = std::hypot(dx, dy);
      // Half-cell steps along the beam: every cell it crosses is visited.
      const int steps = static_cast<int>(length / (0.5 * cell)) + 1;
      for (int k = 0; k <= steps; ++k) {
        const double f = static_cast<double>(k) / steps;
        const std::size_t i = index(from.x + f * dx, from.y + f * dy);
        crossed[i] = 1;
        if ((1.0 - f) * length > free_margin) passed[i] = 1;
      }
      hit[index(to.x, to.y)] = 1;
    }
  }
  // A passed cell is free unless a hit lies within hit_clearance (a square of that half-width, in whole cells).
  const int r = static_cast<int>(std::floor(hit_clearance / cell + 1e-9));
  std::vector<int> hits_in_rows(n, 0);  // per cell, the hits among the 2r + 1 cells of its row centred on it
  for (int y = 0; y < h_; ++y)
    for (int x = 0; x < w_; ++x) {
      int c = 0;
      for (int dx = std::max(0, x - r); dx <= std::min(w_ - 1, x + r); ++dx)
        c += hit[static_cast<std::size_t>(y) * w_ + dx];
      hits_in_rows[static_cast<std::size_t>(y) * w_ + x] = c;
    }
  flags_.assign(n, 0);
  for (int y = 0; y < h_; ++y)
    for (int x = 0; x < w_; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w_ + x;
      bool near_crossed = false;
      for (int dy = std::max(0, y - 1); dy <= std::min(h_ - 1, y + 1) && !near_crossed; ++dy)
        for (int dx = std::max(0, x - 1); dx <= std::min(w_ - 1, x + 1) && !near_crossed; ++dx)
          near_crossed = crossed[static_cast<std::size_t>(dy) * w_ + dx] != 0;
      if (near_crossed) flags_[i] |= kSeen;
      if (!passed[i]) continue;
      int near_hits = 0;
      for (int dy = std::max(0, y - r); dy <= std::min(h_ - 1, y + r) && near_hits == 0; ++dy)
        near_hits += hits_in_rows[static_cast<std::size_t>(dy) * w_ + x];
      if (near_hits == 0) flags_[i] |= kFree;
    }
}

bool ObservedArea::at(const Point2& p, std::uint8_t flag) const {
  const double fx = std::floor((p.x - x0_) / cell_), fy = std::floor((p.y - y0_) / cell_);
  if (fx < 0.0 || fy < 0.0 || fx >= w_ || fy >= h_) return false;
  return (flags_[static_cast<std::size_t>(fy) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(fx)] & flag) != 0;
}

MatchEvidence matchEvidence(const CorrelationGrid& grid, const ObservedArea& area, const std::vector<Point2>& query,
                            const Pose2& x) {
  MatchEvidence e;
  if (query.empty()) return e;
  std::size_t seen = 0, free = 0;
  double sum = 0.0;
  for (const Point2& q : query) {
    const Point2 p = transform(x, q);
    if (area.seen(p)) {
      ++seen;
      sum += grid.interpolated(p.x, p.y);
    }
    if (area.seenFree(p)) ++free;
  }
  const double n = static_cast<double>(query.size());
  e.coverage = static_cast<double>(seen) / n;
  e.observed_score = seen ? sum / static_cast<double>(seen) : 0.0;
  e.contradiction = static_cast<double>(free) / n;
  return e;
}

}  // namespace gridtopo::slam
