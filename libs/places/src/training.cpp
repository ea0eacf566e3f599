#include "gridtopo/places/training.h"
#include "gridtopo/core/ini_value.h"

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>

#include "gridtopo/core/error.h"

namespace gridtopo::places {

LabelledMap loadLabelledMap(const std::string& name, const std::string& labels_path, const std::string& map_path,
                            double resolution) {
  LabelledMap m;
  m.name = name;
  cv::Mat lab = cv::imread(labels_path, cv::IMREAD_GRAYSCALE);
  if (lab.empty()) throw InputError(labels_path, "cannot read labelled map image");
  cv::Mat img = cv::imread(map_path, cv::IMREAD_UNCHANGED);
  if (img.empty()) throw InputError(map_path, "cannot read map image");
  m.occ = occupancyFromGrey(img, resolution, map_path);
  if (lab.size() != img.size())
    throw InputError(labels_path, "labelled map is " + std::to_string(lab.cols) + "x" + std::to_string(lab.rows) +
                                      " but the map " + map_path + " is " + std::to_string(img.cols) + "x" +
                                      std::to_string(img.rows));
  m.codes = lab;
  return m;
}

std::vector<LabelledMapFiles> standardLabelledMaps(const std::string& dir) {
  const std::string L = dir + "/labelled/", M = dir + "/maps/", G = dir + "/groundtruth/";
  auto e = [&](const std::string& name, const std::string& lab, const std::string& orig, const std::string& bench,
               const std::string& gt) {
    return LabelledMapFiles{name, L + lab + ".png", M + orig + ".png", M + bench, G + gt + "_gt_segmentation.png"};
  };
  return {
      e("Fr101", "training_Fr101", "Fr101_original", "Freiburg101_scan", "Freiburg101_scan"),
      e("Fr52", "training_Fr52", "Fr52_original", "Freiburg52_scan", "Freiburg52_scan"),
      e("NLB", "training_NLB_furniture", "NLB_original", "NLB", "NLB"),
      e("lab_intel", "training_intel", "lab_intel_original", "lab_intel", "lab_intel"),
      e("lab_c", "training_lab_c_furnitures", "lab_c_furnitures_original", "lab_c_scan", "lab_c_scan"),
      e("lab_d", "training_lab_d_furniture", "lab_d_furnitures_original", "lab_d_scan", "lab_d_scan"),
      e("lab_ipa", "training_lab_ipa", "lab_ipa_original", "lab_ipa", "lab_ipa"),
      e("office_e", "training_office_e", "office_e_original", "office_e", "office_e"),
      e("office_h", "training_office_h", "office_h_original", "office_h", "office_h"),
  };
}

std::string simulatedMapPath(const std::string& dir, const std::string& name) {
  return dir + "/" + name + "_sim_map.png";
}

std::optional<LabelledMap> loadSimulatedLabelledMap(const LabelledMapFiles& files, const TrainingOptions& o,
                                                    double resolution) {
  if (o.simulated_maps.empty()) return std::nullopt;
  const std::string path = simulatedMapPath(o.simulated_maps, files.name);
  if (!std::filesystem::is_regular_file(path)) return std::nullopt;
  LabelledMap m;
  m.name = files.name + "_sim";
  cv::Mat lab = cv::imread(files.labels, cv::IMREAD_GRAYSCALE);
  if (lab.empty()) throw InputError(files.labels, "cannot read labelled map image");
  cv::Mat img = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (img.empty()) throw InputError(path, "cannot read simulated map image");
  if (lab.size() != img.size())
    throw InputError(path, "simulated map is " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                               " but its plan's labels " + files.labels + " are " + std::to_string(lab.cols) + "x" +
                               std::to_string(lab.rows) + " (regenerate with gridtopo-simulate-maps)");
  m.occ = occupancyFromGrey(img, resolution, path, o.simulated_free_threshold);
  openFreeSpace(m.occ, o.simulated_free_opening_radius);
  m.codes = lab;
  return m;
}

MapSamples computeSamples(const OccupancyImage& occ, const cv::Mat* codes, const ScanSimulationOptions& scan,
                          const FeatureOptions& features,
                          const std::function<void(std::size_t, std::size_t)>& progress) {
  MapSamples s;
  s.lattice = buildLattice(occ, scan.lattice_spacing);
  const SimulatedScans scans = simulateScans(occ, s.lattice.samples, scan, progress);
  s.features = extractFeatures(scans, features, scan.threads);
  if (features.context_radius > 0)
    s.features = addContextFeatures(s.lattice, s.features, features.context_radius, occ.resolution);
  s.block_labels = cv::Mat(s.lattice.block_sample.size(), CV_32S, cv::Scalar(-1));
  s.labels.assign(s.lattice.samples.size(), -1);
  if (codes) {
    for (std::size_t i = 0; i < s.lattice.samples.size(); ++i) {
      const cv::Point p = s.lattice.samples[i];
      const int l = labelFromCode(codes->at<unsigned char>(p));
      s.labels[i] = l;
      s.block_labels.at<int>(s.lattice.blocks[i]) = l;
    }
  }
  return s;
}

TrainingConfig loadTrainingConfig(const std::string& ini_path) {
  TrainingConfig c;
  if (ini_path.empty()) return c;
  if (!std::filesystem::is_regular_file(ini_path)) throw InputError(ini_path, "INI file not found");
  const mrpt::config::CConfigFile f(ini_path);
  try {
    c.training.loadFromConfigFile(f, "training");
    c.scan.loadFromConfigFile(f, "scan_simulation");
  } catch (const InputError& e) {
    throw InputError(ini_path, 0, e.file() + " " + e.field(), e.message());
  }
  FeatureOptions& feat = c.features;
  readIniValue(f, "features", "beam_cap", feat.beam_cap);
  readIniValue(f, "features", "gap_small", feat.gap_small);
  readIniValue(f, "features", "gap_large", feat.gap_large);
  readIniValue(f, "features", "context_radius", feat.context_radius);
  {
    const std::string unset = "\x01";
    const std::string list = readIni(f, "features", "capped_ranges", unset);
    std::stringstream ss(list == unset ? "" : list);
    if (list != unset) feat.capped_ranges.clear();
    for (std::string tok; std::getline(ss, tok, ',');) {
      if (tok.find_first_not_of(" \t") == std::string::npos) continue;
      char* end = nullptr;
      const double v = std::strtod(tok.c_str(), &end);
      if (end == tok.c_str() || !std::isfinite(v) || v <= 0 || v > 65 ||
          (*end && std::string(end).find_first_not_of(" \t") != std::string::npos))
        throw InputError(ini_path, 0, "[features] capped_ranges", "must be a comma-separated list of ranges in (0, 65] metres, got '" + tok + "'");
      feat.capped_ranges.push_back(v);
    }
  }
  if (!(feat.context_radius >= 0 && feat.context_radius <= 10))
    throw InputError(ini_path, 0, "[features] context_radius", "must be in [0, 10] metres");
  return c;
}

void TrainingOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& s, const std::string& sec) {
  boost.loadFromConfigFile(s, sec);
  readIniValue(s, sec, "order", order);
  readIniValue(s, sec, "prior_weight", prior_weight);
  readIniValue(s, sec, "order_folds", order_folds);
  readIniValue(s, sec, "order_samples_per_class", order_samples_per_class);
  readIniValue(s, sec, "simulated_maps", simulated_maps);
  readIniValue(s, sec, "simulated_free_threshold", simulated_free_threshold);
  readIniValue(s, sec, "simulated_free_opening_radius", simulated_free_opening_radius);
  if (simulated_free_threshold < 1 || simulated_free_threshold > 255)
    throw InputError("[" + sec + "]", 0, "simulated_free_threshold", "must be in [1, 255]");
  if (!(simulated_free_opening_radius >= 0 && simulated_free_opening_radius <= 1))
    throw InputError("[" + sec + "]", 0, "simulated_free_opening_radius", "must be in [0, 1] metres");
  if (!simulated_maps.empty() && !std::filesystem::is_directory(simulated_maps))
    throw InputError("[" + sec + "]", 0, "simulated_maps", "directory '" + simulated_maps + "' not found");
  if (order_folds < 1 || order_folds > 20) throw InputError("[" + sec + "]", 0, "order_folds", "must be in [1, 20]");
  if (order_samples_per_class < 10)
    throw InputError("[" + sec + "]", 0, "order_samples_per_class", "must be >= 10");
  if (!(prior_weight >= 0 && prior_weight <= 2)) throw InputError("[" + sec + "]", 0, "prior_weight", "must be in [0, 2]");
}

