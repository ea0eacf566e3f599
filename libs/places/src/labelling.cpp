#include "gridtopo/places/labelling.h"

#include <chrono>
#include <ctime>

#include "gridtopo/core/error.h"

namespace gridtopo::places {

namespace {
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
// Wall and processor seconds (the whole process's, every thread's) since construction or the last restart.
struct Stopwatch {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  double wallSeconds() const { return since(wall); }
  double cpuSeconds() const { return static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC; }
  void restart() { *this = Stopwatch(); }
};
}  // namespace

cv::Mat cellLabels(const OccupancyImage& occ, const Lattice& lattice, const cv::Mat& probs, cv::Point grid_offset) {
  cv::Mat out(occ.cells.size(), CV_8U, cv::Scalar(kNoLabel));
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c) {
      if (!occ.isFree(r, c)) continue;
      const int by = r / lattice.stride, bx = c / lattice.stride;
      if (lattice.block_sample.at<int>(by, bx) < 0) continue;
      const cv::Vec3f& p = probs.at<cv::Vec3f>(by - grid_offset.y, bx - grid_offset.x);
      int best = 0;
      for (int l = 1; l < kNumLabels; ++l)
        if (p[l] > p[best]) best = l;
      out.at<unsigned char>(r, c) = static_cast<unsigned char>(best);
    }
  return out;
}

cv::Mat labelsToCodes(const cv::Mat& labels) {
  cv::Mat out(labels.size(), CV_8U, cv::Scalar(kNoLabelCode));
  for (int r = 0; r < labels.rows; ++r)
    for (int c = 0; c < labels.cols; ++c) {
      const unsigned char l = labels.at<unsigned char>(r, c);
      if (l < kNumLabels) out.at<unsigned char>(r, c) = labelCode(l);
    }
  return out;
}

cv::Mat labelsFromCodes(const cv::Mat& codes) {
  CV_Assert(codes.type() == CV_8U);
  cv::Mat out(codes.size(), CV_8U, cv::Scalar(kNoLabel));
  for (int r = 0; r < codes.rows; ++r)
    for (int c = 0; c < codes.cols; ++c) {
      const int l = labelFromCode(codes.at<unsigned char>(r, c));
      if (l >= 0) out.at<unsigned char>(r, c) = static_cast<unsigned char>(l);
    }
  return out;
}

namespace {
// Classifier output p (samples x 1, CV_32FC3) -> the lattice grids, relaxation and the cell labels. Without
// `keep_grids` the grids cover only the part of the lattice that relaxLabels relaxes (relaxationBox: the same
// values) and are not returned.
LabellingResult labelFromProbabilities(const OccupancyImage& occ, const Lattice& lattice, const cv::Mat& p,
                                       const PlacesModel& model, const RelaxationOptions& relax, int threads,
                                       bool keep_initial = true, bool keep_grids = true) {
  LabellingResult res;
  res.lattice = lattice;
  cv::Rect box(cv::Point(), lattice.block_sample.size());
  if (!keep_grids) {
    cv::Rect blocks;
    for (const cv::Point& b : lattice.blocks) blocks = blocks.empty() ? cv::Rect(b, cv::Size(1, 1)) : blocks | cv::Rect(b, cv::Size(1, 1));
    box = relaxationBox(blocks, box.size(), relax);
  }
  cv::Mat probs(box.size(), CV_32FC3, cv::Scalar(0, 0, 0)), valid(box.size(), CV_8U, cv::Scalar(0));
  for (std::size_t i = 0; i < lattice.samples.size(); ++i) {
    probs.at<cv::Vec3f>(lattice.blocks[i] - box.tl()) = p.at<cv::Vec3f>(static_cast<int>(i));
    valid.at<unsigned char>(lattice.blocks[i] - box.tl()) = 1;
  }
  if (keep_initial) {
    res.probs_initial = probs.clone();
    res.labels_initial = cellLabels(occ, lattice, res.probs_initial, box.tl());
  }
  const auto t0 = std::chrono::steady_clock::now();
  res.relaxation = relaxLabels(probs, valid, model.compatibility, relax, threads);
  res.seconds_relax = since(t0);
  res.labels = cellLabels(occ, lattice, probs, box.tl());
  if (keep_grids) res.probs = probs, res.valid = valid;
  return res;
}
}  // namespace

LabellingResult labelFromFeatures(const OccupancyImage& occ, const Lattice& lattice, const cv::Mat& features,
                                  const PlacesModel& model, const RelaxationOptions& relax, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const cv::Mat p = model.classify(features, threads);
  const double tc = since(t0);
  LabellingResult res = labelFromProbabilities(occ, lattice, p, model, relax, threads);
  res.seconds_classify = tc;
  return res;
}

