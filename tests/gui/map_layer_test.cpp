// MapLayer geometry (cell <-> world, row 0 = top) and its conversions from an MRPT grid, from the SLAM particle
// map, tiled, and back to an MRPT grid. No display needed.
#include <gtest/gtest.h>

#include <cmath>

#include "gridtopo/io/map_io.h"
#include "gridtopo/session/map_layer.h"

using namespace gridtopo;
using session::MapLayer;

namespace {
/// 3 rows x 4 cols at 0.5 m, lower-left corner at (-1, 2): covers x in [-1, 1), y in [2, 3.5).
MapLayer smallLayer() {
  MapLayer m;
  m.grey = (cv::Mat_<unsigned char>(3, 4) << 0, 51, 128, 255,  //
            10, 20, 30, 40,                                     //
            200, 210, 220, 230);
  m.resolution = 0.5;
  m.origin_x = -1.0;
  m.origin_y = 2.0;
  m.source = "small";
  return m;
}
}  // namespace

TEST(MapLayer, SizesAndOccupancy) {
  const MapLayer m = smallLayer();
  EXPECT_FALSE(m.empty());
  EXPECT_EQ(m.rows(), 3);
  EXPECT_EQ(m.cols(), 4);
  EXPECT_DOUBLE_EQ(m.width_m(), 2.0);
  EXPECT_DOUBLE_EQ(m.height_m(), 1.5);
  EXPECT_DOUBLE_EQ(m.occupancy(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(m.occupancy(0, 1), 0.8);
  EXPECT_DOUBLE_EQ(m.occupancy(0, 3), 0.0);
  EXPECT_TRUE(MapLayer{}.empty());
  EXPECT_EQ(MapLayer{}.kind, MapKind::PlainImage);
}

TEST(MapLayer, CellCentresAndWorldToCellAgreeWithRowZeroAtTheTop) {
  const MapLayer m = smallLayer();
  const cv::Point2d tl = m.cellCentre(0, 0), br = m.cellCentre(2, 3);
  EXPECT_DOUBLE_EQ(tl.x, -0.75);
  EXPECT_DOUBLE_EQ(tl.y, 3.25);  // row 0 = largest y
  EXPECT_DOUBLE_EQ(br.x, 0.75);
  EXPECT_DOUBLE_EQ(br.y, 2.25);
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) {
      const cv::Point2d p = m.cellCentre(r, c);
      int rr = -1, cc = -1;
      ASSERT_TRUE(m.worldToCell(p.x, p.y, rr, cc));
      EXPECT_EQ(rr, r);
      EXPECT_EQ(cc, c);
    }
  int r = -7, c = -7;
  // Edges: the lower-left corner is inside, the right and top edges are outside.
  ASSERT_TRUE(m.worldToCell(-1.0, 2.0, r, c));
  EXPECT_EQ(r, 2);
  EXPECT_EQ(c, 0);
  ASSERT_TRUE(m.worldToCell(0.999, 3.499, r, c));
  EXPECT_EQ(r, 0);
  EXPECT_EQ(c, 3);
  r = c = -7;
  EXPECT_FALSE(m.worldToCell(1.0, 2.5, r, c));
  EXPECT_FALSE(m.worldToCell(0.0, 3.5, r, c));
  EXPECT_FALSE(m.worldToCell(-1.001, 2.5, r, c));
  EXPECT_FALSE(m.worldToCell(0.0, 1.999, r, c));
  EXPECT_EQ(r, -7);  // untouched when outside
  EXPECT_EQ(c, -7);
  EXPECT_FALSE(MapLayer{}.worldToCell(0.0, 0.0, r, c));
}

TEST(MapLayer, FromGridIsTheGridImageWithTheGridGeometry) {
  mrpt::maps::COccupancyGridMap2D g(-1.0f, 1.0f, 2.0f, 3.5f, 0.5f);
  ASSERT_EQ(g.getSizeX(), 4u);
  ASSERT_EQ(g.getSizeY(), 3u);
  g.setCell(0, 0, 0.0f);  // bottom-left cell occupied
  g.setCell(3, 2, 1.0f);  // top-right cell free
  const MapLayer m = session::mapLayerFromGrid(g, "a.gridmap", MapKind::ProbabilisticGrid);
  EXPECT_EQ(m.source, "a.gridmap");
  EXPECT_EQ(m.kind, MapKind::ProbabilisticGrid);
  EXPECT_DOUBLE_EQ(m.resolution, 0.5);
  EXPECT_DOUBLE_EQ(m.origin_x, -1.0);
  EXPECT_DOUBLE_EQ(m.origin_y, 2.0);
  ASSERT_EQ(m.rows(), 3);
  ASSERT_EQ(m.cols(), 4);
  EXPECT_EQ(cv::countNonZero(m.grey != io::gridToImage(g)), 0);
  EXPECT_LT(m.grey.at<unsigned char>(2, 0), 5);    // occupied, at the image's bottom-left
  EXPECT_GT(m.grey.at<unsigned char>(0, 3), 250);  // free, at the image's top-right
  EXPECT_EQ(m.grey.at<unsigned char>(1, 1), 128);  // unknown
  // The world point of the occupied cell maps back onto it.
  int r, c;
  ASSERT_TRUE(m.worldToCell(-0.75, 2.25, r, c));
  EXPECT_EQ(r, 2);
  EXPECT_EQ(c, 0);
}

TEST(MapLayer, FromSlamCoversTheAllocatedTilesWithUnknownElsewhere) {
  slam::GridMap g(0.05);
  g.mutableLogOdds(-3, 5) = 2.0f;    // tile (-1, 0)
  g.mutableLogOdds(20, -1) = -1.0f;  // tile (1, -1)
  g.mutableLogOdds(21, -1) = 20.0f;  // beyond the table: clamped (p_free ~ 0)
  g.mutableLogOdds(22, -1) = -20.0f; // p_free ~ 1
  const MapLayer m = session::mapLayerFromSlam(g);
  EXPECT_EQ(m.kind, MapKind::ProbabilisticGrid);
  EXPECT_EQ(m.source, "<slam>");
  EXPECT_DOUBLE_EQ(m.resolution, 0.05);
  // Tiles of 16 cells: x in [-16, 32), y in [-16, 16).
  ASSERT_EQ(m.cols(), 48);
  ASSERT_EQ(m.rows(), 32);
  EXPECT_DOUBLE_EQ(m.origin_x, -16 * 0.05);
  EXPECT_DOUBLE_EQ(m.origin_y, -16 * 0.05);
  // Cell (cx, cy) is at row 15 - cy, col cx + 16; value round(255 / (1 + e^l)).
  EXPECT_EQ(m.grey.at<unsigned char>(10, 13), 30);   // l = 2
  EXPECT_EQ(m.grey.at<unsigned char>(16, 36), 186);  // l = -1
  EXPECT_EQ(m.grey.at<unsigned char>(16, 37), 0);
  EXPECT_EQ(m.grey.at<unsigned char>(16, 38), 255);
  EXPECT_EQ(m.grey.at<unsigned char>(11, 13), 128);  // allocated, never written
  EXPECT_EQ(m.grey.at<unsigned char>(0, 20), 128);   // tile (0, 0) not allocated
  EXPECT_EQ(cv::countNonZero(m.grey != 128), 4);
  // The layer's cell centre is the SLAM cell centre.
  const cv::Point2d p = m.cellCentre(10, 13);
  EXPECT_NEAR(p.x, g.cellCenter(-3), 1e-12);
  EXPECT_NEAR(p.y, g.cellCenter(5), 1e-12);
  int r, c;
  ASSERT_TRUE(m.worldToCell(g.cellCenter(20), g.cellCenter(-1), r, c));
  EXPECT_EQ(r, 16);
  EXPECT_EQ(c, 36);

  const MapLayer e = session::mapLayerFromSlam(slam::GridMap(0.1));
  EXPECT_TRUE(e.empty());
  EXPECT_DOUBLE_EQ(e.resolution, 0.1);
  EXPECT_EQ(e.kind, MapKind::ProbabilisticGrid);
}

TEST(MapLayer, TiledRepeatsTheSourceAndKeepsItsGeometry) {
  MapLayer src = smallLayer();
  src.kind = MapKind::RosMap;
  const MapLayer t = session::tiledMap(src, 9, 7);
  ASSERT_EQ(t.cols(), 9);
  ASSERT_EQ(t.rows(), 7);
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 9; ++c) ASSERT_EQ(t.grey.at<unsigned char>(r, c), src.grey.at<unsigned char>(r % 3, c % 4));
  EXPECT_EQ(t.source, "small (tiled 9x7)");
  EXPECT_DOUBLE_EQ(t.resolution, 0.5);
  EXPECT_DOUBLE_EQ(t.origin_x, -1.0);
  EXPECT_DOUBLE_EQ(t.origin_y, 2.0);
  EXPECT_EQ(t.kind, MapKind::RosMap);
  EXPECT_EQ(src.grey.at<unsigned char>(0, 0), 0);  // the source is not written through
  const MapLayer smaller = session::tiledMap(src, 2, 1);
  EXPECT_EQ(smaller.grey.at<unsigned char>(0, 1), 51);
  EXPECT_EQ(smaller.cols(), 2);
}

