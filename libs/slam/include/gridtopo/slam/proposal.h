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
  /// Hähnel, Burgard, Fox, Thrun, IROS 2003: the scan-matched motion is the odometry measurement; sample the motion
  /// model around it, weight p(z|m,x) at the sample (the baseline of Grisetti et al. 2007, Sec. VII)
  Hahnel,
  Odometry,  ///< classic SIR: sample the motion model, weight p(z|m,x)
};

/// How N(μ, Σ) is fitted to the K evaluated poses.
enum class ProposalFit {
  /// Least-squares quadratic of ln p(z|m,x) over the K poses (curvature made positive semi-definite), times the
  /// exact Gaussian motion prior: Σ = (P/gain + Σ_u⁻¹)⁻¹, and ln η by the Laplace integral. Unbiased when the
  /// grid spans about a map cell, so the fit sees the likelihood's shape through its sub-cell ripple.
  Quadratic,
  /// The paper's weighted moments of the K poses (eq. 11-12) and η = Σ τ_j. Σ can never exceed the grid's own
  /// spread, so along a corridor (flat likelihood) the proposal stays as narrow as the grid.
  Moments,
};

/// The informed proposal's weight factor (quadratic fit).
enum class ProposalWeight {
  /// p(z|m,x̂)^(1/gain) at the mode, as GMapping weighs. The default: the motion prior's density is not softened
  /// by the gain while the likelihood is, so in the integral below it dominates the weights where odometry errs
  /// systematically (measured worse on Intel, ACES and MIT CSAIL; doc/slam.md).
  Mode,
  /// The paper's η: ∫ p(z|m,x)^(1/gain) p(x|x_{t-1},u) dx, by Laplace's approximation around the mode.
  Integral,
};

struct ProposalOptions {
  ProposalType type = ProposalType::Informed;
  ProposalFit fit = ProposalFit::Quadratic;
  ProposalWeight weight = ProposalWeight::Mode;
  int points_per_axis = 3;     ///< K = points_per_axis³ poses on a grid around the mode
  double delta_xy = 0.05;      ///< m, grid spacing in x and y (about one map cell: see ProposalFit)
  double delta_theta = 0.02;   ///< rad, grid spacing in θ
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
  double start_spread = 1.0;
  /// Matching fails (the odometry proposal instead) when a weak match's mode lies further than this from the
  /// odometry's prediction, in standard deviations of the motion model (Mahalanobis over x, y, θ): few beams
  /// support it, and the motion model says the robot cannot have got there (the outdoor campus: in an open square
  /// the filter turned 20-30° per metre, its odometry under 1°). 0 = no bound. Scans without odometry are not
  /// bounded.
  double max_motion_sigmas = 3.0;
  /// A match is weak when fewer than this fraction of the matching beams found a correspondence at its mode. A
  /// strong match far from the prediction is a correction of the odometry (FR079's odometry errs by more than six
  /// deviations on 1.4 % of its steps; there 98 % of the beams match, in the campus's open squares 60 %).
  /// 1 = every match is bounded.
  double weak_match_fraction = 0.75;
  /// Informed proposal: the trajectory reports, for each pose, the mean of the Gaussian it was drawn from (the
  /// Rao-Blackwellized estimate of the pose given the particle's past poses and the scan) instead of the sample.
  /// The filter itself (maps, weights, next predictions) always uses the sample. false = report the samples.
  bool report_mean = true;
  /// Quadratic fit: the shape N(μ, Σ) uses the likelihood of a beam whose end point registers to within this
  /// standard deviation (m): ln p(z|m,x)·(match_sigma / beam_sigma)². match_sigma is wide so that the matcher has
  /// a basin to climb, and likelihood_gain softens the weights for correlated beams; neither says how precisely a
  /// scan registers, which is what the proposal's spread must be (a wider spread adds that much noise to every
  /// pose and map). About the laser's range noise plus the map's sub-cell error.
  double beam_sigma = 0.01;
  /// Quadratic fit: a direction whose fitted curvature of ln p(z|m,x) is at most this many nats per grid step²
  /// (moving one step changes ln p by at most half of it) is unobserved: the proposal takes the motion model there.
  double min_curvature = 2.0;
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

/// ln p(z|m, x̂ + δ) ≈ c + bᵀδ − ½ δᵀ P δ around a mode x̂, δ = (dx, dy, dθ) in m and rad, P positive
/// semi-definite. Directions in which the fitted likelihood is not (clearly) concave carry no information (P and b
/// are 0 there).
struct LocalQuadratic {
  double c = 0.0;
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  bool ok = false;  ///< false: fewer than 10 poses or a singular design
};

/// Least-squares quadratic fit of `log_lik` at `poses` (a grid around `mode`, spacing delta_xy, delta_theta).
/// Eigen-directions whose curvature, in nats per grid step², is at most `min_curvature` count as unobserved.
LocalQuadratic fitLocalQuadratic(const std::vector<Pose2>& poses, const std::vector<double>& log_lik,
                                 const Pose2& mode, double delta_xy, double delta_theta, double min_curvature = 0.0);

/// The informed proposal from a local quadratic of ln p(z|m,x) and the Gaussian motion prior N(predicted,
/// diag(σ_xy², σ_xy², σ_θ²)) (the odometry model is exactly Gaussian in world coordinates):
/// τ(x) = p(z|m,x)^scale · p(x|x_{t-1},u); mean and covariance of that Gaussian product, and log_eta = ln ∫ τ dx
/// (Laplace). `scale` = 1/gain.
GaussianProposal informedGaussian(const LocalQuadratic& q, double scale, const Pose2& mode, const Pose2& predicted,
                                  double sigma_xy, double sigma_theta);

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

class GridMap;
struct PreparedScan;
class OdometryMotionModel;
struct SlamOptions;

/// The deterministic part of one particle's step (predict, match, sample around the mode, fit the proposal):
/// it depends only on the particle's map and previous pose, so particles duplicated by resampling share it.
struct ProposalPlan {
  bool matched = false;            ///< false: fall back to the odometry proposal
  ProposalType type = ProposalType::Informed;
  GaussianProposal gaussian;       ///< informed: N(μ, Σ) and ln η; mode-only: the mode in `mean`
  double log_weight_increment = 0.0;  ///< ln(η·Δx·Δy·Δθ) ≈ ln ∫ p(z|m,x)^(1/gain) p(x|x_{t-1},u) dx
  int evaluations = 0;             ///< likelihood evaluations (scan matching + proposal)
};

/// Plans the proposal for a particle at `prev` with odometry increment `u` (in the frame of `prev`). The mode
/// search starts at `start` when given (proposal_start_spread > 0), else at the prediction prev ⊕ u.
ProposalPlan planProposal(const GridMap& map, const Pose2& prev, const Pose2& u, bool has_odometry,
                          const PreparedScan& scan, const SlamOptions& o, const OdometryMotionModel& motion,
                          const Pose2* start = nullptr);

/// Draws the particle's new pose from the plan with the particle's own random stream; returns the weight
/// increment (ln η for the informed proposal, ln p(z|m,x)/gain for mode-only and odometry).
double drawFromProposal(const ProposalPlan& plan, const GridMap& map, const Pose2& prev, const Pose2& u,
                        bool has_odometry, const PreparedScan& scan, const SlamOptions& o,
                        const OdometryMotionModel& motion, Rng& rng, Pose2& out_pose);

}  // namespace gridtopo::slam
