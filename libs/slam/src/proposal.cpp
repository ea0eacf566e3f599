#include "gridtopo/slam/proposal.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

namespace gridtopo::slam {

double logSumExp(const std::vector<double>& v) {
  double m = -std::numeric_limits<double>::infinity();
  for (double x : v) m = std::max(m, x);
  if (!std::isfinite(m)) return m;
  double s = 0.0;
  for (double x : v) s += std::exp(x - m);
  return m + std::log(s);
}

GaussianProposal fitProposal(const std::vector<Pose2>& poses, const std::vector<double>& log_tau,
                             const Pose2& reference) {
  GaussianProposal g;
  g.log_eta = logSumExp(log_tau);
  const double m = g.log_eta;
  Eigen::Vector3d mu = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> d(poses.size());
  std::vector<double> w(poses.size());
  for (std::size_t j = 0; j < poses.size(); ++j) {
    w[j] = std::exp(log_tau[j] - m);  // normalised: Σ w = 1
    d[j] = {poses[j].x, poses[j].y, wrapAngle(poses[j].theta - reference.theta)};
    mu += w[j] * d[j];
  }
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::size_t j = 0; j < poses.size(); ++j) {
    const Eigen::Vector3d e = d[j] - mu;
    cov += w[j] * e * e.transpose();
  }
  g.mean = {mu.x(), mu.y(), wrapAngle(reference.theta + mu.z())};
  g.cov = cov;
  return g;
}

Pose2 sampleGaussian(const GaussianProposal& g, Rng& rng) {
  Eigen::LDLT<Eigen::Matrix3d> ldlt(g.cov);
  Eigen::Vector3d z(rng.gaussian(), rng.gaussian(), rng.gaussian());
  // cov = Pᵀ L D Lᵀ P  ->  x = Pᵀ L sqrt(D) z
  Eigen::Vector3d dz = ldlt.vectorD().cwiseMax(0.0).cwiseSqrt().cwiseProduct(z);
  Eigen::Vector3d x = ldlt.transpositionsP().transpose() * (ldlt.matrixL() * dz);
  return {g.mean.x + x.x(), g.mean.y + x.y(), wrapAngle(g.mean.theta + x.z())};
}

}  // namespace gridtopo::slam
