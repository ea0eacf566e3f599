// Map preparation (map_preparation.h): which free cells of a robot-built map are places. The fixture is a map built
// the way a SLAM map is (free along every beam, occupied at its hit) with a perfect trajectory, in a simulated
// building: a corridor with a window wall (the laser passes, the robot does not) onto a yard, open doors onto rooms
// the robot enters or only looks into, and a wall with a narrow slot that lets a fan of rays into a closed store.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "gridtopo/sim/simulator.h"
#include "gridtopo/topology/map_preparation.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;
using namespace gridtopo::topology;

namespace {

constexpr double kRes = 0.05;
constexpr int kCols = 800, kRows = 800;  // 40 m x 40 m, world (0, 0) at the lower-left corner

cv::Point cell(double x, double y) {
  return {static_cast<int>(std::floor(x / kRes)), kRows - 1 - static_cast<int>(std::floor(y / kRes))};
}

// The building (metres). Corridor y in [10, 12], x in [2, 30]. South of it, behind a window wall (y = 10, the
// laser's walls do not hold it), a yard closed by a far wall at y = 0. North, rooms with doors of 1 m in the
// corridor's wall y = 12: room A (x 4..10) the robot enters, room B (x 12..18) it only looks into from the door,
// and the store (x 20..28) behind a 0.1 m slot.
sim::FloorPlan laserWorld() {
  sim::FloorPlan p;
  auto wall = [&](double x0, double y0, double x1, double y1) { p.walls.push_back({x0, y0, x1, y1}); };
  wall(2, 0, 30, 0);      // the yard's far wall
  wall(2, 0, 2, 18);      // west
  wall(30, 0, 30, 18);    // east
  wall(2, 18, 30, 18);    // north
  // The corridor's north wall with the doors (gaps): A at x 6..7, B at x 14..15, the slot at x 23.95..24.05.
  wall(2, 12, 6, 12);
  wall(7, 12, 14, 12);
  wall(15, 12, 23.95, 12);
  wall(24.05, 12, 30, 12);
  wall(10, 12, 10, 18);  // room walls
  wall(12, 12, 12, 18);
  wall(18, 12, 18, 18);
  wall(20, 12, 20, 18);
  wall(28, 12, 28, 18);
  return p;
}

struct Fixture {
  places::OccupancyImage occ;
  std::vector<cv::Point2d> path;  // cells
};

// Ray-casts 360 beams every 0.25 m of the path (30 m range) into a grid: free along a beam, occupied at its hit;
// a hit cell stays occupied.
Fixture buildMap() {
  const sim::FloorPlan world = laserWorld();
  std::vector<cv::Point2d> poses;
  auto drive = [&](cv::Point2d a, cv::Point2d b) {
    const int n = static_cast<int>(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / 0.25));
    for (int i = 0; i <= n; ++i) poses.emplace_back(a.x + (b.x - a.x) * i / n, a.y + (b.y - a.y) * i / n);
  };
  drive({3, 11}, {6.5, 11});
  drive({6.5, 11}, {6.5, 15});   // into room A
  drive({6.5, 15}, {6.5, 11});
  drive({6.5, 11}, {29, 11});    // along the corridor, past B's door and the slot
  cv::Mat hits(kRows, kCols, CV_8U, cv::Scalar(0)), seen(kRows, kCols, CV_8U, cv::Scalar(0));
  for (const cv::Point2d& p : poses)
    for (int k = 0; k < 720; ++k) {
      const double a = k * M_PI / 360.0;
      const double r = world.rayCast(p.x, p.y, a);
      const double len = std::min(r, 30.0);
      for (double t = 0; t < len; t += 0.5 * kRes) {
        const cv::Point c = cell(p.x + t * std::cos(a), p.y + t * std::sin(a));
        if (c.x >= 0 && c.y >= 0 && c.x < kCols && c.y < kRows) seen.at<unsigned char>(c) = 255;
      }
      if (r <= 30.0) {
        const cv::Point c = cell(p.x + r * std::cos(a), p.y + r * std::sin(a));
        if (c.x >= 0 && c.y >= 0 && c.x < kCols && c.y < kRows) hits.at<unsigned char>(c) = 255;
      }
    }
  Fixture f;
  f.occ.resolution = kRes;
  f.occ.cells = cv::Mat(kRows, kCols, CV_8U, cv::Scalar(places::kUnknown));
  f.occ.cells.setTo(places::kFree, seen);
  f.occ.cells.setTo(places::kOccupied, hits);
  for (const cv::Point2d& p : poses) f.path.emplace_back(p.x / kRes, kRows - p.y / kRes);
  return f;
}

bool isPlace(const PreparedMap& m, double x, double y) { return m.places.at<unsigned char>(cell(x, y)) != 0; }
bool isSeen(const PreparedMap& m, double x, double y) { return m.seen_not_place.at<unsigned char>(cell(x, y)) != 0; }

}  // namespace

