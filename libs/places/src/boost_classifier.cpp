#include "gridtopo/places/boost_classifier.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <opencv2/ml.hpp>
#include <stdexcept>

#include "gridtopo/core/error.h"

namespace gridtopo::places {

double BoostedClassifier::probability(const float* f) const {
  return 1.0 / (1.0 + std::exp(-2.0 * score(f)));
}

const OptionSchema<BoostOptions>& boostOptionSchema() {
  using O = BoostOptions;
  const auto word = [](const char* w) { return std::pair<std::string, std::string>(w, w); };
  static const OptionSchema<O> schema =
      OptionSchema<O>("gridtopo::places::BoostOptions")
          .add("weak_count", &O::weak_count, OptionRange::closed(1, 10000), "stumps",
               "weak classifiers per binary classifier")
          .addWords<std::string>("boost_type", field(&O::boost_type),
                                 {word("real"), word("discrete"), word("gentle"), word("logit")},
                                 "OpenCV's boosting variant (cv::ml::Boost::Types)")
          .add("max_samples_per_class", &O::max_samples_per_class, OptionRange::atLeast(10), "samples",
               "class balancing: at most this many training samples per place class")
          .add("seed", &O::seed, OptionRange::any(), "", "seed of the subsampling")
          .add("weight_trim_rate", &O::weight_trim_rate, OptionRange::closed(0, 1), "",
               "OpenCV's weight trimming (speed); 0 = every sample in every round");
  return schema;
}


BoostedClassifier trainBoostedClassifier(const cv::Mat& features, const std::vector<int>& target,
                                         const BoostOptions& options) {
  options.validate();
  if (features.type() != CV_32F || static_cast<std::size_t>(features.rows) != target.size())
    throw std::invalid_argument("trainBoostedClassifier: features must be CV_32F with one row per target");
  std::vector<int> rows;
  std::size_t npos = 0, nneg = 0;
  for (std::size_t i = 0; i < target.size(); ++i) {
    if (target[i] < 0) continue;
    rows.push_back(static_cast<int>(i));
    (target[i] ? npos : nneg)++;
  }
  if (npos == 0 || nneg == 0) throw std::invalid_argument("trainBoostedClassifier: need samples of both classes");
  cv::Mat X(static_cast<int>(rows.size()), features.cols, CV_32F), y(X.rows, 1, CV_32S), w(X.rows, 1, CV_32F);
  for (int i = 0; i < X.rows; ++i) {
    features.row(rows[static_cast<std::size_t>(i)]).copyTo(X.row(i));
    const int t = target[static_cast<std::size_t>(rows[static_cast<std::size_t>(i)])];
    y.at<int>(i) = t;
    w.at<float>(i) = static_cast<float>(0.5 / static_cast<double>(t ? npos : nneg) * X.rows);
  }
  cv::Mat var_type(features.cols + 1, 1, CV_8U, cv::Scalar(cv::ml::VAR_ORDERED));
  var_type.at<unsigned char>(features.cols) = cv::ml::VAR_CATEGORICAL;
  auto data = cv::ml::TrainData::create(X, cv::ml::ROW_SAMPLE, y, cv::noArray(), cv::noArray(), w, var_type);
  auto boost = cv::ml::Boost::create();
  const int type = options.boost_type == "discrete" ? cv::ml::Boost::DISCRETE
                   : options.boost_type == "gentle" ? cv::ml::Boost::GENTLE
                   : options.boost_type == "logit"  ? cv::ml::Boost::LOGIT
                                                    : cv::ml::Boost::REAL;
  boost->setBoostType(type);
  boost->setWeakCount(options.weak_count);
  boost->setMaxDepth(1);
  boost->setWeightTrimRate(options.weight_trim_rate);
  boost->setUseSurrogates(false);
  boost->setCVFolds(0);
  boost->setMinSampleCount(2);
  if (!boost->train(data)) throw std::runtime_error("trainBoostedClassifier: OpenCV Boost training failed");

  // Copy the stumps out. OpenCV: at an ordered split a sample goes left iff value <= c (reversed if
  // `inversed`); a positive raw sum means the second class label (1).
  BoostedClassifier clf;
  const auto& nodes = boost->getNodes();
  const auto& splits = boost->getSplits();
  for (int root : boost->getRoots()) {
    const auto& n = nodes[static_cast<std::size_t>(root)];
    Stump s;
    if (n.split < 0 || n.left < 0 || n.right < 0) {  // a single-leaf tree: constant
      s.feature = 0, s.threshold = 0, s.left = s.right = static_cast<float>(n.value);
    } else {
      const auto& sp = splits[static_cast<std::size_t>(n.split)];
      s.feature = sp.varIdx;
      s.threshold = sp.c;
      float l = static_cast<float>(nodes[static_cast<std::size_t>(n.left)].value);
      float r = static_cast<float>(nodes[static_cast<std::size_t>(n.right)].value);
      if (sp.inversed) std::swap(l, r);
      s.left = l, s.right = r;
    }
    clf.stumps.push_back(s);
  }
  return clf;
}

}  // namespace gridtopo::places
