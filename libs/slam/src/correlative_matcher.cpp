#include "gridtopo/slam/correlative_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace gridtopo::slam {

CorrelationGrid::CorrelationGrid(const std::vector<Point2>& points, double resolution, double sigma, int depth,
                                 double refine_sigma)
    : res_(resolution), depth_(std::max(0, depth)) {
  if (!(refine_sigma > 0.0)) refine_sigma = sigma;
  refine_k_ = -0.5 / (refine_sigma * refine_sigma);
  double minx = 0.0, miny = 0.0, maxx = 0.0, maxy = 0.0;
  if (!points.empty()) {
    minx = maxx = points.front().x;
    miny = maxy = points.front().y;
    for (const Point2& p : points) {
      minx = std::min(minx, p.x);
      maxx = std::max(maxx, p.x);
      miny = std::min(miny, p.y);
      maxy = std::max(maxy, p.y);
    }
  }
  // The value falls below 1/255 beyond about 3.3 sigma: that much margin around the points.
  const int margin = static_cast<int>(std::ceil(3.5 * sigma / res_)) + 1;
  x0_ = minx - margin * res_;
  y0_ = miny - margin * res_;
  const int w0 = static_cast<int>(std::ceil((maxx - minx) / res_)) + 2 * margin + 1;
  const int h0 = static_cast<int>(std::ceil((maxy - miny) / res_)) + 2 * margin + 1;
  w0_ = w0;
  h0_ = h0;
  // The cells holding points, each with its points' mean (summed in the points' order).
  std::vector<std::pair<std::size_t, std::size_t>> cell_of_point;  // (cell, point index)
  cell_of_point.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const int cx = cellX(points[k].x), cy = cellY(points[k].y);
    if (cx < 0 || cy < 0 || cx >= w0 || cy >= h0) continue;
    cell_of_point.emplace_back(static_cast<std::size_t>(cy) * w0 + cx, k);
  }
  std::sort(cell_of_point.begin(), cell_of_point.end());
  // Distance of every cell centre to the nearest point: OpenCV's distance transform with labels names the nearest
  // cell holding points, and the distance is taken to the mean of that cell's points (not to its centre), so that
  // the grid is exact to well under a cell where it matters, next to the points.
  cv::Mat seeds(h0, w0, CV_8UC1, cv::Scalar(255));
  std::vector<std::size_t> seed_cells;
  std::vector<std::pair<double, double>> means;  // the distances are taken to these; means_ keeps them as floats
  for (std::size_t k = 0; k < cell_of_point.size();) {
    const std::size_t c = cell_of_point[k].first;
    double sx = 0.0, sy = 0.0;
    int n = 0;
    for (; k < cell_of_point.size() && cell_of_point[k].first == c; ++k) {
      sx += points[cell_of_point[k].second].x;
      sy += points[cell_of_point[k].second].y;
      ++n;
    }
    seeds.data[c] = 0;
    seed_cells.push_back(c);
    means.emplace_back(sx / n, sy / n);
    means_.emplace_back(static_cast<float>(sx / n), static_cast<float>(sy / n));
  }
  std::vector<std::pair<std::size_t, std::size_t>>().swap(cell_of_point);
  nearest_.assign(static_cast<std::size_t>(w0) * h0, 0);
  levels_.resize(static_cast<std::size_t>(depth_) + 1);
  levels_[0] = Level{0, w0, h0, std::vector<std::uint8_t>(static_cast<std::size_t>(w0) * h0, 0)};
  if (!means_.empty()) {
    cv::Mat dist, labels;
    cv::distanceTransform(seeds, dist, labels, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
    dist.release();
    seeds.release();
    const int* label = labels.ptr<int>();  // per cell, the label of the nearest seed cell (a seed's own label)
    // Label of each seed cell -> its index in means_.
    int max_label = 0;
    for (std::size_t c : seed_cells) max_label = std::max(max_label, label[c]);
    std::vector<std::uint32_t> mean_of_label(static_cast<std::size_t>(max_label) + 1, 0);
    for (std::size_t m = 0; m < seed_cells.size(); ++m)
      mean_of_label[static_cast<std::size_t>(label[seed_cells[m]])] = static_cast<std::uint32_t>(m);
    const double k = -0.5 / (sigma * sigma);
    // Beyond this squared distance the value rounds to 0 (255 exp(k d^2) < 0.5, with a margin for hypot's and the
    // float's rounding): most of a grid's cells, which then need neither hypot nor exp.
    const double zero_d2 = 1.001 * std::log(510.0) / -k;
    std::vector<std::uint8_t>& base = levels_[0].v;
    for (int y = 0; y < h0; ++y)
      for (int x = 0; x < w0; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w0 + x;
        const std::uint32_t m = mean_of_label[static_cast<std::size_t>(label[i])];
        nearest_[i] = m;
        const double dx = x0_ + (x + 0.5) * res_ - means[m].first, dy = y0_ + (y + 0.5) * res_ - means[m].second;
        if (dx * dx + dy * dy > zero_d2) continue;  // base[i] stays 0
        const double dd = static_cast<float>(std::hypot(dx, dy));
        base[i] = static_cast<std::uint8_t>(std::lround(255.0 * std::exp(k * dd * dd)));
      }
  }
  // Level h: the maximum of level h−1 over the cell and its neighbours 2^(h−1) cells right, up, and both; 0 outside
  // level h−1. Separably: the maximum of each of level h−1's rows with itself shifted by s = 2^(h−1), then of those
  // rows with the ones s further. (Level h−1's padding is s − 1, level h's 2s − 1: level h's column x reads level
  // h−1's columns x − s and x, its row y the rows y − s and y.)
  std::vector<std::uint8_t> rows;  // level h−1's rows maxed horizontally, with s rows of zeros above and below
  std::vector<std::uint8_t> padded;  // one row of level h−1 with s zeros either side
  for (int h = 1; h <= depth_; ++h) {
    const int s = 1 << (h - 1);
    const int pad = (1 << h) - 1;
    Level& cur = levels_[static_cast<std::size_t>(h)];
    const Level& prev = levels_[static_cast<std::size_t>(h) - 1];
    cur.pad = pad;
    cur.w = w0 + pad;
    cur.h = h0 + pad;
    const std::size_t cw = static_cast<std::size_t>(cur.w);
    rows.assign(cw * static_cast<std::size_t>(prev.h + 2 * s), 0);
    padded.assign(static_cast<std::size_t>(prev.w + 2 * s), 0);
    for (int py = 0; py < prev.h; ++py) {
      std::copy_n(prev.v.data() + static_cast<std::size_t>(py) * prev.w, prev.w, padded.data() + s);
      std::uint8_t* out = rows.data() + static_cast<std::size_t>(py + s) * cw;
      const std::uint8_t* a = padded.data();
      const std::uint8_t* b = padded.data() + s;
      for (std::size_t x = 0; x < cw; ++x) out[x] = std::max(a[x], b[x]);
    }
    cur.v.resize(cw * static_cast<std::size_t>(cur.h));
    for (int y = 0; y < cur.h; ++y) {
      const std::uint8_t* a = rows.data() + static_cast<std::size_t>(y) * cw;
      const std::uint8_t* b = a + static_cast<std::size_t>(s) * cw;
      std::uint8_t* dst = cur.v.data() + static_cast<std::size_t>(y) * cw;
      for (std::size_t x = 0; x < cw; ++x) dst[x] = std::max(a[x], b[x]);
    }
  }
}

