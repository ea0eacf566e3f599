#include "gridtopo/places/model.h"

#include <cmath>
#include <filesystem>
#include <thread>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"

namespace gridtopo::places {

void PlacesModel::probabilities(const float* f, float* out) const {
  const double p1 = first.probability(f), p2 = second.probability(f);
  out[order[0]] = static_cast<float>(p1);
  out[order[1]] = static_cast<float>((1 - p1) * p2);
  out[order[2]] = static_cast<float>((1 - p1) * (1 - p2));
}

cv::Mat PlacesModel::classify(const cv::Mat& features, int threads) const {
  CV_Assert(features.type() == CV_32F);
  cv::Mat out(features.rows, 1, CV_32FC3);
  auto work = [&](int b, int e) {
    for (int i = b; i < e; ++i) probabilities(features.ptr<float>(i), out.ptr<float>(i));
  };
  const int nt = std::max(1, threads);
  std::vector<std::thread> pool;
  for (int t = 1; t < nt; ++t) pool.emplace_back(work, features.rows * t / nt, features.rows * (t + 1) / nt);
  work(0, features.rows / nt);
  for (auto& t : pool) t.join();
  return out;
}

namespace {
void writeClassifier(cv::FileStorage& fs, const std::string& name, const BoostedClassifier& c) {
  fs << name + "_bias" << c.bias;
  fs << name << "[";
  for (const auto& s : c.stumps)
    fs << "{" << "feature" << s.feature << "threshold" << s.threshold << "left" << s.left << "right" << s.right << "}";
  fs << "]";
}
BoostedClassifier readClassifier(const cv::FileNode& n, std::size_t nfeat, const std::string& path,
                                 const std::string& name) {
  if (!n.isSeq()) throw InputError(path, 0, name, "missing classifier");
  BoostedClassifier c;
  for (const auto& s : n) {
    Stump st;
    st.feature = static_cast<int>(s["feature"]);
    st.threshold = static_cast<float>(s["threshold"]);
    st.left = static_cast<float>(s["left"]);
    st.right = static_cast<float>(s["right"]);
    if (st.feature < 0 || static_cast<std::size_t>(st.feature) >= nfeat)
      throw InputError(path, 0, name, "stump uses feature " + std::to_string(st.feature) + " out of range");
    c.stumps.push_back(st);
  }
  if (c.stumps.empty()) throw InputError(path, 0, name, "classifier has no stumps");
  for (const Stump& s : c.stumps)
    if (!std::isfinite(s.threshold) || !std::isfinite(s.left) || !std::isfinite(s.right))
      throw InputError(path, 0, name, "non-finite stump value");
  return c;
}
}  // namespace

void PlacesModel::save(const std::string& path) const {
  writeFileAtomically(path, [&](const std::string& tmp) {
    cv::FileStorage fs(tmp, cv::FileStorage::WRITE);
    if (!fs.isOpened()) throw std::runtime_error("cannot write " + path);
    fs << "format" << kFormat << "version" << kVersion;
    fs << "num_beams" << scan.num_beams << "max_range" << scan.max_range << "lattice_spacing" << scan.lattice_spacing;
    fs << "unknown_cells" << beamStopName(scan.unknown_cells) << "map_border" << beamStopName(scan.map_border);
    fs << "beam_cap" << features.beam_cap << "gap_small" << features.gap_small << "gap_large" << features.gap_large
       << "context_radius" << features.context_radius;
    fs << "capped_ranges" << "[";
    for (double r : features.capped_ranges) fs << r;
    fs << "]";
    fs << "feature_names" << "[";
    for (const auto& n : feature_names) fs << n;
    fs << "]";
    fs << "order" << "[" << order[0] << order[1] << order[2] << "]";
    fs << "compatibility" << "[";
    for (int a = 0; a < kNumLabels; ++a)
      for (int b = 0; b < kNumLabels; ++b) fs << compatibility[a][b];
    fs << "]";
    writeClassifier(fs, "first", first);
    writeClassifier(fs, "second", second);
    fs << "notes" << notes;
    fs.release();
  });
}

PlacesModel PlacesModel::load(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "model file not found");
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw InputError(path, "not a readable model file (YAML/JSON expected)");
  }
  if (!fs.isOpened()) throw InputError(path, "not a readable model file");
  if (static_cast<std::string>(fs["format"]) != kFormat)
    throw InputError(path, 0, "format", std::string("not a gridtopo places model (expected format: ") + kFormat + ")");
  const int version = static_cast<int>(fs["version"]);
  if (version < 1 || version > kVersion)
    throw InputError(path, 0, "version",
                     "unsupported model version " + std::to_string(version) + " (this build reads versions 1 to " +
                         std::to_string(kVersion) + "; retrain with gridtopo-train)");
  PlacesModel m;
  m.scan.num_beams = static_cast<int>(fs["num_beams"]);
  m.scan.max_range = static_cast<double>(fs["max_range"]);
  m.scan.lattice_spacing = static_cast<double>(fs["lattice_spacing"]);
  // Models written before issue 15 have neither key: their beams stopped at unknown cells and at the border.
  if (!fs["unknown_cells"].empty())
    m.scan.unknown_cells = parseBeamStop(static_cast<std::string>(fs["unknown_cells"]), path, "unknown_cells", true);
  if (!fs["map_border"].empty())
    m.scan.map_border = parseBeamStop(static_cast<std::string>(fs["map_border"]), path, "map_border", false);
  m.scan.validate(path);
  m.features.beam_cap = static_cast<double>(fs["beam_cap"]);
  m.features.gap_small = static_cast<double>(fs["gap_small"]);
  m.features.gap_large = static_cast<double>(fs["gap_large"]);
  m.features.context_radius = fs["context_radius"].empty() ? 0.0 : static_cast<double>(fs["context_radius"]);
  if (!std::isfinite(m.features.context_radius) || m.features.context_radius < 0)
    throw InputError(path, 0, "context_radius", "must be >= 0");
  if (version >= 2 && !fs["capped_ranges"].isSeq())
    throw InputError(path, 0, "capped_ranges", "missing (a version-2 model lists its capped ranges, possibly [])");
  m.features.capped_ranges.clear();  // version 1: none
  for (const auto& n : fs["capped_ranges"]) {
    const double r = static_cast<double>(n);
    if (!std::isfinite(r) || r <= 0) throw InputError(path, 0, "capped_ranges", "ranges must be > 0");
    m.features.capped_ranges.push_back(r);
  }
  for (const auto& n : fs["feature_names"]) m.feature_names.push_back(static_cast<std::string>(n));
  if (m.feature_names != featureNames(m.features))
    throw InputError(path, 0, "feature_names",
                     "model was trained with other features than this build computes (retrain with gridtopo-train)");
  std::vector<int> order;
  for (const auto& n : fs["order"]) order.push_back(static_cast<int>(n));
  if (order.size() != 3) throw InputError(path, 0, "order", "decision list must name 3 labels");
  for (int i = 0; i < 3; ++i) m.order[static_cast<std::size_t>(i)] = order[static_cast<std::size_t>(i)];
  {
    std::array<int, 3> seen{0, 0, 0};
    for (int l : m.order) {
      if (l < 0 || l > 2) throw InputError(path, 0, "order", "label out of range");
      seen[static_cast<std::size_t>(l)]++;
    }
    if (seen != std::array<int, 3>{1, 1, 1}) throw InputError(path, 0, "order", "labels must be distinct");
  }
  std::vector<double> comp;
  for (const auto& n : fs["compatibility"]) comp.push_back(static_cast<double>(n));
  if (comp.size() != 9) throw InputError(path, 0, "compatibility", "expected 9 values");
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double v = comp[static_cast<std::size_t>(a * 3 + b)];
      if (!(v >= -1.0 && v <= 1.0)) throw InputError(path, 0, "compatibility", "values must be in [-1, 1]");
      m.compatibility[a][b] = v;
    }
  m.first = readClassifier(fs["first"], m.feature_names.size(), path, "first");
  m.second = readClassifier(fs["second"], m.feature_names.size(), path, "second");
  m.first.bias = static_cast<double>(fs["first_bias"]);
  m.second.bias = static_cast<double>(fs["second_bias"]);
  if (!std::isfinite(m.first.bias) || !std::isfinite(m.second.bias))
    throw InputError(path, 0, "bias", "must be finite");
  m.notes = static_cast<std::string>(fs["notes"]);
  return m;
}

}  // namespace gridtopo::places
