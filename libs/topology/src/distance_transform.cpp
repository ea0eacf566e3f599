#include "gridtopo/topology/distance_transform.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace gridtopo::topology {

cv::Mat preciseDistance(const cv::Mat& mask) {
  CV_Assert(mask.type() == CV_8U);
  const int m = mask.rows, n = mask.cols;
  cv::Mat dst(m, n, CV_32F);
  if (m == 0 || n == 0) return dst;
  constexpr float kInf = 1e15f;
  // Column pass: per column, the distance in cells to the nearest zero cell above or below (a column without one
  // counts on from m - 1), as a float square from a table (i * i below m, "infinite" from m on).
  std::vector<float> col_sq(static_cast<std::size_t>(2 * m));
  for (int i = 0; i < m; ++i) col_sq[static_cast<std::size_t>(i)] = static_cast<float>(i * i);
  for (int i = m; i < 2 * m; ++i) col_sq[static_cast<std::size_t>(i)] = kInf;
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
          o[c] = col_sq[static_cast<std::size_t>(dist[c])];
        }
      }
    }
  }, n * static_cast<double>(m) / (1 << 16));
  // Row pass: per row, the lower envelope of the parabolas (x - p)^2 + f(p), OpenCV's float arithmetic in its order.
  std::vector<float> sq(static_cast<std::size_t>(n)), inv(static_cast<std::size_t>(n));
  sq[0] = 0.f, inv[0] = 0.f;
  for (int i = 1; i < n; ++i) {
    inv[static_cast<std::size_t>(i)] = static_cast<float>(0.5 / i);
    sq[static_cast<std::size_t>(i)] = static_cast<float>(i * i);
  }
  cv::parallel_for_(cv::Range(0, m), [&](const cv::Range& range) {
    std::vector<float> f(static_cast<std::size_t>(n)), z(static_cast<std::size_t>(n) + 1);
    std::vector<int> v(static_cast<std::size_t>(n));
    for (int i = range.start; i < range.end; ++i) {
      float* d = dst.ptr<float>(i);
      int p, q, k;
      v[0] = 0;
      z[0] = -kInf;
      z[1] = kInf;
      f[0] = d[0];
      for (q = 1, k = 0; q < n; ++q) {
        const float fq = d[q];
        f[static_cast<std::size_t>(q)] = fq;
        const float fq_sq = fq + sq[static_cast<std::size_t>(q)];
        for (;; --k) {
          p = v[static_cast<std::size_t>(k)];
          const float s = (fq_sq - d[p] - sq[static_cast<std::size_t>(p)]) * inv[static_cast<std::size_t>(q - p)];
          if (s > z[static_cast<std::size_t>(k)]) {
            ++k;
            v[static_cast<std::size_t>(k)] = q;
            z[static_cast<std::size_t>(k)] = s;
            z[static_cast<std::size_t>(k) + 1] = kInf;
            break;
          }
        }
      }
      for (q = 0, k = 0; q < n; ++q) {
        while (z[static_cast<std::size_t>(k) + 1] < static_cast<float>(q)) ++k;
        p = v[static_cast<std::size_t>(k)];
        d[q] = std::sqrt(sq[static_cast<std::size_t>(std::abs(q - p))] + f[static_cast<std::size_t>(p)]);
      }
    }
  });
  return dst;
}

}  // namespace gridtopo::topology
