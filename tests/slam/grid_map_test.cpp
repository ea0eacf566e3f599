#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iterator>

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

namespace {
/// Tiles of a held by b at the same place.
std::size_t sharedTiles(const GridMap& a, const GridMap& b) {
  std::size_t n = 0;
  a.forEachTile([&](int tx, int ty, const GridMap::Tile& t) {
    n += b.tileAt(tx * GridMap::kTileSize, ty * GridMap::kTileSize) == &t;
  });
  return n;
}
std::size_t sharedBlocks(const GridMap& a, const GridMap& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.blocks().size(); ++i)
    if (a.blocks()[i]) n += a.blocks()[i].get() == b.blocks()[i].get();
  return n;
}
std::size_t blockCount(const GridMap& a) {
  std::size_t n = 0;
  for (const auto& b : a.blocks()) n += static_cast<bool>(b);
  return n;
}
}  // namespace

TEST(GridMap, CopiesShareTilesUntilWritten) {
  GridMap a(0.05);
  MapUpdateOptions o;
  std::vector<MapBeam> beams;
  for (int k = 0; k < 180; ++k) beams.push_back({5 * std::cos(k * 0.035), 5 * std::sin(k * 0.035), true});
  a.insertScan({0, 0, 0}, {}, beams, o);
  const std::size_t tiles = a.tileCount(), blocks = blockCount(a);
  ASSERT_GT(tiles, 20u);
  ASSERT_GT(blocks, 1u);
  GridMap b = a;  // a particle copy at resampling
  EXPECT_EQ(sharedTiles(a, b), tiles);  // nothing copied
  EXPECT_EQ(sharedBlocks(a, b), blocks);
  // Writing one cell of b copies exactly one tile and its block (8 x 8 tiles); a is unchanged.
  const float before = a.cell(10, 10)->log_odds;
  b.mutableLogOdds(10, 10) = 3.0f;
  EXPECT_FLOAT_EQ(a.cell(10, 10)->log_odds, before);
  EXPECT_FLOAT_EQ(b.cell(10, 10)->log_odds, 3.0f);
  EXPECT_EQ(sharedTiles(a, b), tiles - 1);
  EXPECT_EQ(sharedBlocks(a, b), blocks - 1);
  // A second write to the same tile, or to another tile of the same block, copies only that other tile.
  b.mutableLogOdds(11, 10) = 2.0f;
  EXPECT_EQ(sharedTiles(a, b), tiles - 1);
  b.mutableLogOdds(10 + GridMap::kTileSize, 10) = 2.0f;
  EXPECT_EQ(sharedTiles(a, b), tiles - 2);
  EXPECT_EQ(sharedBlocks(a, b), blocks - 1);
  // Writing a's copy of the block now copies nothing that b still needs: b's cells keep their values.
  a.mutableLogOdds(10, 10) = -1.0f;
  EXPECT_FLOAT_EQ(b.cell(10, 10)->log_odds, 3.0f);
  EXPECT_FLOAT_EQ(a.cell(10, 10)->log_odds, -1.0f);
  // The tiles die with their last map.
  GridMap c = b;
  b = GridMap(0.05);
  EXPECT_FLOAT_EQ(c.cell(10, 10)->log_odds, 3.0f);
  EXPECT_EQ(sharedTiles(a, c), tiles - 2);
}

