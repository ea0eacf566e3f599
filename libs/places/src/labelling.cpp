#include "gridtopo/places/labelling.h"

#include <chrono>

#include "gridtopo/core/error.h"

namespace gridtopo::places {

namespace {
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
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

LabellingResult labelFromFeatures(const OccupancyImage& occ, const Lattice& lattice, const cv::Mat& features,
                                  const PlacesModel& model, const RelaxationOptions& relax, int threads) {
  LabellingResult res;
  res.lattice = lattice;
  auto t0 = std::chrono::steady_clock::now();
  const cv::Mat p = model.classify(features, threads);
  res.probs_initial = cv::Mat(lattice.block_sample.size(), CV_32FC3, cv::Scalar(0, 0, 0));
  res.valid = cv::Mat(lattice.block_sample.size(), CV_8U, cv::Scalar(0));
  for (std::size_t i = 0; i < lattice.samples.size(); ++i) {
    res.probs_initial.at<cv::Vec3f>(lattice.blocks[i]) = p.at<cv::Vec3f>(static_cast<int>(i));
    res.valid.at<unsigned char>(lattice.blocks[i]) = 1;
  }
  res.seconds_classify = since(t0);
  t0 = std::chrono::steady_clock::now();
  res.probs = res.probs_initial.clone();
  res.relaxation = relaxLabels(res.probs, res.valid, model.compatibility, relax, threads);
  res.seconds_relax = since(t0);
  res.labels_initial = cellLabels(occ, lattice, res.probs_initial);
  res.labels = cellLabels(occ, lattice, res.probs);
  return res;
}

LabellingResult labelPlaces(const OccupancyImage& occ, const PlacesModel& model, const RelaxationOptions& relax,
                            int threads, const std::string& source,
                            const std::function<void(const std::string&, std::size_t, std::size_t)>& progress,
                            bool keep_scans_and_features) {
  if (countFree(occ) == 0) throw InputError(source, "the map has no free cell (nothing to label)");
  ScanSimulationOptions scan = model.scan;
  scan.threads = threads;
  auto t0 = std::chrono::steady_clock::now();
  const Lattice lattice = buildLattice(occ, scan.lattice_spacing);
  SimulatedScans scans = simulateScans(occ, lattice.samples, scan, [&](std::size_t d, std::size_t n) {
    if (progress) progress("scans", d, n);
  });
  const double ts = since(t0);
  t0 = std::chrono::steady_clock::now();
  cv::Mat features = extractFeatures(scans, model.features, threads);
  if (model.features.context_radius > 0)
    features = addContextFeatures(lattice, features, model.features.context_radius, occ.resolution);
  const double tf = since(t0);
  if (progress) progress("features", 1, 1);
  LabellingResult res = labelFromFeatures(occ, lattice, features, model, relax, threads);
  res.seconds_scans = ts, res.seconds_features = tf;
  if (keep_scans_and_features) {
    res.scans = std::move(scans);
    res.features = std::move(features);
  }
  return res;
}

}  // namespace gridtopo::places
