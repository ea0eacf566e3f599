#include "gridtopo/slam/proposal.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/motion_model.h"
#include "gridtopo/slam/prepared_scan.h"
#include "gridtopo/slam/scan_matcher.h"
#include "gridtopo/slam/slam_options.h"

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

namespace {
/// The minimum sigmas on the proposal's diagonal (numerical safety).
void addFloor(GaussianProposal& g, const ProposalOptions& p) {
  g.cov(0, 0) += p.min_sigma_xy * p.min_sigma_xy;
  g.cov(1, 1) += p.min_sigma_xy * p.min_sigma_xy;
  g.cov(2, 2) += p.min_sigma_theta * p.min_sigma_theta;
}
}  // namespace

ProposalPlan planProposal(const GridMap& map, const Pose2& prev, const Pose2& u, bool has_odometry,
                          const PreparedScan& scan, const SlamOptions& o, const OdometryMotionModel& motion,
                          const Pose2* start) {
  ProposalPlan plan;
  plan.type = o.proposal.type;
  if (o.proposal.type == ProposalType::Odometry) return plan;
  if (o.proposal.type == ProposalType::ModeOnly) {
    plan.matched = true;  // matched per particle in drawFromProposal (from its own motion sample)
    return plan;
  }
  const double inv_gain = 1.0 / o.likelihood_gain;
  const Pose2 predicted = start ? *start : compose(prev, u);
  MatchPrior prior;
  prior.likelihood_scale = inv_gain;
  prior.log_prior = [&](const Pose2& x) { return motion.logDensity(x, prev, u, has_odometry); };
  ScanScorer scorer(map, scan, o.matcher);
  const MatchResult m = matchScan(scorer, predicted, o.matcher.use_motion_prior ? &prior : nullptr);
  plan.evaluations = m.evaluations;
  if (!m.ok) return plan;
  // A weakly supported mode far from the odometry's prediction is a wrong mode (an open square, a featureless
  // facade), not a correction: matching failed.
  const double bound = o.proposal.max_motion_sigmas, weak = o.proposal.weak_match_fraction;
  if (bound > 0.0 && has_odometry && (weak >= 1.0 || m.score.matched < weak * static_cast<double>(scan.size())) &&
      motion.squaredDeviations(relative(prev, m.pose), u) > bound * bound)
    return plan;
  plan.matched = true;
  if (o.proposal.type == ProposalType::Hahnel) {
    plan.gaussian.mean = m.pose;  // the scan-matched pose; the motion model is sampled around it per particle
    return plan;
  }
  // Informed proposal: ln p(z|m,x_j) at K poses on a grid around the mode.
  const int n = o.proposal.points_per_axis;
  const double half = 0.5 * (n - 1);
  std::vector<Pose2> xs;
  std::vector<double> log_lik;
  xs.reserve(static_cast<std::size_t>(n) * n * n);
  log_lik.reserve(xs.capacity());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Pose2 x{m.pose.x + (i - half) * o.proposal.delta_xy, m.pose.y + (j - half) * o.proposal.delta_xy,
                      wrapAngle(m.pose.theta + (k - half) * o.proposal.delta_theta)};
        xs.push_back(x);
        log_lik.push_back((i == n / 2 && j == n / 2 && k == n / 2 && (n % 2) == 1) ? m.score.log_likelihood
                                                                                    : scorer.score(x).log_likelihood);
      }
  plan.evaluations += static_cast<int>(xs.size()) - (n % 2);
  if (o.proposal.fit == ProposalFit::Quadratic) {
    // Laplace's approximation of τ, centred on the mode the hill climb found (to a millimetre; the fit's own peak
    // is smoothed over the grid and biased by truncated beams), with the curvature fitted over the K poses.
    auto fitAtMode = [&](double min_curvature) {
      LocalQuadratic q =
          fitLocalQuadratic(xs, log_lik, m.pose, o.proposal.delta_xy, o.proposal.delta_theta, min_curvature);
      q.b.setZero();
      q.c = m.score.log_likelihood;
      return q;
    };
    // The shape keeps only the directions the scan clearly observes.
    const LocalQuadratic observed = fitAtMode(o.proposal.min_curvature);
    if (observed.ok) {
      const OdometryMotionModel::Sigmas sg = motion.sigmas(u, has_odometry);
      const Pose2 prediction = compose(prev, u);  // the motion prior's mean (the search may start elsewhere)
      // The weight: the softened likelihood at the mode, or the integral of the softened target with every concave
      // direction (the best local model of the integrand). The shape: the likelihood of beams that register to
      // beam_sigma, times the motion prior.
      plan.log_weight_increment =
          o.proposal.weight == ProposalWeight::Mode
              ? m.score.log_likelihood * inv_gain
              : informedGaussian(fitAtMode(0.0), inv_gain, m.pose, prediction, sg.xy, sg.theta).log_eta;
      const double shape_scale = std::pow(o.matcher.sigma / o.proposal.beam_sigma, 2);
      plan.gaussian = informedGaussian(observed, shape_scale, m.pose, prediction, sg.xy, sg.theta);
      addFloor(plan.gaussian, o.proposal);
      return plan;
    }
  }
  // The paper's moments: τ_j = p(z|m,x_j)^(1/gain)·p(x_j|x_{t-1},u).
  std::vector<double> log_tau(xs.size());
  for (std::size_t j = 0; j < xs.size(); ++j)
    log_tau[j] = log_lik[j] * inv_gain + motion.logDensity(xs[j], prev, u, has_odometry);
  plan.gaussian = fitProposal(xs, log_tau, m.pose);
  addFloor(plan.gaussian, o.proposal);
  // The weight factor approximates the integral ∫ p(z|m,x)^(1/gain) p(x|x_{t-1},u) dx, so that it is
  // commensurate with the weight of a particle whose matching failed (odometry proposal: p(z|m,x)^(1/gain) at a
  // motion sample, a one-sample Monte-Carlo estimate of the same integral). η = Σ τ_j alone lacks the grid
  // volume Δx·Δy·Δθ, and such particles would be discarded in every mixed step.
  plan.log_weight_increment =
      o.proposal.laplace_weight
          ? logIntegralOnGrid(xs, log_tau, m.pose, o.proposal.delta_xy, o.proposal.delta_theta)
          : logSumExp(log_tau) + 2.0 * std::log(o.proposal.delta_xy) + std::log(o.proposal.delta_theta);
  return plan;
}