std::vector<std::pair<std::size_t, std::size_t>> latticeStripes(const Lattice& lattice, std::size_t max_samples) {
  std::vector<std::pair<std::size_t, std::size_t>> stripes;
  const std::size_t n = lattice.samples.size();
  for (std::size_t a = 0; a < n;) {
    // Whole block rows (the samples come in block-row order), at least one.
    std::size_t b = a;
    while (b < n) {
      std::size_t e = b;
      while (e < n && lattice.blocks[e].y == lattice.blocks[b].y) ++e;
      if (b > a && e - a > max_samples) break;
      b = e;
    }
    stripes.emplace_back(a, b);
    a = b;
  }
  return stripes;
}

cv::Mat classifyLattice(const OccupancyImage& occ, const Lattice& lattice, const PlacesModel& model, int threads,
                        std::size_t stripe_samples, const std::function<void(std::size_t, std::size_t)>& progress,
                        LatticeSeconds* seconds) {
  CV_Assert(model.features.context_radius <= 0);
  ScanSimulationOptions scan = model.scan;
  scan.threads = threads;
  const auto stripes = latticeStripes(lattice, stripe_samples);
  cv::Mat p(static_cast<int>(lattice.samples.size()), 1, CV_32FC3);
  LatticeSeconds t;
  for (std::size_t k = 0; k < stripes.size(); ++k) {
    const auto [a, b] = stripes[k];
    Stopwatch sw;
    const std::vector<cv::Point> samples(lattice.samples.begin() + static_cast<long>(a),
                                         lattice.samples.begin() + static_cast<long>(b));
    cv::Mat beams = simulateBeams(occ, samples, scan, [&](std::size_t d, std::size_t n) {
      if (progress) progress(k * n + d, stripes.size() * n);
    });
    t.scans += sw.wallSeconds(), t.cpu_scans += sw.cpuSeconds();
    sw.restart();
    cv::Mat features = extractFeaturesOfBeams(beams, model.features, threads);
    beams.release();
    t.features += sw.wallSeconds(), t.cpu_features += sw.cpuSeconds();
    sw.restart();
    model.classify(features, threads).copyTo(p.rowRange(static_cast<int>(a), static_cast<int>(b)));
    t.classify += sw.wallSeconds();
  }
  if (seconds) *seconds = t;
  return p;
}

LabellingResult labelPlaces(const OccupancyImage& occ, const PlacesModel& model, const RelaxationOptions& relax,
                            int threads, const std::string& source,
                            const std::function<void(const std::string&, std::size_t, std::size_t)>& progress,
                            bool keep_scans_and_features, bool keep_initial, bool keep_grids) {
  if (countFree(occ) == 0) throw InputError(source, "the map has no free cell (nothing to label)");
  const Lattice lattice = buildLattice(occ, model.scan.lattice_spacing);
  if (!keep_scans_and_features && model.features.context_radius <= 0) {
    // A stripe of the lattice at a time: its scans, features and class probabilities (nothing of it is kept).
    LatticeSeconds t;
    const cv::Mat p = classifyLattice(
        occ, lattice, model, threads, kStripeSamples,
        [&](std::size_t d, std::size_t n) {
          if (progress) progress("scans", d, n);
        },
        &t);
    if (progress) progress("features", 1, 1);
    LabellingResult res = labelFromProbabilities(occ, lattice, p, model, relax, threads, keep_initial, keep_grids);
    res.seconds_scans = t.scans, res.seconds_features = t.features, res.seconds_classify = t.classify;
    res.cpu_seconds_scans = t.cpu_scans, res.cpu_seconds_features = t.cpu_features;
    return res;
  }
  ScanSimulationOptions scan = model.scan;
  scan.threads = threads;
  Stopwatch sw;
  SimulatedScans scans = simulateScans(occ, lattice.samples, scan, [&](std::size_t d, std::size_t n) {
    if (progress) progress("scans", d, n);
  });
  const double ts = sw.wallSeconds(), cs = sw.cpuSeconds();
  sw.restart();
  cv::Mat features = extractFeatures(scans, model.features, threads);
  if (model.features.context_radius > 0)
    features = addContextFeatures(lattice, features, model.features.context_radius, occ.resolution);
  const double tf = sw.wallSeconds(), cf = sw.cpuSeconds();
  if (progress) progress("features", 1, 1);
  LabellingResult res = labelFromFeatures(occ, lattice, features, model, relax, threads);
  res.seconds_scans = ts, res.seconds_features = tf;
  res.cpu_seconds_scans = cs, res.cpu_seconds_features = cf;
  if (keep_scans_and_features) {
    res.scans = std::move(scans);
    res.features = std::move(features);
  }
  return res;
}

}  // namespace gridtopo::places
