#include "gridtopo/places/scan_simulation.h"
#include "gridtopo/core/ini_value.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "gridtopo/core/error.h"

namespace gridtopo::places {

void ScanSimulationOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& s, const std::string& sec) {
  readIniValue(s, sec, "num_beams", num_beams);
  readIniValue(s, sec, "max_range", max_range);
  readIniValue(s, sec, "lattice_spacing", lattice_spacing);
  readIniValue(s, sec, "threads", threads);
  validate("[" + sec + "]");
}

void ScanSimulationOptions::dumpToTextStream(std::ostream& out) const {
  out << "num_beams       = " << num_beams << "   // beams per simulated scan (even)\n"
      << "max_range       = " << max_range << "   // m, beams capped here\n"
      << "lattice_spacing = " << lattice_spacing << "   // m between classified cells\n"
      << "threads         = " << threads << "\n";
}

void ScanSimulationOptions::validate(const std::string& where) const {
  if (num_beams < 8 || num_beams % 4 != 0 || num_beams > 3600)
    throw InputError(where, 0, "num_beams", "must be a multiple of 4 in [8, 3600]");
  if (!std::isfinite(max_range) || max_range <= 0 || max_range > 65.0)
    throw InputError(where, 0, "max_range", "must be in (0, 65] metres");
  if (!std::isfinite(lattice_spacing) || lattice_spacing < 0 || lattice_spacing > 2.0)
    throw InputError(where, 0, "lattice_spacing", "must be in [0, 2] metres");
  if (threads < 1 || threads > 256) throw InputError(where, 0, "threads", "must be in [1, 256]");
}

Lattice buildLattice(const OccupancyImage& occ, double lattice_spacing) {
  Lattice lat;
  lat.stride = std::max(1, static_cast<int>(std::lround(lattice_spacing / occ.resolution)));
  const int s = lat.stride;
  const int br = (occ.rows() + s - 1) / s, bc = (occ.cols() + s - 1) / s;
  lat.block_sample = cv::Mat(br, bc, CV_32S, cv::Scalar(-1));
  const double mid = (s - 1) / 2.0;
  for (int by = 0; by < br; ++by)
    for (int bx = 0; bx < bc; ++bx) {
      int best_r = -1, best_c = -1;
      double best_d = 1e18;
      for (int r = by * s; r < std::min(occ.rows(), by * s + s); ++r)
        for (int c = bx * s; c < std::min(occ.cols(), bx * s + s); ++c) {
          if (!occ.isFree(r, c)) continue;
          const double d = (r - by * s - mid) * (r - by * s - mid) + (c - bx * s - mid) * (c - bx * s - mid);
          if (d < best_d) best_d = d, best_r = r, best_c = c;
        }
      if (best_r < 0) continue;
      lat.block_sample.at<int>(by, bx) = static_cast<int>(lat.samples.size());
      lat.samples.emplace_back(best_c, best_r);
      lat.blocks.emplace_back(bx, by);
    }
  return lat;
}

namespace {

// One family of parallel digital lines along the columns of `cells` (the caller transposes the image for
// steep directions, so memory is always walked along rows): the row of line j at column k is j + offset[k],
// offset[k] = floor(k * slope + 0.5), |slope| <= 1. Every cell lies on exactly one line. A forward pass
// (k increasing) measures the free run behind each cell (the beam pointing to decreasing k), a backward pass the
// run ahead.
void sweepFamily(const cv::Mat& cells, const cv::Mat& sample_index, double resolution, double slope, int beam_back,
                 int beam_ahead, double max_range_mm, cv::Mat& by_beam) {
  const int n_major = cells.cols, n_minor = cells.rows;
  std::vector<int> offset(static_cast<std::size_t>(n_major));
  for (int k = 0; k < n_major; ++k) offset[static_cast<std::size_t>(k)] = static_cast<int>(std::floor(k * slope + 0.5));
  const int min_off = *std::min_element(offset.begin(), offset.end());
  const int max_off = *std::max_element(offset.begin(), offset.end());
  const double step_mm = resolution * 1000.0 * std::sqrt(1.0 + slope * slope);
  // Run lengths in steps, converted to mm through a small table (runs beyond max range saturate).
  const int max_run = static_cast<int>(max_range_mm / step_mm) + 2;
  std::vector<std::uint16_t> mm(static_cast<std::size_t>(max_run) + 1);
  for (int r = 0; r <= max_run; ++r)
    mm[static_cast<std::size_t>(r)] = static_cast<std::uint16_t>(std::lround(std::min((r + 0.5) * step_mm, max_range_mm)));
  for (int j = -max_off; j <= n_minor - 1 - min_off; ++j) {
    // The columns where line j is inside the image form one interval (offset is monotonic).
    int k0 = 0, k1 = n_major;
    while (k0 < n_major && (j + offset[static_cast<std::size_t>(k0)] < 0 || j + offset[static_cast<std::size_t>(k0)] >= n_minor)) ++k0;
    while (k1 > k0 && (j + offset[static_cast<std::size_t>(k1 - 1)] < 0 || j + offset[static_cast<std::size_t>(k1 - 1)] >= n_minor)) --k1;
    for (int pass = 0; pass < 2; ++pass) {
      // Beam-major output: one row per beam, so a sweep's writes stay within one row (cache friendly).
      std::uint16_t* row_out = by_beam.ptr<std::uint16_t>(pass == 0 ? beam_back : beam_ahead);
      int run = 0;
      for (int t = k0; t < k1; ++t) {
        const int k = pass == 0 ? t : k0 + k1 - 1 - t;
        const int row = j + offset[static_cast<std::size_t>(k)];
        if (cells.ptr<unsigned char>(row)[k] != kFree) { run = 0; continue; }
        const int idx = sample_index.ptr<int>(row)[k];
        if (idx >= 0) row_out[idx] = mm[static_cast<std::size_t>(std::min(run, max_run))];
        ++run;
      }
    }
  }
}

}  // namespace