void TrainingOptions::dumpToTextStream(std::ostream& out) const {
  boost.dumpToTextStream(out);
  out << "order                 = " << order << "\n"
      << "prior_weight          = " << prior_weight << "\n"
      << "order_folds           = " << order_folds << "\n"
      << "order_samples_per_class = " << order_samples_per_class << "\n"
      << "simulated_maps        = " << simulated_maps << "\n"
      << "simulated_free_threshold = " << simulated_free_threshold << "\n"
      << "simulated_free_opening_radius = " << simulated_free_opening_radius << "\n";
}

std::string orderName(const std::array<int, kNumLabels>& o) {
  return labelName(o[0]) + "," + labelName(o[1]) + "," + labelName(o[2]);
}

namespace {

struct Pool {
  cv::Mat features;
  std::vector<int> labels;
};

// Concatenates the labelled samples of `maps`, keeping at most `per_class` of each class (uniform random
// subset, deterministic for the seed).
Pool pool(const std::vector<const MapSamples*>& maps, int per_class, unsigned seed) {
  std::vector<std::pair<const MapSamples*, int>> by_class[kNumLabels];
  for (const MapSamples* m : maps)
    for (std::size_t i = 0; i < m->labels.size(); ++i)
      if (m->labels[i] >= 0) by_class[m->labels[i]].emplace_back(m, static_cast<int>(i));
  std::mt19937 rng(seed);
  Pool p;
  std::vector<std::pair<const MapSamples*, int>> chosen;
  for (auto& v : by_class) {
    std::shuffle(v.begin(), v.end(), rng);
    if (v.size() > static_cast<std::size_t>(per_class)) v.resize(static_cast<std::size_t>(per_class));
    chosen.insert(chosen.end(), v.begin(), v.end());
  }
  if (chosen.empty()) return p;
  p.features.create(static_cast<int>(chosen.size()), chosen.front().first->features.cols, CV_32F);
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    chosen[i].first->features.row(chosen[i].second).copyTo(p.features.row(static_cast<int>(i)));
    p.labels.push_back(chosen[i].first->labels[static_cast<std::size_t>(chosen[i].second)]);
  }
  return p;
}

