#include "gridtopo/core/distance_transform.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

namespace gridtopo {

namespace {
// The lower envelope of the parabolas (x - p)^2 + f[p] over the columns p < n with used(p) (Felzenszwalb &
// Huttenlocher), in exact integers and doubles: v[0..k) the envelope's columns, z[j] where parabola j begins
// (z[0] = -inf, z[k] = inf). Returns k, 0 when no column is used.
template <class Used>
int lowerEnvelope(const std::vector<double>& f, int n, Used used, std::vector<int>& v, std::vector<double>& z,
                  double inf) {
  const auto sq = [](int x) { return static_cast<double>(x) * x; };
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (!used(q)) continue;
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -inf;
      z[1] = inf;
      continue;
    }
    const double fq = f[static_cast<std::size_t>(q)] + sq(q);
    for (;; --k) {
      const int p = v[static_cast<std::size_t>(k)];
      const double s = (fq - f[static_cast<std::size_t>(p)] - sq(p)) / (2.0 * (q - p));
      if (s > z[static_cast<std::size_t>(k)]) {
        ++k;
        v[static_cast<std::size_t>(k)] = q;
        z[static_cast<std::size_t>(k)] = s;
        z[static_cast<std::size_t>(k) + 1] = inf;
        break;
      }
    }
  }
  return k + 1;
}
}  // namespace

cv::Mat preciseDistance(const cv::Mat& mask) {
  CV_Assert(mask.type() == CV_8U);
  const int m = mask.rows, n = mask.cols;
  cv::Mat dst(m, n, CV_32F);
  if (m == 0 || n == 0) return dst;
  // Column pass: per column, the distance in cells to the nearest zero cell above or below (a column without one
  // counts on from m - 1: m and more mean none), kept as an int in the float's four bytes until the row pass.
  constexpr int kBlock = 64;  // columns per block
  const int blocks = (n + kBlock - 1) / kBlock;
  cv::parallel_for_(cv::Range(0, blocks), [&](const cv::Range& range) {
    std::vector<int> below(static_cast<std::size_t>(m) * kBlock);
    int dist[kBlock];
    for (int b = range.start; b < range.end; ++b) {
      const int c0 = b * kBlock, w = std::min(kBlock, n - c0);
      // Upwards: distance to the nearest zero at or below.
      std::fill(dist, dist + w, m - 1);
      for (int j = m - 1; j >= 0; --j) {
        const unsigned char* s = mask.ptr<unsigned char>(j) + c0;
        int* d = below.data() + static_cast<std::size_t>(j) * kBlock;
        for (int c = 0; c < w; ++c) d[c] = dist[c] = s[c] == 0 ? 0 : dist[c] + 1;
      }
      // Downwards: the nearer of that and the nearest zero above.
      std::fill(dist, dist + w, m - 1);
      for (int j = 0; j < m; ++j) {
        const int* d = below.data() + static_cast<std::size_t>(j) * kBlock;
        float* o = dst.ptr<float>(j) + c0;
        for (int c = 0; c < w; ++c) {
          dist[c] = std::min(dist[c] + 1, d[c]);
          std::memcpy(o + c, &dist[c], sizeof(int));
        }
      }
    }
  }, n * static_cast<double>(m) / (1 << 16));
  // Row pass: per row, the lower envelope of the parabolas (x - p)^2 + f(p) (Felzenszwalb & Huttenlocher), in
  // exact integers and doubles. OpenCV's float arithmetic (which this function once copied bit for bit) squares
  // the column index in a float: beyond 4 096 columns the squares are rounded and its envelope goes wrong (zero
  // cells 1 cell from the nearest zero, errors up to 2.8 cells on the hospital's 10 079-column map).
  constexpr double kInf = 1e15;  // a column without a zero cell (OpenCV's "infinite" square)
  cv::parallel_for_(cv::Range(0, m), [&](const cv::Range& range) {
    std::vector<double> f(static_cast<std::size_t>(n)), z(static_cast<std::size_t>(n) + 1);
    std::vector<int> v(static_cast<std::size_t>(n));
    for (int i = range.start; i < range.end; ++i) {
      float* d = dst.ptr<float>(i);
      for (int q = 0; q < n; ++q) {
        int c;
        std::memcpy(&c, d + q, sizeof(int));
        f[static_cast<std::size_t>(q)] = c >= m ? kInf : static_cast<double>(c) * c;
      }
      const auto sq = [](int x) { return static_cast<double>(x) * x; };
      lowerEnvelope(f, n, [](int) { return true; }, v, z, kInf);
      for (int q = 0, k2 = 0; q < n; ++q) {
        while (z[static_cast<std::size_t>(k2) + 1] < q) ++k2;
        const int p = v[static_cast<std::size_t>(k2)];
        d[q] = static_cast<float>(std::sqrt(sq(q - p) + f[static_cast<std::size_t>(p)]));
      }
    }
  });
  return dst;
}

