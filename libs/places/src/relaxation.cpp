#include "gridtopo/places/relaxation.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "gridtopo/core/error.h"

namespace gridtopo::places {

const OptionSchema<RelaxationOptions>& relaxationOptionSchema() {
  using O = RelaxationOptions;
  static const OptionSchema<O> schema =
      OptionSchema<O>("gridtopo::places::RelaxationOptions")
          .add("max_iterations", &O::max_iterations, OptionRange::closed(0, 10000), "",
               "upper bound on the iterations (0 = no relaxation)")
          .add("tolerance", &O::tolerance, OptionRange::above(0), "",
               "stop when no probability changes by more than this in an iteration")
          .add("neighbourhood_radius", &O::neighbourhood_radius, OptionRange::closed(1, 50), "lattice cells",
               "N(i): the lattice cells within this Chebyshev distance (1 = the 8-neighbourhood)");
  return schema;
}

void RelaxationOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& s, const std::string& sec) {
  relaxationOptionSchema().load(*this, s, sec);
}

void RelaxationOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t, const std::string& sec) const {
  relaxationOptionSchema().save(*this, t, sec);
}

void RelaxationOptions::dumpToTextStream(std::ostream& out) const { relaxationOptionSchema().dump(*this, out); }

void RelaxationOptions::validate(const std::string& file, const std::string& section) const {
  relaxationOptionSchema().validate(*this, file, section);
}

void accumulateNeighbourCounts(const cv::Mat& labels, std::array<std::array<double, kNumLabels>, kNumLabels>& counts) {
  CV_Assert(labels.type() == CV_32S);
  for (int r = 0; r < labels.rows; ++r)
    for (int c = 0; c < labels.cols; ++c) {
      const int a = labels.at<int>(r, c);
      if (a < 0) continue;
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
          if (!dr && !dc) continue;
          const int rr = r + dr, cc = c + dc;
          if (rr < 0 || cc < 0 || rr >= labels.rows || cc >= labels.cols) continue;
          const int b = labels.at<int>(rr, cc);
          if (b >= 0) counts[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] += 1;
        }
    }
}

Compatibility compatibilityFromCounts(const std::array<std::array<double, kNumLabels>, kNumLabels>& counts) {
  double total = 0;
  std::array<double, kNumLabels> marg{};
  for (int a = 0; a < kNumLabels; ++a)
    for (int b = 0; b < kNumLabels; ++b) total += counts[a][b], marg[a] += counts[a][b];
  Compatibility r{};
  for (int a = 0; a < kNumLabels; ++a)
    for (int b = 0; b < kNumLabels; ++b) {
      if (total <= 0 || marg[a] <= 0 || marg[b] <= 0) { r[a][b] = 0; continue; }
      const double pab = 0.5 * (counts[a][b] + counts[b][a]) / total;
      if (pab <= 0) { r[a][b] = -1; continue; }
      const double pa = marg[a] / total, pb = marg[b] / total;
      const double npmi = pab >= 1.0 ? 1.0 : std::log(pab / (pa * pb)) / -std::log(pab);
      r[a][b] = std::clamp(npmi, -1.0, 1.0);
    }
  return r;
}

