#include <gtest/gtest.h>

#include <cmath>

#include "gridtopo/slam/proposal.h"
#include "gridtopo/slam/resampling.h"

using namespace gridtopo::slam;

TEST(Proposal, MeanAndCovarianceMatchBruteForceAcrossPi) {
  // Poses straddling ±pi with arbitrary log-weights far from 0 (would underflow without log-sum-exp).
  Rng rng(3);
  std::vector<Pose2> xs;
  std::vector<double> lt;
  for (int i = 0; i < 27; ++i) {
    xs.push_back({1.0 + 0.02 * rng.gaussian(), -3.0 + 0.02 * rng.gaussian(), wrapAngle(M_PI + 0.01 * rng.gaussian())});
    lt.push_back(-2000.0 - 3.0 * rng.uniform());
  }
  const Pose2 ref{1.0, -3.0, M_PI - 0.001};
  const GaussianProposal g = fitProposal(xs, lt, ref);
  // Brute force with long double and explicit unwrapping around pi.
  long double eta = 0, m[3] = {0, 0, 0};
  std::vector<std::array<long double, 3>> v;
  for (std::size_t j = 0; j < xs.size(); ++j) {
    double th = xs[j].theta;
    if (th < 0) th += 2 * M_PI;
    v.push_back({xs[j].x, xs[j].y, th});
    const long double w = std::exp(static_cast<long double>(lt[j]) + 2000.0L);
    eta += w;
    for (int a = 0; a < 3; ++a) m[a] += w * v.back()[a];
  }
  for (auto& a : m) a /= eta;
  long double c[3][3] = {};
  for (std::size_t j = 0; j < xs.size(); ++j) {
    const long double w = std::exp(static_cast<long double>(lt[j]) + 2000.0L) / eta;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) c[a][b] += w * (v[j][a] - m[a]) * (v[j][b] - m[b]);
  }
  EXPECT_NEAR(g.log_eta, static_cast<double>(std::log(eta) - 2000.0L), 1e-9);
  EXPECT_NEAR(g.mean.x, static_cast<double>(m[0]), 1e-12);
  EXPECT_NEAR(g.mean.y, static_cast<double>(m[1]), 1e-12);
  EXPECT_NEAR(wrapAngle(g.mean.theta - static_cast<double>(m[2])), 0.0, 1e-12);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(g.cov(a, b), static_cast<double>(c[a][b]), 1e-12) << a << b;
}

TEST(Proposal, SamplesHaveTheFittedCovariance) {
  GaussianProposal g;
  g.mean = {2.0, 1.0, 3.1};
  g.cov << 4e-4, 1e-4, 2e-5, 1e-4, 2e-4, -1e-5, 2e-5, -1e-5, 1e-4;
  Rng rng(9);
  const int n = 100000;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> d(n);
  for (int i = 0; i < n; ++i) {
    const Pose2 p = sampleGaussian(g, rng);
    d[i] = {p.x - 2.0, p.y - 1.0, wrapAngle(p.theta - 3.1)};
    mean += d[i];
  }
  mean /= n;
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (const auto& e : d) c += (e - mean) * (e - mean).transpose();
  c /= n - 1;
  EXPECT_LT(mean.norm(), 3e-4);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(c(a, b), g.cov(a, b), 0.03 * std::sqrt(g.cov(a, a) * g.cov(b, b)));
}

TEST(Proposal, DegenerateCovarianceSamplesTheMean) {
  GaussianProposal g;
  g.mean = {1, 2, 0.5};
  Rng rng(1);
  const Pose2 p = sampleGaussian(g, rng);
  EXPECT_DOUBLE_EQ(p.x, 1);
  EXPECT_DOUBLE_EQ(p.theta, 0.5);
}

TEST(Resampling, EffectiveSampleSize) {
  EXPECT_DOUBLE_EQ(effectiveSampleSize(normalizedWeights({-5, -5, -5, -5})), 4.0);
  EXPECT_NEAR(effectiveSampleSize(normalizedWeights({0, -1000, -1000, -1000})), 1.0, 1e-12);
  // Two equal particles out of four: N_eff = 2.
  EXPECT_NEAR(effectiveSampleSize(normalizedWeights({-1e4, -1e4, -1e6, -1e6})), 2.0, 1e-12);
  const auto w = normalizedWeights({1000.0, 1000.0 + std::log(3.0)});
  EXPECT_NEAR(w[0], 0.25, 1e-12);
  EXPECT_NEAR(w[1], 0.75, 1e-12);
}

TEST(Resampling, LowVarianceKeepsCopiesProportionalToWeights) {
  const std::vector<double> w = {0.5, 0.25, 0.125, 0.125, 0.0, 0.0, 0.0, 0.0};
  for (int seed = 0; seed < 50; ++seed) {
    Rng rng(seed);
    const auto idx = lowVarianceResample(w, rng);
    ASSERT_EQ(idx.size(), w.size());
    std::vector<int> count(w.size(), 0);
    for (auto i : idx) ++count[i];
    // Systematic resampling: every count is floor or ceil of N·w (here exact).
    EXPECT_EQ(count[0], 4);
    EXPECT_EQ(count[1], 2);
    EXPECT_EQ(count[2], 1);
    EXPECT_EQ(count[3], 1);
    EXPECT_TRUE(std::is_sorted(idx.begin(), idx.end()));
  }
  // Non-dyadic weights: counts within one of N·w.
  const std::vector<double> w2 = {0.3, 0.45, 0.05, 0.2};
  Rng rng(5);
  std::vector<int> count(4, 0);
  for (auto i : lowVarianceResample(w2, rng)) ++count[i];
  for (int i = 0; i < 4; ++i) EXPECT_LE(std::abs(count[i] - 4 * w2[i]), 1.0);
}