cv::Mat withinDistance(const cv::Mat& mask, double max_distance) {
  CV_Assert(mask.type() == CV_8U);
  const int m = mask.rows, n = mask.cols;
  if (m == 0 || n == 0 || max_distance < 0) return cv::Mat(m, n, CV_8U, cv::Scalar(0));
  // The largest integer squared distance whose float root (as preciseDistance gives it) is within max_distance,
  // compared as cv::compare(preciseDistance(mask), max_distance, CMP_LE) does: the threshold rounded to a float
  // (0.3 / 0.05 = 5.999999999999999 is 6).
  const float limit = static_cast<float>(max_distance);
  const auto within = [&](long long d2) { return static_cast<float>(std::sqrt(static_cast<double>(d2))) <= limit; };
  long long max_sq = static_cast<long long>(std::floor(static_cast<double>(limit) * limit));
  while (max_sq > 0 && !within(max_sq)) --max_sq;
  while (within(max_sq + 1)) ++max_sq;
  int reach = 0;  // the largest vertical (or horizontal) distance that can be within: floor(sqrt(max_sq))
  while (static_cast<long long>(reach + 1) * (reach + 1) <= max_sq) ++reach;
  if (reach >= 255) {
    cv::Mat out;
    cv::compare(preciseDistance(mask), max_distance, out, cv::CMP_LE);
    return out;
  }
  const int cap = reach + 1;  // "further than reach"
  // Column pass: per cell, the vertical distance to the nearest zero cell of its column, capped at `cap`. The row
  // pass then writes each row's result over that row's distances (it reads no other row): one image in all.
  cv::Mat vert(m, n, CV_8U);
  {
    std::vector<unsigned char> run(static_cast<std::size_t>(n), static_cast<unsigned char>(cap));
    for (int y = 0; y < m; ++y) {
      const unsigned char* s = mask.ptr<unsigned char>(y);
      unsigned char* v = vert.ptr<unsigned char>(y);
      for (int x = 0; x < n; ++x) {
        const int up = std::min(run[static_cast<std::size_t>(x)] + 1, cap);
        run[static_cast<std::size_t>(x)] = v[x] = static_cast<unsigned char>(s[x] == 0 ? 0 : up);
      }
    }
    std::fill(run.begin(), run.end(), static_cast<unsigned char>(cap));
    for (int y = m - 1; y >= 0; --y) {
      const unsigned char* s = mask.ptr<unsigned char>(y);
      unsigned char* v = vert.ptr<unsigned char>(y);
      for (int x = 0; x < n; ++x) {
        const int down = std::min(run[static_cast<std::size_t>(x)] + 1, cap);
        run[static_cast<std::size_t>(x)] = static_cast<unsigned char>(s[x] == 0 ? 0 : down);
        v[x] = std::min(v[x], run[static_cast<std::size_t>(x)]);
      }
    }
  }
  // Row pass: a cell at vertical distance h from a zero cell reaches the cells of its row within
  // half[h] = floor(sqrt(max_sq - h^2)) columns; the union of those intervals, by a difference array.
  std::vector<int> half(static_cast<std::size_t>(cap) + 1, -1);
  for (int h = 0; h <= reach; ++h) {
    int w = 0;
    while (static_cast<long long>(w + 1) * (w + 1) + static_cast<long long>(h) * h <= max_sq) ++w;
    half[static_cast<std::size_t>(h)] = w;
  }
  cv::parallel_for_(cv::Range(0, m), [&](const cv::Range& rows) {
    std::vector<int> diff(static_cast<std::size_t>(n) + 1);
    for (int y = rows.start; y < rows.end; ++y) {
      std::fill(diff.begin(), diff.end(), 0);
      const unsigned char* v = vert.ptr<unsigned char>(y);
      for (int x = 0; x < n; ++x) {
        const int w = half[v[x]];
        if (w < 0) continue;
        ++diff[static_cast<std::size_t>(std::max(0, x - w))];
        --diff[static_cast<std::size_t>(std::min(n, x + w + 1))];
      }
      unsigned char* o = vert.ptr<unsigned char>(y);  // the row's distances are read: its result goes over them
      int on = 0;
      for (int x = 0; x < n; ++x) {
        on += diff[static_cast<std::size_t>(x)];
        o[x] = on > 0 ? 255 : 0;
      }
    }
  }, m / 64.0);
  return vert;
}