double drawFromProposal(const ProposalPlan& plan, const GridMap& map, const Pose2& prev, const Pose2& u,
                        bool has_odometry, const PreparedScan& scan, const SlamOptions& o,
                        const OdometryMotionModel& motion, Rng& rng, Pose2& out_pose) {
  if (plan.type == ProposalType::ModeOnly) {
    // GMapping: draw from the motion model, climb to the likelihood mode from there, weight p(z|m,x̂).
    const Pose2 start = motion.sample(prev, u, rng, has_odometry);
    const MatchResult m = matchScan(map, start, scan, o.matcher);
    if (m.ok) {
      out_pose = m.pose;
      return m.score.log_likelihood / o.likelihood_gain;
    }
    out_pose = start;
    return scoreScan(map, start, scan, o.matcher).log_likelihood / o.likelihood_gain;
  }
  if (!plan.matched) {
    // Odometry proposal (also the fallback when matching failed): sample the motion model, weight by p(z|m,x).
    out_pose = motion.sample(prev, u, rng, has_odometry);
    return scoreScan(map, out_pose, scan, o.matcher).log_likelihood / o.likelihood_gain;
  }
  if (plan.type == ProposalType::Hahnel) {
    // Hähnel et al. 2003: the motion from x_{t-1} to the scan-matched pose replaces the odometry increment; the
    // motion model (with the noise of the measured increment u) is sampled around it; weight p(z|m,x)^(1/gain).
    const Pose2 u_matched = relative(prev, plan.gaussian.mean);
    const OdometryMotionModel::Sigmas sg = motion.sigmas(u, has_odometry);
    out_pose = compose(prev, {u_matched.x + rng.gaussian(sg.xy), u_matched.y + rng.gaussian(sg.xy),
                              u_matched.theta + rng.gaussian(sg.theta)});
    return scoreScan(map, out_pose, scan, o.matcher).log_likelihood / o.likelihood_gain;
  }
  out_pose = plan.type == ProposalType::Informed ? sampleGaussian(plan.gaussian, rng) : plan.gaussian.mean;
  return plan.log_weight_increment;
}

}  // namespace gridtopo::slam