// w/2 ln(N+ / N-) over all labelled samples of `maps` (positive = label `positive`, negative = `negative`
// or, if negative < 0, every other label).
double priorBias(const std::vector<const MapSamples*>& maps, int positive, int negative, double w) {
  double np = 0, nn = 0;
  for (const MapSamples* m : maps)
    for (int l : m->labels) {
      if (l < 0) continue;
      if (l == positive) np += 1;
      else if (negative < 0 || l == negative) nn += 1;
    }
  return np > 0 && nn > 0 ? 0.5 * w * std::log(np / nn) : 0.0;
}

BoostedClassifier trainBinary(const Pool& p, int positive, int negative, const BoostOptions& o) {
  std::vector<int> t(p.labels.size(), -1);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const int l = p.labels[i];
    if (l == positive) t[i] = 1;
    else if (negative < 0 || l == negative) t[i] = 0;
  }
  return trainBoostedClassifier(p.features, t, o);
}

std::array<int, kNumLabels> parseOrder(const std::string& s) {
  std::array<int, kNumLabels> o{};
  std::stringstream ss(s);
  std::string tok;
  int i = 0;
  while (std::getline(ss, tok, ',')) {
    if (i >= 3) break;
    int l = -1;
    for (int k = 0; k < kNumLabels; ++k)
      if (labelName(k) == tok) l = k;
    if (l < 0) throw InputError("TrainingOptions", 0, "order", "unknown label '" + tok + "'");
    o[static_cast<std::size_t>(i++)] = l;
  }
  if (i != 3 || o[0] == o[1] || o[1] == o[2] || o[0] == o[2])
    throw InputError("TrainingOptions", 0, "order", "must be 'auto' or three distinct labels, e.g. corridor,room,doorway");
  return o;
}

}  // namespace

