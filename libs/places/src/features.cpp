#include "gridtopo/places/features.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

namespace gridtopo::places {

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
  const double sgn = a00 < 0 ? -1.0 : 1.0;
  return cv::Moments(sgn * a00 / 2, sgn * a10 / 6, sgn * a01 / 6, sgn * a20 / 12, sgn * a11 / 24, sgn * a02 / 12,
                     sgn * a30 / 20, sgn * a21 / 60, sgn * a12 / 60, sgn * a03 / 20);
}

void extractFeatures(const float* b, int M, const FeatureOptions& o, float* out) {
  MeanStd diff, diffc, beam, ratio, rel;
  int gs = 0, gl = 0;
  double bmax = 0, bmin = 1e18;
  for (int k = 0; k < M; ++k) bmax = std::max<double>(bmax, b[k]), bmin = std::min<double>(bmin, b[k]);
  const double inv_bmax = 1.0 / std::max(bmax, 1e-6);
  for (int k = 0; k < M; ++k) {
    const double x = b[k], y = b[k + 1 < M ? k + 1 : 0];
    const double d = std::abs(x - y);
    diff.add(d);
    diffc.add(std::abs(std::min(x, o.beam_cap) - std::min(y, o.beam_cap)));
    beam.add(x);
    ratio.add(std::max(x, y) > 0 ? std::min(x, y) / std::max(x, y) : 1.0);
    rel.add(x * inv_bmax);
    gs += d > o.gap_small;
    gl += d > o.gap_large;
  }
  const double mu = beam.mean();
  double m2 = 0, m4 = 0;
  for (int k = 0; k < M; ++k) {
    const double e = b[k] - mu;
    m2 += e * e, m4 += e * e * e * e;
  }
  m2 /= M, m4 /= M;
  const double kurt = m2 > 1e-12 ? m4 / (m2 * m2) - 3.0 : 0.0;
  // Chords through the cell.
  const int h = M / 2, q = M / 4;
  double cmin = 1e18, cmax = 0;
  int kstar = 0;
  for (int k = 0; k < h; ++k) {
    const double c = b[k] + b[k + h];
    if (c < cmin) cmin = c, kstar = k;
    cmax = std::max(cmax, c);
  }
  const double perp = b[(kstar + q) % M] + b[(kstar + q + h) % M];
  const double centering = cmin > 0 ? std::min(b[kstar], b[kstar + h]) / cmin : 0.5;
  // Polygon.
  thread_local std::vector<cv::Point2d> poly;
  poly.resize(static_cast<std::size_t>(M));
  const auto& dirs = beamDirections(M);
  for (int k = 0; k < M; ++k) poly[static_cast<std::size_t>(k)] = dirs[static_cast<std::size_t>(k)] * static_cast<double>(b[k]);
  const cv::Moments m = polygonMoments(poly);
  const double A = std::abs(m.m00);
  double L = 0;
  for (int k = 0; k < M; ++k) {
    const cv::Point2d d = poly[static_cast<std::size_t>(k)] - poly[static_cast<std::size_t>(k + 1 < M ? k + 1 : 0)];
    L += std::sqrt(d.x * d.x + d.y * d.y);
  }
  cv::Point2d cen(0, 0);
  if (A > 1e-12) cen = cv::Point2d(m.m10 / m.m00, m.m01 / m.m00);
  MeanStd cd;
  for (const auto& p : poly) cd.add(std::sqrt((p.x - cen.x) * (p.x - cen.x) + (p.y - cen.y) * (p.y - cen.y)));
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
  out[i++] = static_cast<float>(diff.mean());
  out[i++] = static_cast<float>(diff.std());
  out[i++] = static_cast<float>(diffc.mean());
  out[i++] = static_cast<float>(diffc.std());
  out[i++] = static_cast<float>(beam.mean());
  out[i++] = static_cast<float>(beam.std());
  out[i++] = static_cast<float>(gs);
  out[i++] = static_cast<float>(gl);
  out[i++] = static_cast<float>(ratio.mean());
  out[i++] = static_cast<float>(ratio.std());
  out[i++] = static_cast<float>(kurt);
  out[i++] = static_cast<float>(rel.mean());
  out[i++] = static_cast<float>(rel.std());
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
  out[i++] = static_cast<float>(cd.mean());
  out[i++] = static_cast<float>(cd.std());
  out[i++] = static_cast<float>(emaj);
  out[i++] = static_cast<float>(emin);
  out[i++] = static_cast<float>(emaj > 0 ? emin / emaj : 0.0);
  for (double v : hu) out[i++] = static_cast<float>(v);
  out[i++] = static_cast<float>(std::hypot(cen.x, cen.y));
  out[i++] = static_cast<float>(bmax > 0 ? A / (M_PI * bmax * bmax) : 0.0);
}

cv::Mat extractFeatures(const SimulatedScans& scans, const FeatureOptions& options, int threads) {
  const std::size_t n = scans.size(), F = numFeatures();
  const int M = scans.num_beams;
  const std::size_t copies = 1 + options.capped_ranges.size();
  cv::Mat out(static_cast<int>(n), static_cast<int>(F * copies), CV_32F, cv::Scalar(0));
  auto work = [&](std::size_t begin, std::size_t end) {
    std::vector<float> beams(static_cast<std::size_t>(M)), capped(static_cast<std::size_t>(M));
    for (std::size_t i = begin; i < end; ++i) {
      const std::uint16_t* s = scans.scan(i);
      for (int k = 0; k < M; ++k) beams[static_cast<std::size_t>(k)] = s[k] * 0.001f;
      float* row = out.ptr<float>(static_cast<int>(i));
      extractFeatures(beams.data(), M, options, row);
      const float longest = *std::max_element(beams.begin(), beams.end());
      for (std::size_t c = 0; c < options.capped_ranges.size(); ++c) {
        const float cap = static_cast<float>(options.capped_ranges[c]);
        float* copy = row + F * (c + 1);
        if (longest <= cap) {  // no beam reaches the cap: the capped scan is the scan, so are its features
          std::copy(row, row + F, copy);
          continue;
        }
        for (int k = 0; k < M; ++k) capped[static_cast<std::size_t>(k)] = std::min(beams[static_cast<std::size_t>(k)], cap);
        extractFeatures(capped.data(), M, options, copy);
      }
    }
  };
  const std::size_t nt = static_cast<std::size_t>(std::max(1, threads));
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < nt; ++t) pool.emplace_back(work, n * t / nt, n * (t + 1) / nt);
  work(0, n / nt);
  for (auto& t : pool) t.join();
  return out;
}

}  // namespace gridtopo::places
