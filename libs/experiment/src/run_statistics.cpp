#include "gridtopo/experiment/run_statistics.h"

#include <algorithm>
#include <cmath>

namespace gridtopo::experiment {

Spread Spread::of(std::vector<double> values) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }), values.end());
  Spread s;
  s.count = values.size();
  if (values.empty()) {
    s.mean = s.std = s.median = s.min = s.max = NAN;
    return s;
  }
  std::sort(values.begin(), values.end());
  double sum = 0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(values.size());
  if (values.size() > 1) {
    double ss = 0;
    for (double v : values) ss += (v - s.mean) * (v - s.mean);
    s.std = std::sqrt(ss / static_cast<double>(values.size() - 1));
  }
  const std::size_t n = values.size();
  s.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  s.min = values.front();
  s.max = values.back();
  return s;
}

int successOf(const ExperimentSpec& spec, const RunRecord& r) {
  if (!r.ok()) return 0;
  if (!r.hasErrors()) return -1;
  double v = r.trans_mean;
  switch (spec.success_metric) {
    case SuccessMetric::TransMean: v = r.trans_mean; break;
    case SuccessMetric::TransMax: v = r.trans_max; break;
    case SuccessMetric::RotMean: v = r.rot_mean; break;
    case SuccessMetric::RotMax: v = r.rot_max; break;
  }
  return v <= spec.success_threshold ? 1 : 0;
}

std::vector<RunGroup> groupRuns(const std::vector<RunRecord>& records, const std::vector<std::string>& keys) {
  std::vector<RunGroup> groups;
  for (const auto& r : records) {
    Assignment key;
    for (const auto& k : keys) key.emplace_back(k, valueOf(r.params, k, k == "dataset" ? r.dataset : ""));
    auto it = std::find_if(groups.begin(), groups.end(), [&](const RunGroup& g) { return g.key == key; });
    if (it == groups.end()) {
      groups.push_back({key, {}});
      it = groups.end() - 1;
    }
    it->runs.push_back(&r);
  }
  return groups;
}

std::vector<std::string> keysBut(const std::vector<std::string>& keys, const std::vector<std::string>& except) {
  std::vector<std::string> out;
  for (const auto& k : keys)
    if (std::find(except.begin(), except.end(), k) == except.end()) out.push_back(k);
  return out;
}

}  // namespace gridtopo::experiment
