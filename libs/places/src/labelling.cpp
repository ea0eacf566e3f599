#include "gridtopo/places/labelling.h"

#include <chrono>
#include <ctime>

#include "gridtopo/core/error.h"

namespace gridtopo::places {

namespace {
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
// Processor seconds of the whole process (every thread) since `c0`.
double cpuSince(std::clock_t c0) { return static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC; }
}  // namespace

cv::Mat cellLabels(const OccupancyImage& occ, const Lattice& lattice, const cv::Mat& probs) {
  cv::Mat out(occ.cells.size(), CV_8U, cv::Scalar(kNoLabel));
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c) {
      if (!occ.isFree(r, c)) continue;
      const int by = r / lattice.stride, bx = c / lattice.stride;
      if (lattice.block_sample.at<int>(by, bx) < 0) continue;
      const cv::Vec3f& p = probs.at<cv::Vec3f>(by, bx);
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
// Classifier output p (samples x 1, CV_32FC3) -> the lattice grids, relaxation and the cell labels.
LabellingResult labelFromProbabilities(const OccupancyImage& occ, const Lattice& lattice, const cv::Mat& p,
                                       const PlacesModel& model, const RelaxationOptions& relax, int threads) {
  LabellingResult res;
  res.lattice = lattice;
  res.probs_initial = cv::Mat(lattice.block_sample.size(), CV_32FC3, cv::Scalar(0, 0, 0));
  res.valid = cv::Mat(lattice.block_sample.size(), CV_8U, cv::Scalar(0));
  for (std::size_t i = 0; i < lattice.samples.size(); ++i) {
    res.probs_initial.at<cv::Vec3f>(lattice.blocks[i]) = p.at<cv::Vec3f>(static_cast<int>(i));
    res.valid.at<unsigned char>(lattice.blocks[i]) = 1;
  }
  const auto t0 = std::chrono::steady_clock::now();
  res.probs = res.probs_initial.clone();
  res.relaxation = relaxLabels(res.probs, res.valid, model.compatibility, relax, threads);
  res.seconds_relax = since(t0);
  res.labels_initial = cellLabels(occ, lattice, res.probs_initial);
  res.labels = cellLabels(occ, lattice, res.probs);
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
                        double* seconds_scans, double* seconds_features, double* seconds_classify,
                        double* cpu_seconds_scans, double* cpu_seconds_features) {
  CV_Assert(model.features.context_radius <= 0);
  ScanSimulationOptions scan = model.scan;
  scan.threads = threads;
  const auto stripes = latticeStripes(lattice, stripe_samples);
  cv::Mat p(static_cast<int>(lattice.samples.size()), 1, CV_32FC3);
  double ts = 0, tf = 0, tc = 0, cs = 0, cf = 0;
  for (std::size_t k = 0; k < stripes.size(); ++k) {
    const auto [a, b] = stripes[k];
    auto t0 = std::chrono::steady_clock::now();
    std::clock_t c0 = std::clock();
    const std::vector<cv::Point> samples(lattice.samples.begin() + static_cast<long>(a),
                                         lattice.samples.begin() + static_cast<long>(b));
    cv::Mat beams = simulateBeams(occ, samples, scan, [&](std::size_t d, std::size_t n) {
      if (progress) progress(k * n + d, stripes.size() * n);
    });
    ts += since(t0);
    cs += cpuSince(c0);
    t0 = std::chrono::steady_clock::now();
    c0 = std::clock();
    cv::Mat features = extractFeaturesOfBeams(beams, model.features, threads);
    beams.release();
    tf += since(t0);
    cf += cpuSince(c0);
    t0 = std::chrono::steady_clock::now();
    model.classify(features, threads).copyTo(p.rowRange(static_cast<int>(a), static_cast<int>(b)));
    tc += since(t0);
  }
  if (seconds_scans) *seconds_scans = ts;
  if (seconds_features) *seconds_features = tf;
  if (seconds_classify) *seconds_classify = tc;
  if (cpu_seconds_scans) *cpu_seconds_scans = cs;
  if (cpu_seconds_features) *cpu_seconds_features = cf;
  return p;
}

LabellingResult labelPlaces(const OccupancyImage& occ, const PlacesModel& model, const RelaxationOptions& relax,
                            int threads, const std::string& source,
                            const std::function<void(const std::string&, std::size_t, std::size_t)>& progress,
                            bool keep_scans_and_features) {
  if (countFree(occ) == 0) throw InputError(source, "the map has no free cell (nothing to label)");
  const Lattice lattice = buildLattice(occ, model.scan.lattice_spacing);
  if (!keep_scans_and_features && model.features.context_radius <= 0) {
    // A stripe of the lattice at a time: its scans, features and class probabilities (nothing of it is kept).
    double ts = 0, tf = 0, tc = 0, cs = 0, cf = 0;
    const cv::Mat p = classifyLattice(
        occ, lattice, model, threads, kStripeSamples,
        [&](std::size_t d, std::size_t n) {
          if (progress) progress("scans", d, n);
        },
        &ts, &tf, &tc, &cs, &cf);
    if (progress) progress("features", 1, 1);
    LabellingResult res = labelFromProbabilities(occ, lattice, p, model, relax, threads);
    res.seconds_scans = ts, res.seconds_features = tf, res.seconds_classify = tc;
    res.cpu_seconds_scans = cs, res.cpu_seconds_features = cf;
    return res;
  }
  ScanSimulationOptions scan = model.scan;
  scan.threads = threads;
  auto t0 = std::chrono::steady_clock::now();
  std::clock_t c0 = std::clock();
  SimulatedScans scans = simulateScans(occ, lattice.samples, scan, [&](std::size_t d, std::size_t n) {
    if (progress) progress("scans", d, n);
  });
  const double ts = since(t0), cs = cpuSince(c0);
  t0 = std::chrono::steady_clock::now();
  c0 = std::clock();
  cv::Mat features = extractFeatures(scans, model.features, threads);
  if (model.features.context_radius > 0)
    features = addContextFeatures(lattice, features, model.features.context_radius, occ.resolution);
  const double tf = since(t0), cf = cpuSince(c0);
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
