#include <gtest/gtest.h>

#include "gridtopo/slam/grid_map.h"

using namespace gridtopo::slam;

TEST(GridMap, BeamMarksFreeCellsAndTheHit) {
  GridMap m(0.1);
  MapUpdateOptions o;
  m.insertScan({0.05, 0.05, 0}, {0, 0, 0}, {{1.0, 0.0, true}}, o);  // from cell (0,0) to cell (10,0)
  for (int x = 0; x < 10; ++x) EXPECT_FLOAT_EQ(m.cell(x, 0)->log_odds, o.log_odds_free) << x;
  const auto hit = m.cell(10, 0);
  ASSERT_TRUE(hit);
  EXPECT_FLOAT_EQ(hit->log_odds, o.log_odds_hit);
  EXPECT_EQ(hit->hits, 1u);
  EXPECT_FLOAT_EQ(hit->hit_x, 1.05f);
  EXPECT_EQ(m.cell(11, 0) ? m.cell(11, 0)->log_odds : 0.0f, 0.0f);  // nothing beyond the hit
  EXPECT_FALSE(m.cell(500, 500));
  // A free-only beam (no return) clears its last cell too and records no hit.
  m.insertScan({0.05, 0.05, 0}, {0, 0, 0}, {{0.0, 1.0, false}}, o);
  EXPECT_FLOAT_EQ(m.cell(0, 10)->log_odds, o.log_odds_free);
  EXPECT_EQ(m.cell(0, 10)->hits, 0u);
}

TEST(GridMap, LogOddsAreClamped) {
  GridMap m(0.1);
  MapUpdateOptions o;
  for (int i = 0; i < 100; ++i) m.insertScan({0.05, 0.05, 0}, {}, {{0.5, 0, true}}, o);
  EXPECT_FLOAT_EQ(m.cell(5, 0)->log_odds, o.log_odds_max);
  EXPECT_FLOAT_EQ(m.cell(2, 0)->log_odds, o.log_odds_min);
}

TEST(GridMap, GrowsInEveryDirection) {
  GridMap m(0.05);
  MapUpdateOptions o;
  std::vector<MapBeam> beams = {{30, 0, true}, {-30, 0, true}, {0, 25, true}, {0, -25, true}};
  m.insertScan({-100.0, 200.0, 0}, {}, beams, o);
  EXPECT_GT(m.cell(m.cellIndex(-70.0), m.cellIndex(200.0))->log_odds, 0);
  EXPECT_GT(m.cell(m.cellIndex(-130.0), m.cellIndex(200.0))->log_odds, 0);
  EXPECT_GT(m.cell(m.cellIndex(-100.0), m.cellIndex(225.0))->log_odds, 0);
  EXPECT_GT(m.cell(m.cellIndex(-100.0), m.cellIndex(175.0))->log_odds, 0);
  EXPECT_LT(m.cell(m.cellIndex(-110.0), m.cellIndex(200.02))->log_odds, 0);
}

TEST(GridMap, CopiesShareTilesUntilWritten) {
  GridMap a(0.05);
  MapUpdateOptions o;
  std::vector<MapBeam> beams;
  for (int k = 0; k < 180; ++k) beams.push_back({5 * std::cos(k * 0.035), 5 * std::sin(k * 0.035), true});
  a.insertScan({0, 0, 0}, {}, beams, o);
  const std::size_t tiles = a.tileCount();
  ASSERT_GT(tiles, 20u);
  GridMap b = a;  // a particle copy at resampling
  std::size_t shared = 0;
  for (std::size_t i = 0; i < a.tiles().size(); ++i)
    if (a.tiles()[i]) shared += a.tiles()[i].get() == b.tiles()[i].get();
  EXPECT_EQ(shared, tiles);  // nothing copied
  // Writing one cell of b copies exactly one tile; a is unchanged.
  const float before = a.cell(10, 10)->log_odds;
  b.mutableLogOdds(10, 10) = 3.0f;
  EXPECT_FLOAT_EQ(a.cell(10, 10)->log_odds, before);
  EXPECT_FLOAT_EQ(b.cell(10, 10)->log_odds, 3.0f);
  shared = 0;
  for (std::size_t i = 0; i < a.tiles().size(); ++i)
    if (a.tiles()[i]) shared += a.tiles()[i].get() == b.tiles()[i].get();
  EXPECT_EQ(shared, tiles - 1);
  // A second write to the same tile does not copy again.
  const auto* tile = b.tiles()[0].get();
  (void)tile;
  b.mutableLogOdds(11, 10) = 2.0f;
  shared = 0;
  for (std::size_t i = 0; i < a.tiles().size(); ++i)
    if (a.tiles()[i]) shared += a.tiles()[i].get() == b.tiles()[i].get();
  EXPECT_EQ(shared, tiles - 1);
}

TEST(GridMap, TileCopiesShareHitMeansUntilHit) {
  GridMap a(0.05);
  MapUpdateOptions o;
  a.insertScan({0, 0, 0}, {}, {{1.0, 0.0, true}}, o);  // hit in cell (20, 0)
  const GridMap::Tile* ta = a.tileAt(20, 0);
  ASSERT_TRUE(ta && ta->hits);
  const HitMean before = *ta->hit(GridMap::cellOffset(20, 0));
  GridMap b = a;
  // A beam that only crosses the tile (free space) copies its log-odds; the hit means stay shared.
  b.insertScan({0, 0.01, 0}, {}, {{1.2, 0.0, false}}, o);
  const GridMap::Tile* tb = b.tileAt(20, 0);
  ASSERT_NE(ta, tb);
  EXPECT_EQ(ta->hits.get(), tb->hits.get());
  EXPECT_EQ(ta->log_odds[GridMap::cellOffset(20, 0)], o.log_odds_hit);
  EXPECT_LT(tb->log_odds[GridMap::cellOffset(20, 0)], o.log_odds_hit);
  // A hit in b's tile copies the hit means first; a keeps its own.
  b.insertScan({0, 0, 0}, {}, {{1.01, 0.01, true}}, o);
  EXPECT_NE(a.tileAt(20, 0)->hits.get(), b.tileAt(20, 0)->hits.get());
  const HitMean* ha = a.tileAt(20, 0)->hit(GridMap::cellOffset(20, 0));
  EXPECT_EQ(ha->n, 1u);
  EXPECT_EQ(ha->x, before.x);
  EXPECT_EQ(ha->y, before.y);
  EXPECT_EQ(b.cell(20, 0)->hits, 2u);
  // The hits of a tile nobody else holds are written in place.
  const GridMap::HitMeans* own = b.tileAt(20, 0)->hits.get();
  b.insertScan({0, 0, 0}, {}, {{1.02, 0.0, true}}, o);
  EXPECT_EQ(b.tileAt(20, 0)->hits.get(), own);
  EXPECT_EQ(b.cell(20, 0)->hits, 3u);
}
