#pragma once
// The simple geometric features of Mozos et al. (ICRA 2005; RAS 55(5) 2007) computed from one simulated
// 360-degree scan, all in metres / radians / dimensionless, so independent of the map's resolution.
// Notation: b_k beam k (m), k = 0..M-1 cyclic; d_k = |b_k - b_{k+1}|; P = polygon through the beam end points
// p_k = b_k (cos th_k, sin th_k); A, L its area and perimeter; mu_pq its central moments.
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gridtopo/places/scan_simulation.h"

namespace gridtopo::places {

struct FeatureOptions {
  double beam_cap = 5.0;      ///< m, cap for the "capped" beam-difference features
  double gap_small = 0.5;     ///< m, d_k above this counts as a small gap
  double gap_large = 1.5;     ///< m, d_k above this counts as a large gap
  /// m; > 0 appends a context copy of every feature: its mean over the lattice samples within this distance
  /// (square window), named "<feature>_ctx". 0 = off.
  double context_radius = 0.0;
  /// m; for each range R here, a copy of every base feature computed on the scan with beams capped at R
  /// (b_k <- min(b_k, R)), named "<feature>_cap<R>": the features of the same cell seen by a shorter-range
  /// sensor (Mozos et al. use several maximum ranges), so one long beam through a door matters less. Empty = off.
  /// Default {10}: see doc/topology.md (10 m and 15 m were compared).
  std::vector<double> capped_ranges{10.0};
};

/// The key table of FeatureOptions ([features] of a training INI).
const OptionSchema<FeatureOptions>& featureOptionSchema();

/// One line per feature: "name: formula". The order is the column order of extractFeatures().
const std::vector<std::string>& featureDescriptions();
/// Just the names (text before the colon).
std::vector<std::string> featureNames();
std::size_t numFeatures();
/// Names of the columns a model with these options uses (base features, then the context copies if enabled).
std::vector<std::string> featureNames(const FeatureOptions& options);

/// Raw moments (up to order 3) of a simple polygon, equal to cv::moments of the same contour.
cv::Moments polygonMoments(const std::vector<cv::Point2d>& polygon);

/// Features of one scan of M beams given in metres.
void extractFeatures(const float* beams_m, int M, const FeatureOptions& options, float* out);

/// Features of every simulated scan: CV_32F, samples x (numFeatures() x (1 + capped_ranges.size())), without the
/// context copies. Parallel over samples (chunks handed out dynamically), and within a thread several scans at
/// once in SIMD lanes; bit-identical to calling the one-scan extractFeatures() on each (capped) scan.
cv::Mat extractFeatures(const SimulatedScans& scans, const FeatureOptions& options, int threads = 2);
/// The same of beam-major scans (simulateBeams: CV_16U, beams x samples), bit-identical.
cv::Mat extractFeaturesOfBeams(const cv::Mat& by_beam, const FeatureOptions& options, int threads = 2);

/// Scans per SIMD batch of the whole-map extraction: 8 with AVX-512F, 4 with AVX, else 2. `allow_avx = false`
/// forces the SSE2 kernel for the rest of the process (for tests: every kernel must give the bits of the scalar
/// function); featureLanesUpTo(n) allows kernels of at most n lanes (2, 4 or 8) and returns the one chosen.
int featureLanes(bool allow_avx = true);
int featureLanesUpTo(int max_lanes);

/// Appends the context features (see FeatureOptions::context_radius) to `features` (rows = lattice samples):
/// for each column, the mean over the samples whose blocks lie within the window (masked box filter).
cv::Mat addContextFeatures(const Lattice& lattice, const cv::Mat& features, double context_radius, double resolution);

}  // namespace gridtopo::places
