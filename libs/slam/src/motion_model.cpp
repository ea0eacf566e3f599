#include "gridtopo/slam/motion_model.h"

#include <cmath>

namespace gridtopo::slam {

OdometryMotionModel::Sigmas OdometryMotionModel::sigmas(const Pose2& u, bool has_odometry) const {
  if (!has_odometry) return {o_.no_odometry_sigma_xy, o_.no_odometry_sigma_theta};
  const double d2 = u.x * u.x + u.y * u.y;
  const double r2 = u.theta * u.theta;
  return {std::sqrt(o_.alpha_tt * d2 + o_.alpha_tr * r2 + o_.min_sigma_xy * o_.min_sigma_xy),
          std::sqrt(o_.alpha_rr * r2 + o_.alpha_rt * d2 + o_.min_sigma_theta * o_.min_sigma_theta)};
}

Pose2 OdometryMotionModel::sample(const Pose2& prev, const Pose2& u, Rng& rng, bool has_odometry) const {
  const Sigmas s = sigmas(u, has_odometry);
  const Pose2 noisy{u.x + rng.gaussian(s.xy), u.y + rng.gaussian(s.xy), u.theta + rng.gaussian(s.theta)};
  return compose(prev, noisy);
}

double OdometryMotionModel::squaredDeviations(const Pose2& d, const Pose2& u, bool has_odometry) const {
  const Sigmas s = sigmas(u, has_odometry);
  const double ex = d.x - u.x, ey = d.y - u.y, et = wrapAngle(d.theta - u.theta);
  return (ex * ex + ey * ey) / (s.xy * s.xy) + et * et / (s.theta * s.theta);
}

double OdometryMotionModel::logDensity(const Pose2& x, const Pose2& prev, const Pose2& u,
                                       bool has_odometry) const {
  const Sigmas s = sigmas(u, has_odometry);
  constexpr double kLog2Pi = 1.8378770664093453;
  return -0.5 * squaredDeviations(relative(prev, x), u, has_odometry) - 2.0 * std::log(s.xy) - std::log(s.theta) -
         1.5 * kLog2Pi;
}

}  // namespace gridtopo::slam
