#pragma once
// Probabilistic relaxation labelling (Rosenfeld, Hummel, Zucker 1976), as used by Mozos et al. to smooth the
// per-cell classification:  q_i(l) = sum_j d_ij sum_l' r(l, l') P_j(l'),
//                           P_i(l) <- P_i(l) (1 + q_i(l)) / sum_m P_i(m) (1 + q_i(m)),
// on a (2R+1)^2 neighbourhood of the classification lattice (R = 1: the 8-neighbourhood), d_ij = 1 / |N(i)|.
#include <mrpt/config/CLoadableOptions.h>

#include <array>
#include <opencv2/core.hpp>
#include <vector>

#include "gridtopo/core/option_schema.h"
#include "gridtopo/places/place_label.h"

namespace gridtopo::places {

using Compatibility = std::array<std::array<double, kNumLabels>, kNumLabels>;

struct RelaxationOptions : public mrpt::config::CLoadableOptions {
  int max_iterations = 30;   ///< upper bound on iterations (0 = no relaxation)
  double tolerance = 1e-3;   ///< stop when no probability changes by more than this in an iteration
  /// N(i) = the lattice cells within this Chebyshev distance (1 = the 8-neighbourhood), d_ij = 1 / |N(i)|
  int neighbourhood_radius = 1;

  void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  /// Every key, loadable by loadFromConfigFile to the same values (doubles to 17 digits).
  void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  void dumpToTextStream(std::ostream& out) const override;
  /// InputError(file, 0, "[section] key", ...) for a value out of its range.
  void validate(const std::string& file = "<options>", const std::string& section = "relaxation") const;
};

/// The key table of [relaxation] (load, save, dump, validation, help, the GUI's grid).
const OptionSchema<RelaxationOptions>& relaxationOptionSchema();

/// Counts of label pairs over 8-neighbour pairs of a label grid (CV_32S, -1 = no label).
void accumulateNeighbourCounts(const cv::Mat& labels, std::array<std::array<double, kNumLabels>, kNumLabels>& counts);

/// r(l, l') = normalised pointwise mutual information of neighbouring labels:
/// ln(P(l,l') / (P(l) P(l'))) / -ln P(l,l'), in [-1, 1] (-1 for pairs never seen together).
Compatibility compatibilityFromCounts(const std::array<std::array<double, kNumLabels>, kNumLabels>& counts);

struct RelaxationResult {
  int iterations = 0;
  double last_change = 0;  ///< max |delta P| of the last iteration
  bool converged = false;
};

/// Relaxes `probs` (CV_32FC3 lattice grid, one distribution per cell) in place over cells where
/// `valid` (CV_8U) is non-zero. Deterministic (Jacobi updates); `threads` only changes speed.
RelaxationResult relaxLabels(cv::Mat& probs, const cv::Mat& valid, const Compatibility& r,
                             const RelaxationOptions& options, int threads = 2);

/// The part of a lattice grid of `grid` blocks that relaxLabels relaxes when the valid blocks fill `valid_blocks`
/// (their bounding box): that box widened by the neighbourhood and one block more, within the grid (outside it no
/// block is valid, so every sum the box reads is the whole grid's); the whole grid when `valid_blocks` is empty. A
/// grid of that part alone relaxes to the very same values.
cv::Rect relaxationBox(cv::Rect valid_blocks, cv::Size grid, const RelaxationOptions& options);

}  // namespace gridtopo::places
