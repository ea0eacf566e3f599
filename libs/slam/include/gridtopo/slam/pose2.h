#pragma once
// Planar poses and the two operations the filter needs: composition (a ⊕ b) and the relative pose (a ⊖ b).
#include <cmath>

namespace gridtopo::slam {

struct Pose2 {
  double x = 0.0, y = 0.0, theta = 0.0;
};

/// Angle wrapped to (-pi, pi].
inline double wrapAngle(double a) {
  constexpr double kPi = 3.14159265358979323846;
  if (a > -kPi && a <= kPi) return a;
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a <= 0.0) a += 2.0 * kPi;
  return a - kPi;
}

/// a ⊕ b: the pose b, given in the frame of a, expressed in a's parent frame.
inline Pose2 compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, wrapAngle(a.theta + b.theta)};
}

/// b ⊖ a: the pose b expressed in the frame of a (so that compose(a, relative(a, b)) == b).
inline Pose2 relative(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, wrapAngle(b.theta - a.theta)};
}

}  // namespace gridtopo::slam
