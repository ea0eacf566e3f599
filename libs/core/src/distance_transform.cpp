#include "gridtopo/core/distance_transform.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace gridtopo {

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
      int k = 0;
      v[0] = 0;
      z[0] = -kInf;
      z[1] = kInf;
      for (int q = 1; q < n; ++q) {
        const double fq = f[static_cast<std::size_t>(q)] + sq(q);
        for (;; --k) {
          const int p = v[static_cast<std::size_t>(k)];
          const double s = (fq - f[static_cast<std::size_t>(p)] - sq(p)) / (2.0 * (q - p));
          if (s > z[static_cast<std::size_t>(k)]) {
            ++k;
            v[static_cast<std::size_t>(k)] = q;
            z[static_cast<std::size_t>(k)] = s;
            z[static_cast<std::size_t>(k) + 1] = kInf;
            break;
          }
        }
      }
      for (int q = 0, k2 = 0; q < n; ++q) {
        while (z[static_cast<std::size_t>(k2) + 1] < q) ++k2;
        const int p = v[static_cast<std::size_t>(k2)];
        d[q] = static_cast<float>(std::sqrt(sq(q - p) + f[static_cast<std::size_t>(p)]));
      }
    }
  });
  return dst;
}

}  // namespace gridtopo
