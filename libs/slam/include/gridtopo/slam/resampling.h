#pragma once
// Adaptive resampling (Doucet et al. 2000; Grisetti et al. 2007, section V): N_eff = 1 / Σ w̃², and
// low-variance (systematic) resampling (Thrun et al., Probabilistic Robotics, table 4.4).
#include <cstddef>
#include <vector>

#include "gridtopo/slam/random.h"

namespace gridtopo::slam {

/// Normalised weights w̃_i = exp(lw_i) / Σ exp(lw) from log-weights (stable for any offset).
std::vector<double> normalizedWeights(const std::vector<double>& log_weights);
/// N_eff = 1 / Σ w̃² of normalised weights.
double effectiveSampleSize(const std::vector<double>& normalized);
/// Indices of the particles to keep (one per new particle, sorted), drawn with a single random offset.
std::vector<std::size_t> lowVarianceResample(const std::vector<double>& normalized, Rng& rng);
/// The same with `count` new particles (any count >= 1; the adaptive particle set, kld_sampling.h): the offset is
/// the same first draw of `rng`, the comb's teeth 1 / count apart.
std::vector<std::size_t> lowVarianceResample(const std::vector<double>& normalized, Rng& rng, std::size_t count);

}  // namespace gridtopo::slam