double CorrelationGrid::interpolated(double x, double y) const {
  const double gx = (x - x0_) / res_ - 0.5, gy = (y - y0_) / res_ - 0.5;
  const int ix = floorInt(gx), iy = floorInt(gy);
  const double fx = gx - ix, fy = gy - iy;
  const double v00 = value(0, ix, iy), v10 = value(0, ix + 1, iy), v01 = value(0, ix, iy + 1),
               v11 = value(0, ix + 1, iy + 1);
  return ((1 - fy) * ((1 - fx) * v00 + fx * v10) + fy * ((1 - fx) * v01 + fx * v11)) / 255.0;
}

double CorrelationGrid::refined(double x, double y) const {
  const int ix = cellX(x), iy = cellY(y);
  if (ix < 0 || iy < 0 || ix >= w0_ || iy >= h0_) return 0.0;
  if (means_.empty()) return 0.0;
  const auto& p = means_[nearest_[static_cast<std::size_t>(iy) * w0_ + ix]];
  const double dx = x - p.first, dy = y - p.second;
  return std::exp(refine_k_ * (dx * dx + dy * dy));
}

std::size_t CorrelationGrid::bytes() const {
  std::size_t b = sizeof(*this) + nearest_.capacity() * sizeof(nearest_[0]) + means_.capacity() * sizeof(means_[0]);
  for (const Level& l : levels_) b += l.v.capacity();
  return b;
}