namespace {
RelaxationResult relaxGrid(cv::Mat& probs, const cv::Mat& valid, const Compatibility& r,
                           const RelaxationOptions& options, int threads) {
  RelaxationResult res;
  cv::Mat next = probs.clone();
  const int rows = probs.rows, cols = probs.cols;
  std::vector<double> change(static_cast<std::size_t>(std::max(1, threads)), 0.0);
  const int R = options.neighbourhood_radius;
  // Sums over the (2R+1)^2 window from integral images (rows+1 x cols+1): per-cell cost independent of R. The
  // integral's rows are computed in order and kept in a ring of kBand + 2R + 2 rows: a band of kBand output rows
  // reads the integral rows from its first row - R to its last + R + 1 (the values, and so the results, are those
  // of the whole integral image).
  constexpr int kBand = 128;
  const int ring = kBand + 2 * R + 2;
  const std::size_t row_len = static_cast<std::size_t>(cols + 1) * (kNumLabels + 1);
  std::vector<double> integ(static_cast<std::size_t>(ring) * row_len, 0.0);
  const auto at = [&](int y, int x) {
    return integ.data() + static_cast<std::size_t>(y % ring) * row_len + static_cast<std::size_t>(x) * (kNumLabels + 1);
  };
  for (int it = 0; it < options.max_iterations; ++it) {
    std::fill(at(0, 0), at(0, 0) + row_len, 0.0);
    int computed = 0;  // integral rows 0..computed are ready
    auto work = [&](int t, int r0, int r1) {
      double mx = 0;
      for (int y = r0; y < r1; ++y)
        for (int x = 0; x < cols; ++x) {
          if (!valid.at<unsigned char>(y, x)) continue;
          const int y0 = std::max(0, y - R), y1 = std::min(rows, y + R + 1);
          const int x0 = std::max(0, x - R), x1 = std::min(cols, x + R + 1);
          const double *a = at(y1, x1), *b = at(y0, x1), *c = at(y1, x0), *d = at(y0, x0);
          const cv::Vec3f& pi = probs.at<cv::Vec3f>(y, x);
          double s[kNumLabels];
          for (int l = 0; l < kNumLabels; ++l) s[l] = a[l] - b[l] - c[l] + d[l] - pi[l];  // without the cell itself
          const double n = std::round(a[kNumLabels] - b[kNumLabels] - c[kNumLabels] + d[kNumLabels]) - 1;
          cv::Vec3f& out = next.at<cv::Vec3f>(y, x);
          if (n < 0.5) { out = pi; continue; }
          double u[kNumLabels], z = 0;
          for (int l = 0; l < kNumLabels; ++l) {
            double q = 0;
            for (int m = 0; m < kNumLabels; ++m) q += r[l][m] * s[m] / n;
            u[l] = pi[l] * (1.0 + q);
            z += u[l];
          }
          for (int l = 0; l < kNumLabels; ++l) {
            const float v = z > 0 ? static_cast<float>(u[l] / z) : pi[l];
            mx = std::max(mx, static_cast<double>(std::abs(v - pi[l])));
            out[l] = v;
          }
        }
      change[static_cast<std::size_t>(t)] = std::max(change[static_cast<std::size_t>(t)], mx);
    };
    std::fill(change.begin(), change.end(), 0.0);
    const int nt = std::max(1, threads);
    for (int band = 0; band < rows; band += kBand) {
      const int band_end = std::min(rows, band + kBand);
      for (const int need = std::min(rows, band_end + R); computed < need; ++computed) {
        const int y = computed;  // integral row y + 1 from image row y
        double* o0 = at(y + 1, 0);
        std::fill(o0, o0 + (kNumLabels + 1), 0.0);
        for (int x = 0; x < cols; ++x) {
          double v[kNumLabels + 1] = {0, 0, 0, 0};
          if (valid.at<unsigned char>(y, x)) {
            const cv::Vec3f& pj = probs.at<cv::Vec3f>(y, x);
            for (int l = 0; l < kNumLabels; ++l) v[l] = pj[l];
            v[kNumLabels] = 1;
          }
          double* o = at(y + 1, x + 1);
          const double *a = at(y, x + 1), *b = at(y + 1, x), *c = at(y, x);
          for (int l = 0; l <= kNumLabels; ++l) o[l] = v[l] + a[l] + b[l] - c[l];
        }
      }
      const int n_rows = band_end - band;
      std::vector<std::thread> pool;
      for (int t = 1; t < nt; ++t) pool.emplace_back(work, t, band + n_rows * t / nt, band + n_rows * (t + 1) / nt);
      work(0, band, band + n_rows / nt);
      for (auto& t : pool) t.join();
    }
    std::swap(probs, next);
    res.iterations = it + 1;
    res.last_change = *std::max_element(change.begin(), change.end());
    if (res.last_change < options.tolerance) { res.converged = true; break; }
  }
  if (options.max_iterations == 0) res.converged = true;
  return res;
}
}  // namespace

cv::Rect relaxationBox(cv::Rect valid_blocks, cv::Size grid, const RelaxationOptions& options) {
  const cv::Rect all(cv::Point(), grid);
  if (valid_blocks.empty()) return all;
  const int m = options.neighbourhood_radius + 1;
  return cv::Rect(valid_blocks.x - m, valid_blocks.y - m, valid_blocks.width + 2 * m, valid_blocks.height + 2 * m) & all;
}

RelaxationResult relaxLabels(cv::Mat& probs, const cv::Mat& valid, const Compatibility& r,
                             const RelaxationOptions& options, int threads) {
  options.validate();
  CV_Assert(probs.type() == CV_32FC3 && valid.type() == CV_8U && valid.size() == probs.size());
  // Only the box of the valid blocks, widened by the neighbourhood and one block more, is relaxed: outside it no
  // block is valid, so the integral sums before it are exact zeros and those the widened box reads are the very
  // values of the whole grid's (on a large map whose places fill a part of it, less time and one grid less).
  int y0 = valid.rows, y1 = -1, x0 = valid.cols, x1 = -1;
  for (int y = 0; y < valid.rows; ++y) {
    const unsigned char* v = valid.ptr<unsigned char>(y);
    for (int x = 0; x < valid.cols; ++x)
      if (v[x]) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = y;
  }
  const cv::Rect all(0, 0, probs.cols, probs.rows);
  const cv::Rect box =
      relaxationBox(y1 < 0 ? cv::Rect() : cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1), probs.size(), options);
  if (box == all) return relaxGrid(probs, valid, r, options, threads);
  cv::Mat part = probs(box);
  RelaxationResult res = relaxGrid(part, valid(box), r, options, threads);
  if (part.data != probs(box).data) part.copyTo(probs(box));  // the last iteration's grid is the other buffer
  return res;
}

}  // namespace gridtopo::places
