#include <gtest/gtest.h>

#include <cmath>

#include "gridtopo/slam/motion_model.h"

using namespace gridtopo::slam;

namespace {
struct Moments {
  double mean[3] = {0, 0, 0}, var[3] = {0, 0, 0};
};
Moments sampleMoments(const OdometryMotionModel& m, const Pose2& prev, const Pose2& u, bool odo, int n) {
  Rng rng(42, 1, 2, 3);
  Moments r;
  std::vector<Pose2> d(n);
  for (int i = 0; i < n; ++i) {
    d[i] = relative(prev, m.sample(prev, u, rng, odo));
    r.mean[0] += d[i].x;
    r.mean[1] += d[i].y;
    r.mean[2] += d[i].theta;
  }
  for (double& v : r.mean) v /= n;
  for (int i = 0; i < n; ++i) {
    r.var[0] += (d[i].x - r.mean[0]) * (d[i].x - r.mean[0]);
    r.var[1] += (d[i].y - r.mean[1]) * (d[i].y - r.mean[1]);
    r.var[2] += (d[i].theta - r.mean[2]) * (d[i].theta - r.mean[2]);
  }
  for (double& v : r.var) v /= (n - 1);
  return r;
}
}  // namespace

TEST(MotionModel, SampleMeanAndVarianceMatchTheFourNoiseTerms) {
  MotionModelOptions o;
  o.alpha_rr = 0.2;
  o.alpha_rt = 0.04;
  o.alpha_tt = 0.09;
  o.alpha_tr = 0.02;
  o.min_sigma_xy = 0.001;
  o.min_sigma_theta = 0.001;
  const OdometryMotionModel m(o);
  const Pose2 prev{3.0, -2.0, 2.9};  // near +pi: the angle of the sample wraps
  const Pose2 u{0.4, 0.1, 0.5};
  const int n = 200000;
  const Moments mo = sampleMoments(m, prev, u, true, n);
  const double d2 = u.x * u.x + u.y * u.y, r2 = u.theta * u.theta;
  const double vxy = o.alpha_tt * d2 + o.alpha_tr * r2 + 1e-6;
  const double vth = o.alpha_rr * r2 + o.alpha_rt * d2 + 1e-6;
  // Means: within 4 standard errors; variances: within 2 % (relative standard error sqrt(2/n) = 0.3 %).
  EXPECT_NEAR(mo.mean[0], u.x, 4 * std::sqrt(vxy / n));
  EXPECT_NEAR(mo.mean[1], u.y, 4 * std::sqrt(vxy / n));
  EXPECT_NEAR(mo.mean[2], u.theta, 4 * std::sqrt(vth / n));
  EXPECT_NEAR(mo.var[0] / vxy, 1.0, 0.02);
  EXPECT_NEAR(mo.var[1] / vxy, 1.0, 0.02);
  EXPECT_NEAR(mo.var[2] / vth, 1.0, 0.02);
  // Each term contributes: rotation-from-translation alone.
  MotionModelOptions only_rt = o;
  only_rt.alpha_rr = only_rt.alpha_tt = only_rt.alpha_tr = 0;
  const Moments m2 = sampleMoments(OdometryMotionModel(only_rt), prev, {1.0, 0, 0}, true, 50000);
  EXPECT_NEAR(m2.var[2], 0.04 + 1e-6, 0.002);
  EXPECT_NEAR(m2.var[0], 1e-6, 1e-7);
  // Translation from rotation alone (turning on the spot).
  MotionModelOptions only_tr = o;
  only_tr.alpha_rr = only_tr.alpha_tt = only_tr.alpha_rt = 0;
  const Moments m3 = sampleMoments(OdometryMotionModel(only_tr), prev, {0, 0, 1.0}, true, 50000);
  EXPECT_NEAR(m3.var[0], 0.02 + 1e-6, 0.001);
  EXPECT_NEAR(m3.var[2], 1e-6, 1e-7);
}

TEST(MotionModel, SamplesDifferFromEachOther) {
  // The MRPT 2.5.8 Thrun-model sampler returns one pose every time; ours must not.
  const OdometryMotionModel m;
  Rng rng(1);
  const Pose2 a = m.sample({}, {1, 0, 0}, rng), b = m.sample({}, {1, 0, 0}, rng);
  EXPECT_NE(a.x, b.x);
  EXPECT_NE(a.theta, b.theta);
}

TEST(MotionModel, DensityIsANormalisedGaussian) {
  const OdometryMotionModel m;
  const Pose2 prev{1, 2, 0.3}, u{0.3, 0.0, 0.2};
  const auto s = m.sigmas(u);
  const Pose2 mode = compose(prev, u);
  const double expected = -std::log(std::pow(2 * M_PI, 1.5) * s.xy * s.xy * s.theta);
  EXPECT_NEAR(m.logDensity(mode, prev, u), expected, 1e-9);
  // One sigma off in x (in prev's frame) costs exactly 1/2.
  const Pose2 off = compose(prev, {u.x + s.xy, u.y, u.theta});
  EXPECT_NEAR(m.logDensity(off, prev, u), expected - 0.5, 1e-9);
  // Numerical integral over a grid in (dx, dy, dθ) is 1.
  double sum = 0;
  const int n = 40;
  const double hx = 10 * s.xy / n, ht = 10 * s.theta / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Pose2 d{u.x + (i - n / 2 + 0.5) * hx, u.y + (j - n / 2 + 0.5) * hx, u.theta + (k - n / 2 + 0.5) * ht};
        sum += std::exp(m.logDensity(compose(prev, d), prev, u)) * hx * hx * ht;
      }
  EXPECT_NEAR(sum, 1.0, 1e-3);
}

TEST(MotionModel, NoOdometryUsesTheWidePrior) {
  MotionModelOptions o;
  o.no_odometry_sigma_xy = 0.5;
  o.no_odometry_sigma_theta = 0.25;
  const OdometryMotionModel m(o);
  const Moments mo = sampleMoments(m, {0, 0, 0}, {}, false, 50000);
  EXPECT_NEAR(std::sqrt(mo.var[0]), 0.5, 0.01);
  EXPECT_NEAR(std::sqrt(mo.var[2]), 0.25, 0.005);
}