namespace {
/// The mean of value(x, y) over the query's points moved to pose x.
template <class Value>
double meanOverQuery(const std::vector<Point2>& query, const Pose2& x, Value value) {
  if (query.empty()) return 0.0;
  const double c = std::cos(x.theta), s = std::sin(x.theta);
  double sum = 0.0;
  for (const Point2& q : query) sum += value(x.x + c * q.x - s * q.y, x.y + s * q.x + c * q.y);
  return sum / static_cast<double>(query.size());
}
}  // namespace

double correlationScore(const CorrelationGrid& grid, const std::vector<Point2>& query, const Pose2& x) {
  return meanOverQuery(query, x, [&](double px, double py) { return grid.interpolated(px, py); });
}

double refinementScore(const CorrelationGrid& grid, const std::vector<Point2>& query, const Pose2& x) {
  return meanOverQuery(query, x, [&](double px, double py) { return grid.refined(px, py); });
}

CorrelativeMatch refineMatch(const CorrelationGrid& grid, const std::vector<Point2>& query, const Pose2& start,
                             double theta_step, int refinements) {
  CorrelativeMatch best{start, refinementScore(grid, query, start)};
  double sxy = 0.5 * grid.resolution(), st = 0.5 * theta_step;
  for (int level = 0; level <= refinements; ++level) {
    for (int it = 0; it < kRefineStepsPerLevel; ++it) {
      const Pose2 moves[6] = {{sxy, 0, 0}, {-sxy, 0, 0}, {0, sxy, 0}, {0, -sxy, 0}, {0, 0, st}, {0, 0, -st}};
      CorrelativeMatch next = best;
      for (const Pose2& m : moves) {
        const Pose2 p{best.pose.x + m.x, best.pose.y + m.y, wrapAngle(best.pose.theta + m.theta)};
        const double sc = refinementScore(grid, query, p);
        if (sc > next.score) next = {p, sc};
      }
      if (next.score <= best.score) break;
      best = next;
    }
    sxy *= 0.5;
    st *= 0.5;
  }
  best.score = correlationScore(grid, query, best.pose);
  return best;
}

namespace {

struct Candidate {
  int angle;   // index into the rotated queries
  int ox, oy;  // offset in cells
  long score;  // sum of grid values over the query's points
};

struct Search {
  const CorrelationGrid& grid;
  const std::vector<std::vector<int>>& cells;  // per angle: x0, y0, x1, y1, ... (finest cells at offset 0)
  int wx;                                      // window half-width in cells
  const Point2* exclude;
  double exclude_radius;
  double cx, cy;  // window centre (m, grid frame)
  Candidate best;

  long score(int h, int angle, int ox, int oy) const {
    const std::vector<int>& c = cells[static_cast<std::size_t>(angle)];
    long s = 0;
    for (std::size_t i = 0; i < c.size(); i += 2) s += grid.value(h, c[i] + ox, c[i + 1] + oy);
    return s;
  }
  /// Every offset a candidate of level h covers lies within the excluded disc.
  bool whollyExcluded(int h, int ox, int oy) const {
    if (!exclude) return false;
    const double r = grid.resolution();
    const int span = (1 << h) - 1;
    for (int dx : {0, span})
      for (int dy : {0, span})
        if (std::hypot(cx + (ox + dx) * r - exclude->x, cy + (oy + dy) * r - exclude->y) >= exclude_radius)
          return false;
    return true;
  }
  /// The scores at level h of the four children of a candidate: offsets (ox, oy), (ox + s, oy), (ox, oy + s) and
  /// (ox + s, oy + s), in one pass over the query's cells (the four cells of a point lie close together).
  void childScores(int h, int angle, int ox, int oy, int s, long out[4]) const {
    const std::vector<int>& c = cells[static_cast<std::size_t>(angle)];
    // The level's fields in locals (the compiler cannot keep them in registers through grid.value's loads), the
    // cells in the level's storage coordinates.
    const CorrelationGrid::LevelView l = grid.level(h);
    const std::uint8_t* const data = l.data;
    const unsigned w = static_cast<unsigned>(l.w), rows = static_cast<unsigned>(l.rows);
    const int dx = ox + l.pad, dy = oy + l.pad;
    long s00 = 0, s10 = 0, s01 = 0, s11 = 0;
    const int* p = c.data();
    const int* const end = p + c.size();
    for (; p != end; p += 2) {
      const unsigned x0 = static_cast<unsigned>(p[0] + dx), y0 = static_cast<unsigned>(p[1] + dy);
      const unsigned x1 = x0 + static_cast<unsigned>(s), y1 = y0 + static_cast<unsigned>(s);
      const bool in_x0 = x0 < w, in_x1 = x1 < w;
      if (y0 < rows) {
        const std::uint8_t* row = data + static_cast<std::size_t>(y0) * w;
        if (in_x0) s00 += row[x0];
        if (in_x1) s10 += row[x1];
      }
      if (y1 < rows) {
        const std::uint8_t* row = data + static_cast<std::size_t>(y1) * w;
        if (in_x0) s01 += row[x0];
        if (in_x1) s11 += row[x1];
      }
    }
    out[0] = s00, out[1] = s10, out[2] = s01, out[3] = s11;
  }
  void descend(Candidate* first, Candidate* last, int h) {
    std::sort(first, last, [](const Candidate& a, const Candidate& b) {
      if (a.score != b.score) return a.score > b.score;
      if (a.angle != b.angle) return a.angle < b.angle;  // a total order: the result does not depend on sort details
      if (a.ox != b.ox) return a.ox < b.ox;
      return a.oy < b.oy;
    });
    for (const Candidate* it = first; it != last; ++it) {
      const Candidate& c = *it;
      if (c.score <= best.score) break;
      if (whollyExcluded(h, c.ox, c.oy)) continue;
      if (h == 0) {
        best = c;
        break;  // the list is sorted: the rest score less
      }
      const int s = 1 << (h - 1);
      long sums[4];
      childScores(h - 1, c.angle, c.ox, c.oy, s, sums);
      Candidate children[4];
      int n = 0, k = 0;
      for (int dy : {0, s})
        for (int dx : {0, s}) {
          const int ox = c.ox + dx, oy = c.oy + dy;
          const long sc = sums[k++];
          if (ox > wx || oy > wx) continue;
          children[n++] = {c.angle, ox, oy, sc};
        }
      descend(children, children + n, h - 1);
    }
  }
};

}  // namespace

