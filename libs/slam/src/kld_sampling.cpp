#include "gridtopo/slam/kld_sampling.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace gridtopo::slam {

double kldBound(std::size_t k, double epsilon, double z) {
  if (k <= 1) return 1.0;
  const double km1 = static_cast<double>(k - 1);
  const double a = 2.0 / (9.0 * km1);
  const double c = 1.0 - a + std::sqrt(a) * z;
  return km1 / (2.0 * epsilon) * c * c * c;
}

bool growOnFailedMatches(int failed, std::size_t n, std::size_t maximum, const KldOptions& o) {
  if (!o.adaptive() || n >= maximum || n == 0) return false;
  return static_cast<double>(failed) >= o.grow_failed_fraction * static_cast<double>(n);
}

std::size_t occupiedBins(const std::vector<Pose2>& poses, const std::vector<std::size_t>& which, double bin_xy,
                         double bin_theta) {
  std::vector<std::tuple<long long, long long, long long>> bins;
  bins.reserve(which.size());
  for (std::size_t i : which) {
    const Pose2& p = poses[i];
    bins.emplace_back(static_cast<long long>(std::floor(p.x / bin_xy)),
                      static_cast<long long>(std::floor(p.y / bin_xy)),
                      static_cast<long long>(std::floor(wrapAngle(p.theta) / bin_theta)));
  }
  std::sort(bins.begin(), bins.end());
  return static_cast<std::size_t>(std::unique(bins.begin(), bins.end()) - bins.begin());
}

std::size_t kldParticleCount(const std::vector<Pose2>& poses, const std::vector<std::size_t>& which,
                             const KldOptions& o, std::size_t maximum) {
  if (!o.adaptive()) return maximum;
  const double n = std::ceil(kldBound(occupiedBins(poses, which, o.bin_xy, o.bin_theta), o.epsilon, o.z));
  const std::size_t lo = std::min(static_cast<std::size_t>(o.min_particles), maximum);
  return std::clamp(static_cast<std::size_t>(std::min(n, 1e9)), lo, maximum);
}

}  // namespace gridtopo::slam