cv::Mat nearestZero(const cv::Mat& mask) {
  CV_Assert(mask.type() == CV_8U);
  const int m = mask.rows, n = mask.cols;
  cv::Mat out(m, n, CV_32S, cv::Scalar(-1));
  if (m == 0 || n == 0) return out;
  // Column pass: the nearest zero row of each cell's column (-1: none), row by row over whole rows.
  {
    std::vector<int> last(static_cast<std::size_t>(n), -1);
    for (int y = 0; y < m; ++y) {
      const unsigned char* s = mask.ptr<unsigned char>(y);
      int* o = out.ptr<int>(y);
      for (int x = 0; x < n; ++x) {
        if (s[x] == 0) last[static_cast<std::size_t>(x)] = y;
        o[x] = last[static_cast<std::size_t>(x)];  // the nearest at or above
      }
    }
    std::fill(last.begin(), last.end(), -1);
    for (int y = m - 1; y >= 0; --y) {
      const unsigned char* s = mask.ptr<unsigned char>(y);
      int* o = out.ptr<int>(y);
      for (int x = 0; x < n; ++x) {
        if (s[x] == 0) last[static_cast<std::size_t>(x)] = y;
        const int below = last[static_cast<std::size_t>(x)];
        if (below >= 0 && (o[x] < 0 || below - y < y - o[x])) o[x] = below;  // a tie keeps the upper one
      }
    }
  }
  // Row pass: per row, the lower envelope of the parabolas (q - p)^2 + (y - r(p))^2 over the columns p that have a
  // zero cell; each cell takes the envelope's parabola at it.
  cv::parallel_for_(cv::Range(0, m), [&](const cv::Range& range) {
    std::vector<int> r(static_cast<std::size_t>(n)), v(static_cast<std::size_t>(n));
    std::vector<double> f(static_cast<std::size_t>(n)), z(static_cast<std::size_t>(n) + 1);
    for (int y = range.start; y < range.end; ++y) {
      int* o = out.ptr<int>(y);
      std::copy(o, o + n, r.begin());
      for (int q = 0; q < n; ++q) {
        const long long dy = y - r[static_cast<std::size_t>(q)];
        if (r[static_cast<std::size_t>(q)] >= 0) f[static_cast<std::size_t>(q)] = static_cast<double>(dy * dy);
      }
      const auto has_zero = [&](int q) { return r[static_cast<std::size_t>(q)] >= 0; };
      if (lowerEnvelope(f, n, has_zero, v, z, 1e300) == 0) continue;  // no zero cell in any column: the row stays -1
      for (int q = 0, j = 0; q < n; ++q) {
        while (z[static_cast<std::size_t>(j) + 1] < q) ++j;
        const int p = v[static_cast<std::size_t>(j)];
        o[q] = r[static_cast<std::size_t>(p)] * n + p;
      }
    }
  });
  return out;
}

float preciseDistanceAt(const cv::Mat& mask, cv::Point p, int max_ring) {
  CV_Assert(mask.type() == CV_8U && p.inside(cv::Rect(0, 0, mask.cols, mask.rows)));
  long long best = mask.at<unsigned char>(p) == 0 ? 0 : std::numeric_limits<long long>::max();
  const int edge = std::max({p.x, p.y, mask.cols - 1 - p.x, mask.rows - 1 - p.y});
  const int far = max_ring >= 0 ? std::min(edge, max_ring) : edge;
  for (int r = 1; r <= far && static_cast<long long>(r) * r < best; ++r) {
    const int x0 = std::max(0, p.x - r), x1 = std::min(mask.cols - 1, p.x + r);
    const auto look = [&](int x, int y) {
      if (mask.at<unsigned char>(y, x)) return;
      const long long dx = x - p.x, dy = y - p.y;
      best = std::min(best, dx * dx + dy * dy);
    };
    if (p.y - r >= 0) for (int x = x0; x <= x1; ++x) look(x, p.y - r);
    if (p.y + r < mask.rows) for (int x = x0; x <= x1; ++x) look(x, p.y + r);
    // The sides without the corners (the rows above did them when they lie inside the image).
    const int ys = std::max(0, p.y - r + 1), ye = std::min(mask.rows - 1, p.y + r - 1);
    if (p.x - r >= 0) for (int y = ys; y <= ye; ++y) look(p.x - r, y);
    if (p.x + r < mask.cols) for (int y = ys; y <= ye; ++y) look(p.x + r, y);
  }
  if (best == std::numeric_limits<long long>::max()) {
    // None within max_ring (the image goes on beyond it): further than that.
    if (far < edge) return std::numeric_limits<float>::infinity();
    // No zero cell at all: preciseDistance's value for that (its "infinite" square, 1e15, before the root).
    return static_cast<float>(std::sqrt(1e15));
  }
  return static_cast<float>(std::sqrt(static_cast<double>(best)));
}

}  // namespace gridtopo
