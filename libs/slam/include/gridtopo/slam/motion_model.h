#pragma once
// Odometry motion model p(x_t | x_{t-1}, u_{t-1}) with the four classic noise terms (Thrun, Burgard, Fox,
// "Probabilistic Robotics", ch. 5; the same terms GMapping calls srr, srt, str, stt). The odometry increment
// u = (dx, dy, dθ) is expressed in the frame of x_{t-1}; the model perturbs it with independent Gaussian noise
//   σ_xy² = alpha_tt·d² + alpha_tr·dθ² + min_sigma_xy²      (on dx and dy; d = |(dx, dy)|)
//   σ_θ²  = alpha_rr·dθ² + alpha_rt·d² + min_sigma_theta²
// and x_t = x_{t-1} ⊕ (u + ε). Sampling and the density use the same model, so the informed proposal's
// τ_j = p(z|m,x_j)·p(x_j|x_{t-1},u) is consistent with the odometry proposal.
// We sample with our own code: MRPT 2.5.8's Thrun-model CActionRobotMovement2D returns one pose every time.
#include "gridtopo/slam/pose2.h"
#include "gridtopo/slam/random.h"

namespace gridtopo::slam {

struct MotionModelOptions {
  double alpha_rr = 0.1;   ///< rotation noise from rotation (rad²/rad²)
  double alpha_rt = 0.05;  ///< rotation noise from translation (rad²/m²)
  double alpha_tt = 0.05;  ///< translation noise from translation (m²/m²)
  double alpha_tr = 0.01;  ///< translation noise from rotation (m²/rad²)
  double min_sigma_xy = 0.01;      ///< m, added in quadrature (keeps the density proper when standing still)
  double min_sigma_theta = 0.005;  ///< rad
  /// Motion prior for scans without odometry: zero motion with these standard deviations.
  double no_odometry_sigma_xy = 0.3;     ///< m
  double no_odometry_sigma_theta = 0.3;  ///< rad
  /// Odometry calibration in the particle state: each particle scales the translation of every odometry
  /// increment by its own factor s (u = (s·dx, s·dy, dθ)), drawn once at the start as 1 + N(0, scale_sigma²) and
  /// then walking by N(0, scale_walk_sigma²·d) per processed step (d = |(dx, dy)| in m). A systematic scale error
  /// of the odometry then spreads the particles along a corridor in proportion to its length while each step
  /// stays as precise as the noise terms above; resampling keeps the particles whose scale agrees with the scans
  /// wherever they can observe it. 0 = off (s = 1).
  double scale_sigma = 0.0;
  double scale_walk_sigma = 0.0;  ///< 1/sqrt(m)
};

class OdometryMotionModel {
 public:
  explicit OdometryMotionModel(MotionModelOptions options = {}) : o_(options) {}

  struct Sigmas {
    double xy, theta;
  };
  /// Standard deviations of the noise on an increment (has_odometry = false: the no-odometry prior).
  Sigmas sigmas(const Pose2& u, bool has_odometry = true) const;
  /// Draws x_t ~ p(x_t | prev, u).
  Pose2 sample(const Pose2& prev, const Pose2& u, Rng& rng, bool has_odometry = true) const;
  /// The squared Mahalanobis distance of the motion `d` (in the previous pose's frame) from the increment u, in
  /// the deviations sigmas(u): the exponent of p(x | prev, u) times -2, for d = prev⁻¹ ⊕ x.
  double squaredDeviations(const Pose2& d, const Pose2& u, bool has_odometry = true) const;
  /// ln p(x | prev, u) (full Gaussian normalisation).
  double logDensity(const Pose2& x, const Pose2& prev, const Pose2& u, bool has_odometry = true) const;
  const MotionModelOptions& options() const { return o_; }

 private:
  MotionModelOptions o_;
};

}  // namespace gridtopo::slam