TEST(MapLayer, GridFromLayerKeepsGeometryOrientationAndValues) {
  const MapLayer m = smallLayer();
  const auto g = session::gridFromLayer(m);
  ASSERT_EQ(g.getSizeX(), 4u);
  ASSERT_EQ(g.getSizeY(), 3u);
  EXPECT_FLOAT_EQ(g.getResolution(), 0.5f);
  EXPECT_FLOAT_EQ(g.getXMin(), -1.0f);
  EXPECT_FLOAT_EQ(g.getYMin(), 2.0f);
  // Image row 0 is the grid's top row (y index 2); p_free = grey / 255 up to MRPT's cell quantisation.
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(g.getCell(c, 2 - r), m.grey.at<unsigned char>(r, c) / 255.0, 0.01) << r << "," << c;
  // And back: the same image within two grey levels (MRPT's 8-bit log-odds cells), free / occupied / unknown exact.
  const MapLayer back = session::mapLayerFromGrid(g, "x", MapKind::PlainImage);
  ASSERT_EQ(back.grey.size(), m.grey.size());
  cv::Mat diff;
  cv::absdiff(back.grey, m.grey, diff);
  double mx = 0;
  cv::minMaxLoc(diff, nullptr, &mx);
  EXPECT_LE(mx, 2) << back.grey;
  EXPECT_EQ(back.grey.at<unsigned char>(0, 0), 0);
  EXPECT_EQ(back.grey.at<unsigned char>(0, 2), 128);
  EXPECT_EQ(back.grey.at<unsigned char>(0, 3), 255);
  EXPECT_DOUBLE_EQ(back.origin_x, -1.0);
  EXPECT_DOUBLE_EQ(back.origin_y, 2.0);
}