SimulatedScans simulateScans(const OccupancyImage& occ, const std::vector<cv::Point>& samples,
                             const ScanSimulationOptions& options,
                             const std::function<void(std::size_t, std::size_t)>& progress) {
  options.validate();
  SimulatedScans out;
  out.num_beams = options.num_beams;
  const int M = options.num_beams;
  out.ranges_mm.assign(samples.size() * static_cast<std::size_t>(M), 0);
  if (samples.empty()) return out;
  cv::Mat sample_index(occ.cells.size(), CV_32S, cv::Scalar(-1));
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const cv::Point& p = samples[i];
    if (p.x < 0 || p.y < 0 || p.x >= occ.cols() || p.y >= occ.rows() || !occ.isFree(p.y, p.x))
      throw std::invalid_argument("simulateScans: sample is not a free cell of the map");
    sample_index.at<int>(p.y, p.x) = static_cast<int>(i);
  }
  const double max_mm = options.max_range * 1000.0;
  cv::Mat by_beam(M, static_cast<int>(samples.size()), CV_16U, cv::Scalar(0));
  cv::Mat cells_t, index_t;
  cv::transpose(occ.cells, cells_t);
  cv::transpose(sample_index, index_t);
  const std::size_t n_dirs = static_cast<std::size_t>(M / 2);
  std::atomic<std::size_t> next{0}, done{0};
  auto process = [&](std::size_t k) {
    // Direction k (image coordinates: dc = cos, dr = -sin) and its opposite k + M/2.
    const double th = 2.0 * M_PI * static_cast<double>(k) / M;
    const double dc = std::cos(th), dr = -std::sin(th);
    const int kb = static_cast<int>(k), ko = static_cast<int>(k) + M / 2;
    if (std::abs(dc) >= std::abs(dr)) {
      // Travelling +1 column moves dr/dc rows; direction k points to +col iff dc > 0.
      sweepFamily(occ.cells, sample_index, occ.resolution, dr / dc, dc > 0 ? ko : kb, dc > 0 ? kb : ko, max_mm, by_beam);
    } else {
      // Steep: the same along the columns of the transposed image (+1 row moves dc/dr columns).
      sweepFamily(cells_t, index_t, occ.resolution, dc / dr, dr > 0 ? ko : kb, dr > 0 ? kb : ko, max_mm, by_beam);
    }
  };
  auto worker = [&](bool report) {
    for (std::size_t k; (k = next.fetch_add(1)) < n_dirs;) {
      process(k);
      const std::size_t d = done.fetch_add(1) + 1;
      if (report && progress) progress(d, n_dirs);
    }
  };
  const int nt = std::max(1, std::min(options.threads, static_cast<int>(n_dirs)));
  std::vector<std::thread> pool;
  for (int t = 1; t < nt; ++t) pool.emplace_back(worker, false);
  worker(true);  // the calling thread works too and reports progress
  for (auto& t : pool) t.join();
  // Sample-major for the feature extraction.
  cv::Mat by_sample(static_cast<int>(samples.size()), M, CV_16U, out.ranges_mm.data());
  cv::transpose(by_beam, by_sample);
  if (progress) progress(n_dirs, n_dirs);
  return out;
}

}  // namespace gridtopo::places
