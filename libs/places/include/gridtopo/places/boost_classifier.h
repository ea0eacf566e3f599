#pragma once
// Binary AdaBoost with decision stumps (Mozos et al. 2005, after Viola & Jones / Friedman, Hastie, Tibshirani):
// H(f) = sum_t h_t(f), each h_t a stump on one feature; P(positive | f) = e^H / (e^H + e^-H).
// Training uses OpenCV's ml::Boost (max depth 1); the learned stumps are copied out so a model is a plain,
// readable list and prediction is a fast loop.
#include <mrpt/config/CLoadableOptions.h>

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "gridtopo/core/option_schema.h"

namespace gridtopo::places {

/// h(f) = f[feature] <= threshold ? left : right.
struct Stump {
  int feature = 0;
  float threshold = 0;
  float left = 0, right = 0;
};

struct BoostedClassifier {
  std::vector<Stump> stumps;
  /// Prior correction added to H: training is class-balanced, so bias = w/2 ln(N+ / N-) restores the class
  /// frequencies of the labelled maps (w = TrainingOptions::prior_weight).
  double bias = 0;
  double score(const float* f) const {
    double h = bias;
    for (const Stump& s : stumps) h += f[s.feature] <= s.threshold ? s.left : s.right;
    return h;
  }
  /// P(positive | f) = 1 / (1 + e^{-2H}).
  double probability(const float* f) const;
};

struct BoostOptions;
/// The key table of BoostOptions.
const OptionSchema<BoostOptions>& boostOptionSchema();

/// Through boostOptionSchema (in a training INI, its keys stand in [training]: trainingOptionSchema).
struct BoostOptions : TableOptions<BoostOptions, boostOptionSchema> {
  static constexpr const char* kSection = "training";
  int weak_count = 100;              ///< number of stumps per binary classifier
  std::string boost_type = "real";   ///< real | discrete | gentle | logit (OpenCV Boost::Types)
  int max_samples_per_class = 15000; ///< class balancing: at most this many training samples per place class
  unsigned seed = 1;                 ///< subsampling seed
  double weight_trim_rate = 0.95;    ///< OpenCV weight trimming (speed); 0 = use every sample in every round
};

/// Trains positive (1) vs negative (0) on rows of `features` (CV_32F). Rows with target < 0 are ignored.
/// Classes are balanced by sample weights (each class carries half of the total weight).
/// Throws std::invalid_argument if either class has no sample.
BoostedClassifier trainBoostedClassifier(const cv::Mat& features, const std::vector<int>& target,
                                         const BoostOptions& options);

}  // namespace gridtopo::places