std::optional<CorrelativeMatch> branchAndBoundSearch(const CorrelationGrid& grid, const std::vector<Point2>& query,
                                                     const SearchWindow& window, double min_score,
                                                     const Point2* exclude_center, double exclude_radius) {
  if (query.empty()) return std::nullopt;
  const double r = grid.resolution();
  double d_max = r;
  for (const Point2& q : query) d_max = std::max(d_max, std::hypot(q.x, q.y));
  // Hess et al. eq. 7: the angular step moves the furthest point by about one cell.
  const double dtheta = std::acos(std::max(-1.0, 1.0 - r * r / (2.0 * d_max * d_max)));
  const int n_theta = static_cast<int>(std::ceil(window.theta / dtheta));
  const int wx = static_cast<int>(std::ceil(window.xy / r));
  std::vector<std::vector<int>> cells(static_cast<std::size_t>(2 * n_theta + 1));
  for (int k = -n_theta; k <= n_theta; ++k) {
    const double th = window.center.theta + k * dtheta;
    const double c = std::cos(th), s = std::sin(th);
    std::vector<int>& out = cells[static_cast<std::size_t>(k + n_theta)];
    out.reserve(2 * query.size());
    for (const Point2& q : query) {
      out.push_back(grid.cellX(window.center.x + c * q.x - s * q.y));
      out.push_back(grid.cellY(window.center.y + s * q.x + c * q.y));
    }
  }
  const long n = static_cast<long>(query.size());
  const long threshold = static_cast<long>(std::ceil(min_score * 255.0 * static_cast<double>(n)));
  Search search{grid, cells, wx, exclude_center, exclude_radius, window.center.x, window.center.y,
                Candidate{-1, 0, 0, threshold - 1}};
  const int H = grid.depth();
  const int step = 1 << H;
  std::vector<Candidate> top;
  for (int a = 0; a < static_cast<int>(cells.size()); ++a)
    for (int oy = -wx; oy <= wx; oy += step)
      for (int ox = -wx; ox <= wx; ox += step) top.push_back({a, ox, oy, search.score(H, a, ox, oy)});
  search.descend(top.data(), top.data() + top.size(), H);
  if (search.best.angle < 0) return std::nullopt;
  CorrelativeMatch m;
  m.pose = {window.center.x + search.best.ox * r, window.center.y + search.best.oy * r,
            wrapAngle(window.center.theta + (search.best.angle - n_theta) * dtheta)};
  m.score = static_cast<double>(search.best.score) / (255.0 * static_cast<double>(n));
  return m;
}

}  // namespace gridtopo::slam