TEST(MapPreparation, FarFansAndIslandsAreSeenButNoPlacesRoomsAndTheCorridorArePlaces) {
  const Fixture f = buildMap();
  const PreparedMap m = prepareMap(f.occ, MapPreparationOptions{}, f.path);
  // The corridor, the room the robot entered, and the room it only looked into through the door (2 m in).
  EXPECT_TRUE(isPlace(m, 16, 11));
  EXPECT_TRUE(isPlace(m, 8, 16));
  EXPECT_TRUE(isPlace(m, 14.5, 14));
  // The yard near the window is seen well from near (a room behind glass looks the same): a place.
  EXPECT_TRUE(isPlace(m, 16, 6));
  // The yard's far part (more than 8 m from every pose) is seen, but no place.
  EXPECT_TRUE(isSeen(m, 16, 1));
  EXPECT_TRUE(isSeen(m, 5, 1.5));
  // The fan through the 0.1 m slot into the store: free in the map, but no disc fits in its narrow part and its
  // wide part is cut off from the corridor: no place anywhere.
  int fan_free = 0, fan_places = 0;
  for (int y = cell(0, 17.9).y; y <= cell(0, 12.1).y; ++y)
    for (int x = cell(20.1, 0).x; x <= cell(27.9, 0).x; ++x) {
      fan_free += f.occ.cells.at<unsigned char>(y, x) == places::kFree;
      fan_places += m.places.at<unsigned char>(y, x) != 0;
    }
  EXPECT_GT(fan_free, 200);
  EXPECT_EQ(fan_places, 0);
  // Every step took something, and the counts add up.
  EXPECT_GT(m.removed_robot_fit, 0u);
  EXPECT_GT(m.removed_far, 0u);
  EXPECT_GT(m.removed_unreachable, 0u);
  EXPECT_EQ(m.free_cells, m.place_cells + m.removed_robot_fit + m.removed_far + m.removed_unreachable);
  EXPECT_EQ(static_cast<std::size_t>(cv::countNonZero(m.seen_not_place)), m.free_cells - m.place_cells);
  // The visibility rays split over threads (the path's samples in parts): the same places.
  for (int threads : {2, 3}) {
    const PreparedMap t = prepareMap(f.occ, MapPreparationOptions{}, f.path, threads);
    EXPECT_EQ(cv::countNonZero(t.places != m.places), 0) << threads << " threads";
    EXPECT_EQ(t.removed_far, m.removed_far);
  }
}

TEST(MapPreparation, WithoutThePathOnlyGeometryDecidesAndOffKeepsEveryFreeCell) {
  const Fixture f = buildMap();
  const PreparedMap geometric = prepareMap(f.occ, MapPreparationOptions{});
  EXPECT_EQ(geometric.removed_far, 0u);
  EXPECT_TRUE(isPlace(geometric, 16, 11));
  EXPECT_TRUE(isPlace(geometric, 16, 1));  // nothing says the far yard was seen from afar
  MapPreparationOptions off;
  off.enabled = false;
  const PreparedMap all = prepareMap(f.occ, off, f.path);
  EXPECT_EQ(all.place_cells, all.free_cells);
  EXPECT_EQ(cv::countNonZero(all.seen_not_place), 0);
}

TEST(MapPreparation, TheTopologyLabelsPlacesOnlyAndDrawsTheRestApart) {
  const Fixture f = buildMap();
  MapImage map;
  map.grey = cv::Mat(kRows, kCols, CV_8U, cv::Scalar(128));
  map.grey.setTo(255, f.occ.cells == places::kFree);
  map.grey.setTo(0, f.occ.cells == places::kOccupied);
  map.resolution = kRes;
  map.origin = {0, 0};
  map.kind = MapKind::RosMap;
  for (const cv::Point2d& c : f.path) map.path.emplace_back(c.x * kRes, (kRows - c.y) * kRes);
  TopologyOptions o;
  PreparedMap p;
  const places::OccupancyImage occ = occupancyForTopology(map, o, &p);
  EXPECT_TRUE(occ.isFree(cell(16, 11).y, cell(16, 11).x));
  EXPECT_EQ(occ.cells.at<unsigned char>(cell(16, 1)), places::kSeen);
  EXPECT_GT(cv::countNonZero(occ.cells == places::kSeen), 0);
  // pathInCells is the inverse of the fixture's cell -> world conversion.
  const std::vector<cv::Point2d> back = pathInCells(map.path, map.origin, kRes, kRows);
  ASSERT_EQ(back.size(), f.path.size());
  EXPECT_NEAR(back[5].x, f.path[5].x, 1e-9);
  EXPECT_NEAR(back[5].y, f.path[5].y, 1e-9);
  // A plain image (a drawn plan) is all floor with the default places_prepare = maps.
  map.kind = MapKind::PlainImage;
  map.grey.setTo(255, f.occ.cells == places::kFree);
  const places::OccupancyImage plan = occupancyForTopology(map, o);
  EXPECT_EQ(cv::countNonZero(plan.cells == places::kSeen), 0);
}