TEST(GridMap, AScanIntoASharedMapEqualsItsBeamsInsertedOneByOne) {
  // A copy of a map shares every tile until written, and a scan writes hundreds of tiles, most of them many times
  // (every beam starts in the sensor's tiles). Beams 12 m long in every direction into a copy must give what the
  // same beams give inserted one call each into another copy, and leave the original untouched.
  MapUpdateOptions o;
  GridMap base(0.05);
  std::vector<MapBeam> wall;
  for (int k = 0; k < 90; ++k) wall.push_back({11.0 * std::cos(k * 0.07), 11.0 * std::sin(k * 0.07), true});
  base.insertScan({0.3, -0.2, 0.1}, {}, wall, o);
  std::vector<MapBeam> beams;
  for (int k = 0; k < 361; ++k) {
    const double r = 12.0 - 0.01 * (k % 7), a = k * 2.0 * M_PI / 361.0;
    beams.push_back({r * std::cos(a), r * std::sin(a), k % 5 != 0, k % 3 == 0 ? 0.8 : 1.0});
  }
  const Pose2 robot{0.12, 0.07, 0.3}, sensor{0.2, 0.0, 0.0};
  GridMap whole = base, one_by_one = base;
  whole.insertScan(robot, sensor, beams, o);
  for (const MapBeam& b : beams) one_by_one.insertScan(robot, sensor, {b}, o);
  std::size_t cells = 0, hits = 0;
  whole.forEachTile([&](int tx, int ty, const GridMap::Tile&) {
    for (int y = 0; y < GridMap::kTileSize; ++y)
      for (int x = 0; x < GridMap::kTileSize; ++x) {
        const int cx = tx * GridMap::kTileSize + x, cy = ty * GridMap::kTileSize + y;
        const auto a = whole.cell(cx, cy), b = one_by_one.cell(cx, cy);
        ASSERT_TRUE(b) << cx << ' ' << cy;
        ASSERT_EQ(a->log_odds, b->log_odds) << cx << ' ' << cy;
        ASSERT_EQ(a->hits, b->hits) << cx << ' ' << cy;
        ASSERT_EQ(a->hit_x, b->hit_x) << cx << ' ' << cy;
        cells += a->log_odds != 0.0f;
        hits += a->hits;
      }
  });
  EXPECT_EQ(whole.tileCount(), one_by_one.tileCount());
  EXPECT_GT(cells, 50000u);
  EXPECT_GT(hits, 280u);
  // The original kept its own tiles: the wall's cells as before, the new scan's far cells unknown.
  EXPECT_FALSE(base.cell(base.cellIndex(-11.9), base.cellIndex(0.0)));
  EXPECT_LT(sharedTiles(base, whole), base.tileCount());
  GridMap again(0.05);
  again.insertScan({0.3, -0.2, 0.1}, {}, wall, o);
  base.forEachTile([&](int tx, int ty, const GridMap::Tile& t) {
    const GridMap::Tile* u = again.tileAt(tx * GridMap::kTileSize, ty * GridMap::kTileSize);
    ASSERT_TRUE(u);
    EXPECT_EQ(t.log_odds, u->log_odds);
  });
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

// A tile keeps hit means only for the cells a beam ended in, found by the rank of the cell's bit: the same means as
// a mean for every cell, in any order of first hits, across all four 64-cell words of the mask.
TEST(GridMap, HitMeansAreKeptForHitCellsOnly) {
  GridMap::HitMeans h;
  EXPECT_EQ(h.size(), 0u);
  for (std::size_t i = 0; i < static_cast<std::size_t>(GridMap::kTileCells); ++i) EXPECT_EQ(h.find(i), nullptr) << i;
  // First hits out of cell order, some in every word.
  const std::size_t cells[] = {200, 3, 255, 64, 0, 130, 63, 128, 191, 65};
  std::array<HitMean, GridMap::kTileCells> dense{};
  float v = 1.0f;
  for (const std::size_t c : cells) {
    HitMean& m = h.at(c);
    EXPECT_EQ(m.n, 0u) << c;  // made empty
    m.x = v, m.y = -v, m.n = static_cast<std::uint32_t>(c + 1);
    dense[c] = m;
    v += 1.0f;
  }
  EXPECT_EQ(h.size(), std::size(cells));
  for (std::size_t i = 0; i < static_cast<std::size_t>(GridMap::kTileCells); ++i) {
    const HitMean* m = h.find(i);
    if (dense[i].n == 0) {
      EXPECT_EQ(m, nullptr) << i;
      continue;
    }
    ASSERT_NE(m, nullptr) << i;
    EXPECT_EQ(m->x, dense[i].x) << i;
    EXPECT_EQ(m->y, dense[i].y) << i;
    EXPECT_EQ(m->n, dense[i].n) << i;
  }
  // A second hit in a cell updates its mean in place; a copy is independent.
  h.at(130).n += 10;
  GridMap::HitMeans copy = h;
  copy.at(130).n += 1;
  copy.at(7).n = 1;
  EXPECT_EQ(h.find(130)->n, 141u);
  EXPECT_EQ(copy.find(130)->n, 142u);
  EXPECT_EQ(h.find(7), nullptr);
  EXPECT_EQ(copy.size(), h.size() + 1);
  // Much smaller than a mean for every cell (3 KiB).
  EXPECT_LT(h.bytes(), sizeof(HitMean) * GridMap::kTileCells / 4);
}
