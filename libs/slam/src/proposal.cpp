#include "gridtopo/slam/proposal.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
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

namespace {
/// Least-squares quadratic v ≈ m + a0 + gᵀu + ½ uᵀHu over the poses, in grid units u = (x, y, θ) offsets from
/// `reference` / spacing (well conditioned). Returns false when it cannot be fitted (fewer than 10 poses, a
/// non-finite maximum, a rank-deficient design); `m` is the maximum of `values`, subtracted before the fit.
bool fitQuadraticInGridUnits(const std::vector<Pose2>& poses, const std::vector<double>& values,
                             const Pose2& reference, double delta_xy, double delta_theta, double& m, double& a0,
                             Eigen::Vector3d& g, Eigen::Matrix3d& H) {
  const std::size_t n = poses.size();
  if (n < 10) return false;
  m = *std::max_element(values.begin(), values.end());
  if (!std::isfinite(m)) return false;
  Eigen::MatrixXd J(n, 10);
  Eigen::VectorXd r(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double u0 = (poses[j].x - reference.x) / delta_xy, u1 = (poses[j].y - reference.y) / delta_xy;
    const double u2 = wrapAngle(poses[j].theta - reference.theta) / delta_theta;
    J.row(static_cast<Eigen::Index>(j)) << 1.0, u0, u1, u2, 0.5 * u0 * u0, 0.5 * u1 * u1, 0.5 * u2 * u2, u0 * u1,
        u0 * u2, u1 * u2;
    r(static_cast<Eigen::Index>(j)) = values[j] - m;
  }
  const auto qr = J.colPivHouseholderQr();
  if (qr.rank() < 10) return false;
  const Eigen::VectorXd a = qr.solve(r);
  a0 = a(0);
  g = {a(1), a(2), a(3)};
  H << a(4), a(7), a(8), a(7), a(5), a(9), a(8), a(9), a(6);
  return true;
}
}  // namespace

double logIntegralOnGrid(const std::vector<Pose2>& poses, const std::vector<double>& log_f, const Pose2& reference,
                         double delta_xy, double delta_theta) {
  const double riemann = logSumExp(log_f) + 2.0 * std::log(delta_xy) + std::log(delta_theta);
  double m = 0.0, a0 = 0.0;
  Eigen::Vector3d g;
  Eigen::Matrix3d A;
  if (!fitQuadraticInGridUnits(poses, log_f, reference, delta_xy, delta_theta, m, a0, g, A)) return riemann;
  Eigen::LLT<Eigen::Matrix3d> llt(-A);
  if (llt.info() != Eigen::Success) return riemann;
  const Eigen::Vector3d ustar = llt.solve(g);  // the quadratic's maximum: u* = (-A)^-1 g
  if (!(ustar.cwiseAbs().maxCoeff() <= 2.0)) return riemann;  // mode far outside the grid: do not extrapolate
  const double peak = m + a0 + 0.5 * g.dot(ustar);
  double log_det = 0.0;
  for (int i = 0; i < 3; ++i) log_det += 2.0 * std::log(llt.matrixL()(i, i));
  constexpr double kLog2Pi = 1.8378770664093453;
  const double laplace = peak + 1.5 * kLog2Pi - 0.5 * log_det + 2.0 * std::log(delta_xy) + std::log(delta_theta);
  // The integral over all poses is at least the integral over the grid's box.
  return std::max(laplace, riemann);
}

LocalQuadratic fitLocalQuadratic(const std::vector<Pose2>& poses, const std::vector<double>& log_lik,
                                 const Pose2& mode, double delta_xy, double delta_theta, double min_curvature) {
  LocalQuadratic q;
  double m = 0.0, a0 = 0.0;
  Eigen::Vector3d g;
  Eigen::Matrix3d H;  // Hessian of ln L in grid units
  if (!fitQuadraticInGridUnits(poses, log_lik, mode, delta_xy, delta_theta, m, a0, g, H)) return q;
  // Curvature −H made positive semi-definite, and degenerate directions removed (Zhang, Kaess, Singh, "On
  // degeneracy of optimization-based state estimation problems", ICRA 2016): a direction along which moving one
  // grid step changes ln p by less than ½·min_curvature (a corridor's axis, where only the sub-cell ripple of the
  // grid likelihood remains) says nothing about the pose, so it gets neither curvature nor slope.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(-H);
  Eigen::Vector3d lambda = es.eigenvalues();
  Eigen::Vector3d gb = es.eigenvectors().transpose() * g;
  for (int i = 0; i < 3; ++i) {
    if (!(lambda(i) > std::max(min_curvature, 1e-9))) {
      lambda(i) = 0.0;
      gb(i) = 0.0;
    }
  }
  const Eigen::Matrix3d Pu = es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
  const Eigen::Vector3d bu = es.eigenvectors() * gb;
  const Eigen::Vector3d s(1.0 / delta_xy, 1.0 / delta_xy, 1.0 / delta_theta);  // δ → u
  q.P = s.asDiagonal() * Pu * s.asDiagonal();
  q.b = s.asDiagonal() * bu;
  q.c = m + a0;
  q.ok = true;
  return q;
}

GaussianProposal informedGaussian(const LocalQuadratic& q, double scale, const Pose2& mode, const Pose2& predicted,
                                  double sigma_xy, double sigma_theta) {
  // ln τ(x̂+δ) = scale·(c + bᵀδ − ½δᵀPδ) + c_u − ½(δ − e)ᵀ W (δ − e), e = prediction − mode, W = Σ_u⁻¹.
  const Eigen::Vector3d w(1.0 / (sigma_xy * sigma_xy), 1.0 / (sigma_xy * sigma_xy), 1.0 / (sigma_theta * sigma_theta));
  const Eigen::Vector3d e(predicted.x - mode.x, predicted.y - mode.y, wrapAngle(predicted.theta - mode.theta));
  constexpr double kLog2Pi = 1.8378770664093453;
  const double c_u = -2.0 * std::log(sigma_xy) - std::log(sigma_theta) - 1.5 * kLog2Pi;
  const Eigen::Matrix3d Lambda = scale * q.P + Eigen::Matrix3d(w.asDiagonal());
  const Eigen::Vector3d h = scale * q.b + w.cwiseProduct(e);
  const Eigen::LLT<Eigen::Matrix3d> llt(Lambda);  // W is positive definite, so Λ is
  const Eigen::Vector3d delta = llt.solve(h);
  double log_det = 0.0;
  for (int i = 0; i < 3; ++i) log_det += 2.0 * std::log(llt.matrixL()(i, i));
  GaussianProposal g;
  g.mean = {mode.x + delta.x(), mode.y + delta.y(), wrapAngle(mode.theta + delta.z())};
  g.cov = llt.solve(Eigen::Matrix3d::Identity());
  g.cov = 0.5 * (g.cov + g.cov.transpose());
  const double peak = scale * q.c + c_u - 0.5 * e.dot(w.cwiseProduct(e)) + 0.5 * h.dot(delta);
  g.log_eta = peak + 1.5 * kLog2Pi - 0.5 * log_det;
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
