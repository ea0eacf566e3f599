#include "gridtopo/slam/resampling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gridtopo::slam {

std::vector<double> normalizedWeights(const std::vector<double>& log_weights) {
  double m = -std::numeric_limits<double>::infinity();
  for (double x : log_weights) m = std::max(m, x);
  std::vector<double> w(log_weights.size());
  double s = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) s += (w[i] = std::exp(log_weights[i] - m));
  for (double& x : w) x /= s;
  return w;
}

double effectiveSampleSize(const std::vector<double>& normalized) {
  double s = 0.0;
  for (double w : normalized) s += w * w;
  return s > 0.0 ? 1.0 / s : 0.0;
}

std::vector<std::size_t> lowVarianceResample(const std::vector<double>& normalized, Rng& rng) {
  return lowVarianceResample(normalized, rng, normalized.size());
}

std::vector<std::size_t> lowVarianceResample(const std::vector<double>& normalized, Rng& rng, std::size_t count) {
  const std::size_t n = normalized.size();
  std::vector<std::size_t> out;
  out.reserve(count);
  if (n == 0 || count == 0) return out;
  const double step = 1.0 / static_cast<double>(count);
  const double r = rng.uniform() * step;
  double c = normalized[0];
  std::size_t i = 0;
  for (std::size_t m = 0; m < count; ++m) {
    const double u = r + static_cast<double>(m) * step;
    while (u > c && i + 1 < n) c += normalized[++i];
    out.push_back(i);
  }
  return out;
}

}  // namespace gridtopo::slam
