#include "gridtopo/slam/proposal.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
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

double logIntegralOnGrid(const std::vector<Pose2>& poses, const std::vector<double>& log_f, const Pose2& reference,
                         double delta_xy, double delta_theta) {
  const double riemann = logSumExp(log_f) + 2.0 * std::log(delta_xy) + std::log(delta_theta);
  const std::size_t n = poses.size();
  if (n < 10) return riemann;
  const double m = *std::max_element(log_f.begin(), log_f.end());
  if (!std::isfinite(m)) return riemann;
  // Least-squares quadratic ln f ≈ c + gᵀu + ½ uᵀAu in grid units u = (x, y, θ) offsets / spacing.
  Eigen::MatrixXd J(n, 10);
  Eigen::VectorXd b(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double u0 = (poses[j].x - reference.x) / delta_xy, u1 = (poses[j].y - reference.y) / delta_xy;
    const double u2 = wrapAngle(poses[j].theta - reference.theta) / delta_theta;
    J.row(static_cast<Eigen::Index>(j)) << 1.0, u0, u1, u2, 0.5 * u0 * u0, 0.5 * u1 * u1, 0.5 * u2 * u2, u0 * u1,
        u0 * u2, u1 * u2;
    b(static_cast<Eigen::Index>(j)) = log_f[j] - m;
  }
  const Eigen::VectorXd q = J.colPivHouseholderQr().solve(b);
  Eigen::Matrix3d A;
  A << q(4), q(7), q(8), q(7), q(5), q(9), q(8), q(9), q(6);
  const Eigen::Vector3d g(q(1), q(2), q(3));
  Eigen::LLT<Eigen::Matrix3d> llt(-A);
  if (llt.info() != Eigen::Success) return riemann;
  const Eigen::Vector3d ustar = llt.solve(g);  // the quadratic's maximum: u* = (-A)^-1 g
  if (!(ustar.cwiseAbs().maxCoeff() <= 2.0)) return riemann;  // mode far outside the grid: do not extrapolate
  const double peak = m + q(0) + 0.5 * g.dot(ustar);
  double log_det = 0.0;
  for (int i = 0; i < 3; ++i) log_det += 2.0 * std::log(llt.matrixL()(i, i));
  constexpr double kLog2Pi = 1.8378770664093453;
  const double laplace = peak + 1.5 * kLog2Pi - 0.5 * log_det + 2.0 * std::log(delta_xy) + std::log(delta_theta);
  // The integral over all poses is at least the integral over the grid's box.
  return std::max(laplace, riemann);
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
