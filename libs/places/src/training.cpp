#include "gridtopo/places/training.h"

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
#include "gridtopo/core/ini_file.h"

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

std::string simulatedTrajectoryPath(const std::string& dir, const std::string& name) {
  return dir + "/" + name + "_sim_trajectory.txt";
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
  // As strict as every -c file (IniFile): a text file, no key twice, unknown sections and keys refused with the
  // line and a "did you mean". Each section may be missing (its defaults).
  const IniFile layout = IniFile::read(ini_path);
  layout.requireOptionsFile({"scan_simulation", "features", "training"}, "");
  const std::string listed = "not an option of this section; see config-ini/topology_train.ini";
  layout.requireKnownKeys("scan_simulation", scanSimulationOptionSchema().keys(), listed);
  layout.requireKnownKeys("features", featureOptionSchema().keys(), listed);
  layout.requireKnownKeys("training", trainingOptionSchema().keys(), listed);
  const mrpt::config::CConfigFile f(ini_path);
  try {
    trainingOptionSchema().load(c.training, f, "training");
    scanSimulationOptionSchema().load(c.scan, f, "scan_simulation");
    featureOptionSchema().load(c.features, f, "features");
  } catch (const InputError& e) {
    throw layout.withLine(e);  // the tables name "[section] key" without the line
  }
  return c;
}

std::string trainingOptionsHelp() {
  return optionsHelp("scan_simulation", scanSimulationOptionSchema().describe({})) + "\n" +
         optionsHelp("features", featureOptionSchema().describe({})) + "\n" +
         optionsHelp("training", trainingOptionSchema().describe({}));
}

const OptionSchema<TrainingOptions>& trainingOptionSchema() {
  using O = TrainingOptions;
  static const OptionSchema<O> schema =
      OptionSchema<O>("gridtopo::places::TrainingOptions")
          .addAll(boostOptionSchema(), &O::boost)
          .add("order", &O::order, OptionRange::any(), "",
               "the decision list: auto (chosen by validation) or the order, e.g. corridor,room,doorway")
          .add("prior_weight", &O::prior_weight, OptionRange::closed(0, 2), "",
               "prior correction: 0 = class-balanced classifiers, 1 = shifted to the maps' class frequencies")
          .add("order_folds", &O::order_folds, OptionRange::closed(1, 20), "groups",
               "order choice: the maps split into this many validation groups (index modulo k)")
          .add("order_samples_per_class", &O::order_samples_per_class, OptionRange::atLeast(10), "samples",
               "order choice: at most this many samples per class for the validation classifiers")
          .add("simulated_maps", &O::simulated_maps, OptionRange::any(), "",
               "a directory of simulated SLAM-like maps NAME_sim_map.png of the labelled plans; empty = off")
          .add("simulated_free_threshold", &O::simulated_free_threshold, OptionRange::closed(1, 255), "grey",
               "the simulated maps: grey >= this is free")
          .add("simulated_free_opening_radius", &O::simulated_free_opening_radius, OptionRange::closed(0, 1), "m",
               "the simulated maps: the free space is opened with this radius")
          .rule("simulated_maps", [](const O& o) -> std::optional<std::string> {
            if (o.simulated_maps.empty() || std::filesystem::is_directory(o.simulated_maps)) return std::nullopt;
            return "directory '" + o.simulated_maps + "' not found";
          });
  return schema;
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
