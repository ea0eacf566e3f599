#pragma once
// A trained place classifier: the decision list of two binary AdaBoost classifiers (Mozos et al.: first
// "class A vs the rest", then "class B vs class C"), the scan/feature settings it was trained with, and the
// relaxation compatibilities learned from the same labelled maps. One file (OpenCV FileStorage YAML/JSON).
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "gridtopo/places/boost_classifier.h"
#include "gridtopo/places/features.h"
#include "gridtopo/places/relaxation.h"
#include "gridtopo/places/scan_simulation.h"

namespace gridtopo::places {

struct PlacesModel {
  static constexpr const char* kFormat = "gridtopo-places-model";
  /// 2: features.capped_ranges (the "_cap<R>" feature copies) is stored.
  /// Version-1 files (no capped copies) still load: their feature set is the base set, which this build computes.
  static constexpr int kVersion = 2;

  ScanSimulationOptions scan;         ///< scans must be simulated as in training (beams, range, lattice)
  FeatureOptions features;
  std::vector<std::string> feature_names;  ///< must equal featureNames() of the running code
  std::array<int, kNumLabels> order{1, 0, 2};  ///< decision list: order[0] vs rest, then order[1] vs order[2]
  BoostedClassifier first, second;
  Compatibility compatibility{};
  std::string notes;                  ///< provenance: training maps, validation scores

  /// P(l | f) for the three labels: P(order0) = p1, P(order1) = (1 - p1) p2, P(order2) = (1 - p1)(1 - p2).
  void probabilities(const float* f, float* out) const;
  /// Rows of `features` -> CV_32FC3 column (n x 1) of distributions.
  cv::Mat classify(const cv::Mat& features, int threads = 2) const;

  void save(const std::string& path) const;
  /// Throws gridtopo::InputError for a missing file, a file of another kind, another version, or features
  /// that do not match this build.
  static PlacesModel load(const std::string& path);
};

}  // namespace gridtopo::places
