#include "gridtopo/places/features.h"

#include <opencv2/imgproc.hpp>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <thread>

namespace gridtopo::places {

const OptionSchema<FeatureOptions>& featureOptionSchema() {
  using O = FeatureOptions;
  static const OptionSchema<O> schema =
      OptionSchema<O>("gridtopo::places::FeatureOptions")
          .add("beam_cap", &O::beam_cap, OptionRange::above(0), "m", "cap of the \"capped\" beam-difference features")
          .add("gap_small", &O::gap_small, OptionRange::atLeast(0), "m", "a beam difference d_k above this is a small gap")
          .add("gap_large", &O::gap_large, OptionRange::atLeast(0), "m", "a beam difference d_k above this is a large gap")
          .addRealList("capped_ranges", &O::capped_ranges, OptionRange::leftOpen(0, 65), "m",
                       "a copy of every base feature per range R, on the scan with beams capped at R; empty = off")
          .add("context_radius", &O::context_radius, OptionRange::closed(0, 10), "m",
               "> 0: a copy of every feature averaged over the lattice samples within this distance; 0 = off");
  return schema;
}

const std::vector<std::string>& featureDescriptions() {
  static const std::vector<std::string> d = {
      "mean_diff: (1/M) sum_k d_k",
      "std_diff: standard deviation of d_k",
      "mean_diff_capped: (1/M) sum_k |c_k - c_{k+1}| with c_k = min(b_k, beam_cap)",
      "std_diff_capped: standard deviation of |c_k - c_{k+1}|",
      "mean_beam: (1/M) sum_k b_k",
      "std_beam: standard deviation of b_k",
      "gaps_small: #{k : d_k > gap_small}",
      "gaps_large: #{k : d_k > gap_large}",
      "mean_ratio: mean of min(b_k, b_{k+1}) / max(b_k, b_{k+1})",
      "std_ratio: standard deviation of min(b_k, b_{k+1}) / max(b_k, b_{k+1})",
      "kurtosis: E[(b - mean)^4] / std^4 - 3",
      "mean_rel: mean of b_k / max_j b_j",
      "std_rel: standard deviation of b_k / max_j b_j",
      "min_beam: min_k b_k (distance to the nearest obstacle)",
      "max_beam: max_k b_k",
      "min_chord: min_k (b_k + b_{k+M/2}) (narrowest passage through the cell)",
      "perp_chord: b_{k*+M/4} + b_{k*+3M/4} with k* the argmin of min_chord (length across it)",
      "max_chord: max_k (b_k + b_{k+M/2})",
      "chord_centering: min(b_k*, b_{k*+M/2}) / min_chord (0.5 = cell in the middle of the passage)",
      "area: A, area of P (m^2)",
      "perimeter: L, perimeter of P (m)",
      "area_perimeter: A / L (m)",
      "compactness: L^2 / A",
      "mean_centroid_dist: mean over vertices of |p_k - centroid(P)|",
      "std_centroid_dist: standard deviation of |p_k - centroid(P)|",
      "ellipse_major: 2 sqrt(l1 / A), l1 the larger eigenvalue of [mu20 mu11; mu11 mu02] of P",
      "ellipse_minor: 2 sqrt(l2 / A), l2 the smaller eigenvalue",
      "ellipse_ratio: ellipse_minor / ellipse_major",
      "hu1: Hu moment invariant 1 of P",
      "hu2: Hu moment invariant 2 of P",
      "hu3: Hu moment invariant 3 of P",
      "hu4: Hu moment invariant 4 of P",
      "hu5: Hu moment invariant 5 of P",
      "hu6: Hu moment invariant 6 of P",
      "hu7: Hu moment invariant 7 of P",
      "centroid_offset: |centroid(P)| (distance from the cell to the centroid of P, m)",
      "fill_ratio: A / (pi max_k b_k^2)",
  };
  return d;
}

std::vector<std::string> featureNames() {
  std::vector<std::string> n;
  for (const auto& d : featureDescriptions()) n.push_back(d.substr(0, d.find(':')));
  return n;
}

std::size_t numFeatures() { return featureDescriptions().size(); }

std::string cappedSuffix(double range) {
  std::ostringstream o;
  o << "_cap" << range;
  return o.str();
}

std::vector<std::string> featureNames(const FeatureOptions& o) {
  std::vector<std::string> n = featureNames();
  const std::size_t base = n.size();
  for (double r : o.capped_ranges)
    for (std::size_t i = 0; i < base; ++i) n.push_back(n[i] + cappedSuffix(r));
  if (o.context_radius > 0) {
    const std::size_t b = n.size();
    for (std::size_t i = 0; i < b; ++i) n.push_back(n[i] + "_ctx");
  }
  return n;
}

cv::Mat addContextFeatures(const Lattice& lattice, const cv::Mat& features, double radius, double resolution) {
  CV_Assert(features.type() == CV_32F && static_cast<std::size_t>(features.rows) == lattice.samples.size());
  const double block_m = lattice.stride * resolution;
  const int half = std::max(1, static_cast<int>(std::lround(radius / block_m)));
  const cv::Size ksize(2 * half + 1, 2 * half + 1);
  const cv::Size grid = lattice.block_sample.size();
  cv::Mat mask(grid, CV_32F, cv::Scalar(0));
  for (const cv::Point& b : lattice.blocks) mask.at<float>(b) = 1.f;
  cv::Mat count;
  cv::boxFilter(mask, count, CV_32F, ksize, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
  cv::Mat out(features.rows, features.cols * 2, CV_32F);
  features.copyTo(out.colRange(0, features.cols));
  cv::Mat g(grid, CV_32F), sum;
  for (int f = 0; f < features.cols; ++f) {
    g.setTo(0);
    for (std::size_t i = 0; i < lattice.blocks.size(); ++i) g.at<float>(lattice.blocks[i]) = features.at<float>(static_cast<int>(i), f);
    cv::boxFilter(g, sum, CV_32F, ksize, cv::Point(-1, -1), false, cv::BORDER_CONSTANT);
    for (std::size_t i = 0; i < lattice.blocks.size(); ++i)
      out.at<float>(static_cast<int>(i), features.cols + f) = sum.at<float>(lattice.blocks[i]) / count.at<float>(lattice.blocks[i]);
  }
  return out;
}

namespace {
struct MeanStd {
  double s = 0, s2 = 0;
  int n = 0;
  void add(double v) { s += v, s2 += v * v, ++n; }
  double mean() const { return n ? s / n : 0.0; }
  double std() const { return n ? std::sqrt(std::max(0.0, s2 / n - mean() * mean())) : 0.0; }
};
}  // namespace

namespace {
// cos / sin of the beam angles, per beam count.
const std::vector<cv::Point2d>& beamDirections(int M) {
  thread_local int cached_m = -1;
  thread_local std::vector<cv::Point2d> dirs;
  if (cached_m != M) {
    dirs.resize(static_cast<std::size_t>(M));
    for (int k = 0; k < M; ++k) {
      const double th = 2.0 * M_PI * k / M;
      dirs[static_cast<std::size_t>(k)] = cv::Point2d(std::cos(th), std::sin(th));
    }
    cached_m = M;
  }
  return dirs;
}
}  // namespace

namespace {
// The raw moments from the edge sums of polygonMoments (orientation-independent).
cv::Moments momentsFromEdgeSums(double a00, double a10, double a01, double a20, double a11, double a02, double a30,
                                double a21, double a12, double a03) {
  const double sgn = a00 < 0 ? -1.0 : 1.0;
  return cv::Moments(sgn * a00 / 2, sgn * a10 / 6, sgn * a01 / 6, sgn * a20 / 12, sgn * a11 / 24, sgn * a02 / 12,
                     sgn * a30 / 20, sgn * a21 / 60, sgn * a12 / 60, sgn * a03 / 20);
}
}  // namespace

// Raw moments up to order 3 of a simple polygon (Green's theorem over its edges), as cv::moments computes them
// for a contour; written out because this runs once per classified cell and cv::moments' overhead dominated.
cv::Moments polygonMoments(const std::vector<cv::Point2d>& p) {
  double a00 = 0, a10 = 0, a01 = 0, a20 = 0, a11 = 0, a02 = 0, a30 = 0, a21 = 0, a12 = 0, a03 = 0;
  const std::size_t n = p.size();
  for (std::size_t i = 0, prev = n - 1; i < n; prev = i++) {
    const double x0 = p[prev].x, y0 = p[prev].y, x1 = p[i].x, y1 = p[i].y;
    const double d = x0 * y1 - x1 * y0, sx = x0 + x1, sy = y0 + y1;
    const double x0s = x0 * x0, x1s = x1 * x1, y0s = y0 * y0, y1s = y1 * y1;
    a00 += d;
    a10 += d * sx;
    a01 += d * sy;
    a20 += d * (x0 * sx + x1s);
    a11 += d * (x0 * (sy + y0) + x1 * (sy + y1));
    a02 += d * (y0 * sy + y1s);
    a30 += d * sx * (x0s + x1s);
    a03 += d * sy * (y0s + y1s);
    a21 += d * (x0s * (3 * y0 + y1) + 2 * x1 * x0 * sy + x1s * (y0 + 3 * y1));
    a12 += d * (y0s * (3 * x0 + x1) + 2 * y1 * y0 * sx + y1s * (x0 + 3 * x1));
  }
  return momentsFromEdgeSums(a00, a10, a01, a20, a11, a02, a30, a21, a12, a03);
}

namespace {
// Everything extractFeatures() accumulates over the beams of one scan; writeFeatures() turns it into the
// features. The scalar path (one scan) and the lane path (several scans at once, extractFeaturesLanes) fill
// it with the same operations in the same order, so both give the same bits.
struct ScanSums {
  MeanStd diff, diffc, beam, ratio, rel, cd;
  int gs = 0, gl = 0;
  double bmax = 0, bmin = 1e18;
  double m2 = 0, m4 = 0;  // sums of (b - mean)^2 and ^4
  double cmin = 1e18, cmax = 0;
  int kstar = 0;
  cv::Moments m;
  double L = 0;
  cv::Point2d cen{0, 0};
};

// Chords through the cell (scalar in both paths: the sums b_k + b_{k+M/2} are float additions).
void chordSums(const float* b, int M, ScanSums& r) {
  const int h = M / 2;
  for (int k = 0; k < h; ++k) {
    const double c = b[k] + b[k + h];
    if (c < r.cmin) r.cmin = c, r.kstar = k;
    r.cmax = std::max(r.cmax, c);
  }
}

cv::Point2d polygonCentroid(const cv::Moments& m) {
  return std::abs(m.m00) > 1e-12 ? cv::Point2d(m.m10 / m.m00, m.m01 / m.m00) : cv::Point2d(0, 0);
}

void writeFeatures(const ScanSums& r, const float* b, int M, float* out) {
  double m2 = r.m2, m4 = r.m4;
  m2 /= M, m4 /= M;
  const double kurt = m2 > 1e-12 ? m4 / (m2 * m2) - 3.0 : 0.0;
  const int h = M / 2, q = M / 4, kstar = r.kstar;
  const double cmin = r.cmin, cmax = r.cmax, bmin = r.bmin, bmax = r.bmax;
  const double perp = b[(kstar + q) % M] + b[(kstar + q + h) % M];
  const double centering = cmin > 0 ? std::min(b[kstar], b[kstar + h]) / cmin : 0.5;
  const cv::Moments& m = r.m;
  const double A = std::abs(m.m00), L = r.L;
  const cv::Point2d cen = r.cen;
  double l1 = 0, l2 = 0;
  if (A > 1e-12) {
    const double a = m.mu20, c = m.mu02, bb = m.mu11;
    const double tr = (a + c) / 2, det = std::sqrt(std::max(0.0, (a - c) * (a - c) / 4 + bb * bb));
    l1 = std::max(0.0, tr + det) / A, l2 = std::max(0.0, tr - det) / A;
  }
  const double emaj = 2 * std::sqrt(l1), emin = 2 * std::sqrt(l2);
  double hu[7] = {0, 0, 0, 0, 0, 0, 0};
  if (A > 1e-12) cv::HuMoments(m, hu);
  int i = 0;
  out[i++] = static_cast<float>(r.diff.mean());
  out[i++] = static_cast<float>(r.diff.std());
  out[i++] = static_cast<float>(r.diffc.mean());
  out[i++] = static_cast<float>(r.diffc.std());
  out[i++] = static_cast<float>(r.beam.mean());
  out[i++] = static_cast<float>(r.beam.std());
  out[i++] = static_cast<float>(r.gs);
  out[i++] = static_cast<float>(r.gl);
  out[i++] = static_cast<float>(r.ratio.mean());
  out[i++] = static_cast<float>(r.ratio.std());
  out[i++] = static_cast<float>(kurt);
  out[i++] = static_cast<float>(r.rel.mean());
  out[i++] = static_cast<float>(r.rel.std());
  out[i++] = static_cast<float>(bmin);
  out[i++] = static_cast<float>(bmax);
  out[i++] = static_cast<float>(cmin);
  out[i++] = static_cast<float>(perp);
  out[i++] = static_cast<float>(cmax);
  out[i++] = static_cast<float>(centering);
  out[i++] = static_cast<float>(A);
  out[i++] = static_cast<float>(L);
  out[i++] = static_cast<float>(L > 0 ? A / L : 0.0);
  out[i++] = static_cast<float>(A > 1e-12 ? L * L / A : 0.0);
  out[i++] = static_cast<float>(r.cd.mean());
  out[i++] = static_cast<float>(r.cd.std());
  out[i++] = static_cast<float>(emaj);
  out[i++] = static_cast<float>(emin);
  out[i++] = static_cast<float>(emaj > 0 ? emin / emaj : 0.0);
  for (double v : hu) out[i++] = static_cast<float>(v);
  out[i++] = static_cast<float>(std::hypot(cen.x, cen.y));
  out[i++] = static_cast<float>(bmax > 0 ? A / (M_PI * bmax * bmax) : 0.0);
}
}  // namespace

void extractFeatures(const float* b, int M, const FeatureOptions& o, float* out) {
  ScanSums r;
  for (int k = 0; k < M; ++k) r.bmax = std::max<double>(r.bmax, b[k]), r.bmin = std::min<double>(r.bmin, b[k]);
  const double inv_bmax = 1.0 / std::max(r.bmax, 1e-6);
  for (int k = 0; k < M; ++k) {
    const double x = b[k], y = b[k + 1 < M ? k + 1 : 0];
    const double d = std::abs(x - y);
    r.diff.add(d);
    r.diffc.add(std::abs(std::min(x, o.beam_cap) - std::min(y, o.beam_cap)));
    r.beam.add(x);
    r.ratio.add(std::max(x, y) > 0 ? std::min(x, y) / std::max(x, y) : 1.0);
    r.rel.add(x * inv_bmax);
    r.gs += d > o.gap_small;
    r.gl += d > o.gap_large;
  }
  const double mu = r.beam.mean();
  for (int k = 0; k < M; ++k) {
    const double e = b[k] - mu;
    r.m2 += e * e, r.m4 += e * e * e * e;
  }
  chordSums(b, M, r);
  // Polygon.
  thread_local std::vector<cv::Point2d> poly;
  poly.resize(static_cast<std::size_t>(M));
  const auto& dirs = beamDirections(M);
  for (int k = 0; k < M; ++k) poly[static_cast<std::size_t>(k)] = dirs[static_cast<std::size_t>(k)] * static_cast<double>(b[k]);
  r.m = polygonMoments(poly);
  for (int k = 0; k < M; ++k) {
    const cv::Point2d d = poly[static_cast<std::size_t>(k)] - poly[static_cast<std::size_t>(k + 1 < M ? k + 1 : 0)];
    r.L += std::sqrt(d.x * d.x + d.y * d.y);
  }
  const cv::Point2d cen = r.cen = polygonCentroid(r.m);
  for (const auto& p : poly) r.cd.add(std::sqrt((p.x - cen.x) * (p.x - cen.x) + (p.y - cen.y) * (p.y - cen.y)));
  writeFeatures(r, b, M, out);
}

namespace {
// The same computation for several scans at once, one scan per SIMD lane (GCC vector extensions): every lane
// performs exactly the scalar operations of extractFeatures() in the same order (no sum is split or reordered,
// selects replace branches; +, -, *, /, sqrt are correctly rounded in SIMD as in scalar code, and no FMA is
// enabled), so the features are bit-identical (test Features.LanesEqualScalarBitForBit). Vectorising over
// scans, not over beams, is what keeps the sums exact. Three builds of the kernel (features_lanes.inc): SSE2, two
// lanes (every x86-64), AVX, four lanes, and AVX-512F, eight lanes, the widest the CPU has chosen at run time.
namespace lanes_sse2 {
constexpr int kLanes = 2;
typedef double vd __attribute__((vector_size(8 * kLanes)));
inline vd vsqrt(vd v) {
#if defined(__SSE2__)
  return reinterpret_cast<vd>(_mm_sqrt_pd(reinterpret_cast<__m128d>(v)));
#else
  vd r;
  for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(v[l]);
  return r;
#endif
}
#include "features_lanes.inc"
}  // namespace lanes_sse2

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)  // GCC: #pragma GCC target
#define GRIDTOPO_FEATURES_AVX 1
#pragma GCC push_options
#pragma GCC target("avx")  // AVX only: no FMA, which would fuse a * b + c and change the bits
namespace lanes_avx {
constexpr int kLanes = 4;
typedef double vd __attribute__((vector_size(8 * kLanes)));
inline vd vsqrt(vd v) { return reinterpret_cast<vd>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(v))); }
#include "features_lanes.inc"
}  // namespace lanes_avx
#pragma GCC pop_options
#define GRIDTOPO_FEATURES_AVX512 1
#pragma GCC push_options
// AVX-512F, eight lanes. It brings FMA instructions: contraction of a * b + c is turned off for this kernel (GCC
// contracts by default in C++), so every operation stays the correctly rounded one of the scalar code.
#pragma GCC target("avx512f")
#pragma GCC optimize("fp-contract=off")
namespace lanes_avx512 {
constexpr int kLanes = 8;
typedef double vd __attribute__((vector_size(8 * kLanes)));
inline vd vsqrt(vd v) {
  const __m512d x = reinterpret_cast<__m512d>(v);
  return reinterpret_cast<vd>(_mm512_mask_sqrt_pd(x, static_cast<__mmask8>(0xff), x));  // every lane: sqrt
}
#include "features_lanes.inc"
}  // namespace lanes_avx512
#pragma GCC pop_options
#endif

