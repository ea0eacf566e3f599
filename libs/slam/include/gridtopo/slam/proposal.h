#pragma once
// The improved proposal of Grisetti, Stachniss, Burgard (IEEE T-RO 2007, eq. 9-13): around the scan-matching
// mode x̂, K poses x_j are weighted by τ_j = p(z|m,x_j)·p(x_j|x_{t-1},u); the Gaussian N(μ, Σ) fitted to them
// is the proposal, and η = Σ_j τ_j is the particle's weight factor. Everything in log space.
#include <Eigen/Core>
#include <vector>

#include "gridtopo/slam/pose2.h"
#include "gridtopo/slam/random.h"

namespace gridtopo::slam {

enum class ProposalType {
  Informed,  ///< Gaussian fitted around the mode (the paper's proposal)
  ModeOnly,  ///< the particle jumps to the mode, weight p(z|m,x̂) (what GMapping ships)
  Odometry,  ///< classic SIR: sample the motion model, weight p(z|m,x)
};

struct ProposalOptions {
  ProposalType type = ProposalType::Informed;
  int points_per_axis = 3;     ///< K = points_per_axis³ poses on a grid around the mode
  double delta_xy = 0.01;      ///< m, grid spacing in x and y
  double delta_theta = 0.005;  ///< rad, grid spacing in θ
  double min_sigma_xy = 1e-3;  ///< m, floor on the proposal's standard deviations (numerical safety)
  double min_sigma_theta = 5e-4;
  /// Weight factor ≈ ∫ p(z|m,x) p(x|x_{t-1},u) dx: false = the Riemann sum η·Δx·Δy·Δθ over the grid (the paper's
  /// η times the grid volume), true = the Laplace approximation of a quadratic fit of ln τ over the grid (also
  /// counts the mass outside a narrow grid; see logIntegralOnGrid).
  bool laplace_weight = false;
  /// Informed proposal: where the mode search starts. 0 = the odometry prediction x_{t-1} ⊕ u (the paper;
  /// particles duplicated by resampling share one search); k > 0 = x_{t-1} ⊕ (u + k·ε), ε drawn from the motion
  /// model, one draw per particle (k = 1: a motion sample, as GMapping starts its search). Where the likelihood
  /// is flat (along a corridor) the mode then keeps that spread, so the particles stay diverse in the directions
  /// the scan cannot observe. Not used for scans without odometry (their prior is no noise model).
  double start_spread = 0.0;
};

struct GaussianProposal {
  Pose2 mean;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double log_eta = 0.0;  ///< ln Σ_j τ_j
};

/// Fits μ, Σ and ln η to poses with log-weights ln τ_j. Angles are averaged relative to `reference` (the mode),
/// with wrapped differences, so poses on both sides of ±π are handled.
GaussianProposal fitProposal(const std::vector<Pose2>& poses, const std::vector<double>& log_tau,
                             const Pose2& reference);

/// Draws from N(mean, cov) (3×3, positive semi-definite), angle wrapped.
Pose2 sampleGaussian(const GaussianProposal& g, Rng& rng);

/// ln ∫ f(x) dx from ln f at the poses of a regular grid around `reference` (spacing delta_xy, delta_theta):
/// the Laplace approximation of a least-squares quadratic fit of ln f (the Gaussian integral of its peak), which
/// also counts the mass outside a narrow grid; never less than the Riemann sum Σ f·Δx·Δy·Δθ, which it falls
/// back to when the fit is not concave or its peak lies outside the grid.
double logIntegralOnGrid(const std::vector<Pose2>& poses, const std::vector<double>& log_f, const Pose2& reference,
                         double delta_xy, double delta_theta);

/// ln Σ exp(v).
double logSumExp(const std::vector<double>& v);

}  // namespace gridtopo::slam