PlacesModel trainModel(const std::vector<const MapSamples*>& maps, const ScanSimulationOptions& scan,
                       const FeatureOptions& features, const TrainingOptions& options,
                       std::vector<OrderScore>* validation, const std::function<void(const std::string&)>& log) {
  options.boost.validate();
  PlacesModel model;
  model.scan = scan;
  model.features = features;
  model.feature_names = featureNames(features);
  // Compatibilities from all labelled maps.
  std::array<std::array<double, kNumLabels>, kNumLabels> counts{};
  for (const MapSamples* m : maps) accumulateNeighbourCounts(m->block_labels, counts);
  model.compatibility = compatibilityFromCounts(counts);

  std::array<int, kNumLabels> order{1, 0, 2};
  if (options.order == "auto") {
    // Validation splits: fold f holds out the maps with index % k == f (k = order_folds; k = 1: the single split
    // of index % 3 == 2). Confusions of the three orders are summed over all held-out maps.
    const int k = std::max(1, std::min<int>(options.order_folds, static_cast<int>(maps.size())));
    double conf[kNumLabels][kNumLabels][kNumLabels] = {};  // [order a][truth][predicted]
    for (int f = 0; f < k; ++f) {
      std::vector<const MapSamples*> train, val;
      for (std::size_t i = 0; i < maps.size(); ++i) {
        const bool held = k == 1 ? (maps.size() >= 3 && i % 3 == 2) : static_cast<int>(i % static_cast<std::size_t>(k)) == f;
        (held ? val : train).push_back(maps[i]);
      }
      if (val.empty()) val = train;
      if (train.empty()) train = val;
      BoostOptions bo = options.boost;
      bo.max_samples_per_class = std::min(options.boost.max_samples_per_class, options.order_samples_per_class);
      const Pool tp = pool(train, bo.max_samples_per_class, bo.seed);
      BoostedClassifier one_vs_rest[kNumLabels], pair[kNumLabels][kNumLabels];
      for (int a = 0; a < kNumLabels; ++a) {
        if (log) log("validation " + std::to_string(f + 1) + "/" + std::to_string(k) + ": training " + labelName(a) + " vs rest");
        one_vs_rest[a] = trainBinary(tp, a, -1, bo);
      }
      for (int a = 0; a < kNumLabels; ++a)
        for (int b = a + 1; b < kNumLabels; ++b) {
          if (log) log("validation " + std::to_string(f + 1) + "/" + std::to_string(k) + ": training " + labelName(a) + " vs " + labelName(b));
          pair[a][b] = trainBinary(tp, a, b, bo);
          pair[b][a] = pair[a][b];
          for (auto& st : pair[b][a].stumps) st.left = -st.left, st.right = -st.right;
        }
      for (int a = 0; a < kNumLabels; ++a) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        // For the second stage the order of b and c does not matter (same classifier up to sign).
        PlacesModel trial = model;
        trial.order = {a, b, c};
        trial.first = one_vs_rest[a];
        trial.second = pair[b][c];
        trial.first.bias = priorBias(train, a, -1, options.prior_weight);
        trial.second.bias = priorBias(train, b, c, options.prior_weight);
        for (const MapSamples* m : val)
          for (std::size_t i = 0; i < m->labels.size(); ++i) {
            if (m->labels[i] < 0) continue;
            float p[3];
            trial.probabilities(m->features.ptr<float>(static_cast<int>(i)), p);
            const int pred = static_cast<int>(std::max_element(p, p + 3) - p);
            conf[a][m->labels[i]][pred] += 1;
          }
      }
    }
    double best = -1;
    for (int a = 0; a < kNumLabels; ++a) {
      double correct = 0, total = 0, bal = 0;
      for (int t = 0; t < kNumLabels; ++t) {
        double row = 0;
        for (int q = 0; q < kNumLabels; ++q) row += conf[a][t][q];
        correct += conf[a][t][t], total += row;
        bal += row > 0 ? conf[a][t][t] / row : 0;
      }
      OrderScore sc{{a, (a + 1) % 3, (a + 2) % 3}, total > 0 ? correct / total : 0, bal / kNumLabels};
      if (validation) validation->push_back(sc);
      if (log) log("order " + orderName(sc.order) + ": validation accuracy " + std::to_string(sc.accuracy) +
                   ", balanced " + std::to_string(sc.balanced_accuracy));
      if (sc.balanced_accuracy > best) best = sc.balanced_accuracy, order = sc.order;
    }
  } else {
    order = parseOrder(options.order);
  }
  model.order = order;
  const Pool all = pool(maps, options.boost.max_samples_per_class, options.boost.seed);
  if (log) log("training final decision list " + orderName(order) + " on all maps");
  model.first = trainBinary(all, order[0], -1, options.boost);
  model.second = trainBinary(all, order[1], order[2], options.boost);
  model.first.bias = priorBias(maps, order[0], -1, options.prior_weight);
  model.second.bias = priorBias(maps, order[1], order[2], options.prior_weight);
  return model;
}

}  // namespace gridtopo::places
