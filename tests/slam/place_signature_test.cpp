// The place signature (place_signature.h, Scan Context after Kim & Kim 2018): a turned copy of a place is found at
// distance ~0 with its heading, a different place is far, and the ring key does not change with the heading.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gridtopo/slam/place_signature.h"
#include "gridtopo/slam/pose2.h"

using namespace gridtopo;

namespace {

// An L-shaped corridor corner with a few door recesses, as points every 5 cm.
std::vector<slam::Point2> cornerPlace() {
  std::vector<slam::Point2> pts;
  for (double x = -12; x <= 3; x += 0.05) {
    pts.push_back({x, -1.25});
    if (x < -1.25) pts.push_back({x, 1.25});
  }
  for (double y = 1.25; y <= 12; y += 0.05) {
    pts.push_back({-1.25, y});
    pts.push_back({1.25 + (y > 5 && y < 6 ? 0.5 : 0.0), y});
  }
  for (double x = -9; x <= -8; x += 0.05) pts.push_back({x, 1.75});
  return pts;
}

std::vector<slam::Point2> turned(const std::vector<slam::Point2>& pts, double yaw) {
  std::vector<slam::Point2> out;
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (const auto& p : pts) out.push_back({c * p.x - s * p.y, s * p.x + c * p.y});
  return out;
}

}  // namespace

TEST(PlaceSignature, ATurnedCopyIsNearWithItsHeadingAndADifferentPlaceIsFar) {
  const slam::PlaceSignatureShape shape;
  const std::vector<slam::Point2> place = cornerPlace();
  const slam::PlaceSignature a(place, shape);
  ASSERT_FALSE(a.empty());
  // The same place seen from a frame turned by 70 degrees (14 sectors of 5).
  const double yaw = 70.0 * M_PI / 180.0;
  const slam::PlaceSignature b(turned(place, -yaw), shape);  // b's points are a's seen from a frame turned by +yaw
  double found = 0.0;
  const double d = a.distance(b, &found);
  EXPECT_LT(d, 0.15);  // not 0: the voxels and the bins of the turned points differ
  EXPECT_NEAR(slam::wrapAngle(found - yaw), 0.0, 2.0 * M_PI / shape.sectors);
  EXPECT_NEAR(a.ringKeyDistance(b), 0.0, 0.03);
  // A straight corridor is another place.
  std::vector<slam::Point2> corridor;
  for (double x = -14; x <= 14; x += 0.05) {
    corridor.push_back({x, -1.25});
    corridor.push_back({x, 1.25});
  }
  const slam::PlaceSignature c(corridor, shape);
  EXPECT_GT(a.distance(c), d + 0.2);
  // Turned by a fraction of a sector the points change bins, and the distance grows, but the heading is found to
  // within a sector.
  const double odd = 1.2;
  double odd_found = 0.0;
  const double d_odd = a.distance(slam::PlaceSignature(turned(place, -odd), shape), &odd_found);
  EXPECT_LT(d_odd, 0.35);
  EXPECT_NEAR(slam::wrapAngle(odd_found - odd), 0.0, 2.0 * M_PI / shape.sectors);
  // The aligned (fast) distance agrees with the exhaustive one on the turned copy.
  double fast_yaw = 0.0;
  EXPECT_NEAR(a.alignedDistance(b, &fast_yaw), d, 0.05);
  // Nothing is near an empty signature.
  const slam::PlaceSignature empty(std::vector<slam::Point2>{}, shape);
  EXPECT_TRUE(empty.empty());
  EXPECT_DOUBLE_EQ(a.distance(empty), 1.0);
}