constexpr int kMaxLanes = 8;
std::atomic<int> g_max_lanes{kMaxLanes};

struct LaneKernel {
  int lanes;
  void (*run)(const float* const*, int, const FeatureOptions&, float* const*);
};

LaneKernel laneKernel() {
#ifdef GRIDTOPO_FEATURES_AVX512
  if (g_max_lanes >= 8 && __builtin_cpu_supports("avx512f"))
    return {lanes_avx512::kLanes, lanes_avx512::extractFeaturesLanes};
#endif
#ifdef GRIDTOPO_FEATURES_AVX
  if (g_max_lanes >= 4 && __builtin_cpu_supports("avx")) return {lanes_avx::kLanes, lanes_avx::extractFeaturesLanes};
#endif
  return {lanes_sse2::kLanes, lanes_sse2::extractFeaturesLanes};
}
}  // namespace

int featureLanesUpTo(int max_lanes) {
  g_max_lanes = max_lanes;
  return laneKernel().lanes;
}

int featureLanes(bool allow_avx) { return featureLanesUpTo(allow_avx ? kMaxLanes : 2); }

namespace {
// Sample i's beam k is ranges[i * sample_stride + k * beam_stride] (millimetres).
cv::Mat extractFeaturesStrided(const std::uint16_t* ranges, std::size_t n, int M, std::size_t sample_stride,
                               std::size_t beam_stride, const FeatureOptions& options, int threads) {
  const std::size_t F = numFeatures();
  const std::size_t Ms = static_cast<std::size_t>(M);
  const std::size_t copies = 1 + options.capped_ranges.size();
  // Not initialised: every row's base columns are computed and every capped copy is computed or copied.
  cv::Mat out(static_cast<int>(n), static_cast<int>(F * copies), CV_32F);
  adviseHugePages(out.data, out.total() * out.elemSize());
  // Jobs (a scan and where its features go) are gathered kLanes at a time for extractFeaturesLanes: the base
  // scan of every sample, and each capped copy whose cap is reached; a copy whose cap no beam reaches is the
  // scan itself, so its features are copied from the base columns.
  constexpr std::size_t kChunk = 512;  // samples per work item (dynamic, so capped copies spread over threads)
  std::atomic<std::size_t> next{0};
  const LaneKernel kernel = laneKernel();
  const int kLanes = kernel.lanes;
  auto work = [&]() {
    std::vector<float> buf(static_cast<std::size_t>(kLanes) * (1 + options.capped_ranges.size()) * Ms);
    std::vector<float> scratch(F);
    const float* lane_beams[kMaxLanes];
    float* lane_out[kMaxLanes];
    int used = 0;
    std::size_t buf_used = 0;
    std::vector<std::pair<float*, std::size_t>> copy_later;  // (row, capped copy c)
    auto flush = [&]() {
      if (used == 0) return;
      for (int l = used; l < kLanes; ++l) lane_beams[l] = lane_beams[0], lane_out[l] = scratch.data();
      kernel.run(lane_beams, M, options, lane_out);
      used = 0, buf_used = 0;
    };
    for (std::size_t b0; (b0 = next.fetch_add(kChunk)) < n;) {
      for (std::size_t i = b0; i < std::min(n, b0 + kChunk); ++i) {
        const std::uint16_t* s = ranges + i * sample_stride;
        float* row = out.ptr<float>(static_cast<int>(i));
        const std::size_t need = Ms * (1 + options.capped_ranges.size());
        if (buf_used + need > buf.size()) flush();
        float* beams = buf.data() + buf_used;
        buf_used += Ms;
        std::uint16_t longest_mm = 0;
        for (int k = 0; k < M; ++k) {
          const std::uint16_t r = s[static_cast<std::size_t>(k) * beam_stride];
          beams[k] = r * 0.001f, longest_mm = std::max(longest_mm, r);
        }
        const float longest = longest_mm * 0.001f;  // the longest beam (the conversion is monotonic)
        lane_beams[used] = beams, lane_out[used] = row;
        if (++used == kLanes) flush();
        for (std::size_t c = 0; c < options.capped_ranges.size(); ++c) {
          const float cap = static_cast<float>(options.capped_ranges[c]);
          if (longest <= cap) {  // no beam reaches the cap: the capped scan is the scan, so are its features
            copy_later.emplace_back(row, c);
            continue;
          }
          if (buf_used + Ms > buf.size()) flush();
          float* capped = buf.data() + buf_used;
          buf_used += Ms;
          for (int k = 0; k < M; ++k) capped[k] = std::min(beams[k], cap);
          lane_beams[used] = capped, lane_out[used] = row + F * (c + 1);
          if (++used == kLanes) flush();
        }
      }
    }
    flush();
    for (const auto& [row, c] : copy_later) std::copy(row, row + F, row + F * (c + 1));
  };
  const int nt = std::max(1, threads);
  std::vector<std::thread> pool;
  for (int t = 1; t < nt; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  return out;
}

}  // namespace

cv::Mat extractFeatures(const SimulatedScans& scans, const FeatureOptions& options, int threads) {
  return extractFeaturesStrided(scans.ranges_mm.data(), scans.size(), scans.num_beams,
                                static_cast<std::size_t>(scans.num_beams), 1, options, threads);
}

cv::Mat extractFeaturesOfBeams(const cv::Mat& by_beam, const FeatureOptions& options, int threads) {
  CV_Assert(by_beam.type() == CV_16U && by_beam.isContinuous());
  return extractFeaturesStrided(by_beam.ptr<std::uint16_t>(), static_cast<std::size_t>(by_beam.cols), by_beam.rows, 1,
                                static_cast<std::size_t>(by_beam.cols), options, threads);
}

}  // namespace gridtopo::places
