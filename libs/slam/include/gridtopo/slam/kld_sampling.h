#pragma once
// KLD-sampling: how many particles a resampled set needs (Fox, "Adapting the sample size in particle filters
// through KLD-sampling", IJRR 22(12), 2003). With k histogram bins holding the posterior's support, n samples
// keep the Kullback-Leibler distance between the sample-based and the true (binned) posterior below epsilon with
// probability 1 - delta when
//   n = (k - 1) / (2 epsilon) · (1 - 2 / (9 (k - 1)) + sqrt(2 / (9 (k - 1))) · z_{1-delta})³   (Fox, eq. 13).
// Here the bins are cells of (x, y, θ) over the particles the low-variance resampler would keep with the full
// (maximum) count, and the new count is that n, clamped to [minimum, maximum].
#include <cstddef>
#include <vector>

#include "gridtopo/slam/pose2.h"

namespace gridtopo::slam {

/// The tunables of the adaptive particle set (keys of [slam]: min_particles, kld_epsilon, kld_z, kld_bin_xy,
/// kld_bin_theta).
struct KldOptions {
  int min_particles = 0;      ///< 0: a fixed particle count (`particles`); else the smallest count after resampling
  double epsilon = 0.15;      ///< bound on the KL distance between the particles and the binned posterior
  double z = 2.326;           ///< upper 1 - delta quantile of the standard normal (2.326: delta = 0.01)
  double bin_xy = 0.1;        ///< m, bin size in x and y
  double bin_theta = 0.1;     ///< rad, bin size in heading
  /// Ambiguity the pose bins do not show: when at least this share of the particles' scan matches failed at a step
  /// (they took the odometry proposal), the set is resampled to the maximum at once. > 1: never.
  double grow_failed_fraction = 0.25;
  bool adaptive() const { return min_particles > 0; }
};

/// Whether a step with `failed` of `n` particles' matches failed calls for the maximum count (KldOptions::
/// grow_failed_fraction; never when the set is not adaptive or already at the maximum).
bool growOnFailedMatches(int failed, std::size_t n, std::size_t maximum, const KldOptions& o);
/// Fox's bound (above) for k occupied bins; 1 for k <= 1 (one bin needs no spread).
double kldBound(std::size_t k, double epsilon, double z);
/// Distinct (x, y, θ) bins of `poses[i]` over the indices `which` (heading wrapped to [-π, π) first).
std::size_t occupiedBins(const std::vector<Pose2>& poses, const std::vector<std::size_t>& which, double bin_xy,
                         double bin_theta);
/// The particle count after resampling: ceil(kldBound(k)) of the bins the kept particles `which` occupy, clamped to
/// [o.min_particles, maximum]; `maximum` when the set is not adaptive.
std::size_t kldParticleCount(const std::vector<Pose2>& poses, const std::vector<std::size_t>& which,
                             const KldOptions& o, std::size_t maximum);

}  // namespace gridtopo::slam
