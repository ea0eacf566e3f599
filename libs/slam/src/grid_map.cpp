#include "gridtopo/slam/grid_map.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace gridtopo::slam {

GridMap::GridMap(double resolution) : res_(resolution), inv_res_(1.0 / resolution) {}

void GridMap::ensureBlockRange(int bx_min, int by_min, int bx_max, int by_max) {
  if (nbx_ > 0 && bx_min >= bx0_ && by_min >= by0_ && bx_max < bx0_ + nbx_ && by_max < by0_ + nby_) return;
  int nx0 = bx_min, ny0 = by_min, nx1 = bx_max, ny1 = by_max;
  if (nbx_ > 0) {
    nx0 = std::min(nx0, bx0_);
    ny0 = std::min(ny0, by0_);
    nx1 = std::max(nx1, bx0_ + nbx_ - 1);
    ny1 = std::max(ny1, by0_ + nby_ - 1);
  }
  // Grow with a margin so that exploring does not reallocate at every scan.
  constexpr int kMargin = 2;
  if (nx0 < bx0_ || nbx_ == 0) nx0 -= kMargin;
  if (ny0 < by0_ || nby_ == 0) ny0 -= kMargin;
  if (nbx_ == 0 || nx1 >= bx0_ + nbx_) nx1 += kMargin;
  if (nby_ == 0 || ny1 >= by0_ + nby_) ny1 += kMargin;
  const int nnbx = nx1 - nx0 + 1, nnby = ny1 - ny0 + 1;
  std::vector<CowPtr<Block>> nb(static_cast<std::size_t>(nnbx) * nnby);
  for (int by = 0; by < nby_; ++by)
    for (int bx = 0; bx < nbx_; ++bx)
      nb[static_cast<std::size_t>(by + by0_ - ny0) * nnbx + (bx + bx0_ - nx0)] =
          std::move(blocks_[static_cast<std::size_t>(by) * nbx_ + bx]);
  blocks_ = std::move(nb);
  bx0_ = nx0;
  by0_ = ny0;
  nbx_ = nnbx;
  nby_ = nnby;
}

GridMap::Tile* GridMap::writableTile(int cx, int cy) {
  const int bx = cx >> kBlockCellBits, by = cy >> kBlockCellBits;
  ensureBlockRange(bx, by, bx, by);
  auto& bslot = blocks_[static_cast<std::size_t>(by - by0_) * nbx_ + (bx - bx0_)];
  if (!bslot) bslot = CowPtr<Block>(new Block());
  auto& slot = bslot.makeUnique().tiles[static_cast<std::size_t>(tileInBlock(cx, cy))];  // copy on write
  if (!slot) slot = CowPtr<Tile>(new Tile());
  return &slot.makeUnique();  // copy on write
}

GridMap::HitMeans& GridMap::Tile::mutableHits() {
  if (!hits) {
    hits = std::make_shared<HitMeans>();
  } else if (hits.use_count() > 1) {
    hits = std::make_shared<HitMeans>(*hits);  // copy on write
  }
  return *hits;
}

float& GridMap::mutableLogOdds(int cx, int cy) {
  return writableTile(cx, cy)->log_odds[static_cast<std::size_t>(cellOffset(cx, cy))];
}

namespace {
inline void addLogOdds(float& l, float delta, const MapUpdateOptions& o) {
  l = std::clamp(l + delta, o.log_odds_min, o.log_odds_max);
}
}  // namespace

void GridMap::insertScan(const Pose2& robot, const Pose2& sensor, const std::vector<MapBeam>& beams,
                         const MapUpdateOptions& o) {
  const Pose2 sp = compose(robot, sensor);
  const double c = std::cos(robot.theta), s = std::sin(robot.theta);
  const int x0 = cellIndex(sp.x), y0 = cellIndex(sp.y);
  // World end points and the bounding box, so the grid grows once per scan.
  std::vector<std::array<double, 2>> ends(beams.size());
  int minx = x0, maxx = x0, miny = y0, maxy = y0;
  for (std::size_t k = 0; k < beams.size(); ++k) {
    const double wx = robot.x + c * beams[k].ex - s * beams[k].ey;
    const double wy = robot.y + s * beams[k].ex + c * beams[k].ey;
    ends[k] = {wx, wy};
    const int ex = cellIndex(wx), ey = cellIndex(wy);
    minx = std::min(minx, ex);
    maxx = std::max(maxx, ex);
    miny = std::min(miny, ey);
    maxy = std::max(maxy, ey);
  }
  ensureBlockRange(minx >> kBlockCellBits, miny >> kBlockCellBits, maxx >> kBlockCellBits, maxy >> kBlockCellBits);

  // Cache of the last writable tile (consecutive cells of a beam mostly share a tile).
  int cached_tx = 0x7fffffff, cached_ty = 0x7fffffff;
  Tile* cached = nullptr;
  auto tileOf = [&](int cx, int cy) -> Tile* {
    const int tx = cx >> kTileBits, ty = cy >> kTileBits;
    if (tx != cached_tx || ty != cached_ty) {
      cached = writableTile(cx, cy);
      cached_tx = tx;
      cached_ty = ty;
    }
    return cached;
  };

  for (std::size_t k = 0; k < beams.size(); ++k) {
    const int x1 = cellIndex(ends[k][0]), y1 = cellIndex(ends[k][1]);
    // Bresenham from the sensor cell to the end cell; every cell before the end is free.
    int x = x0, y = y0;
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    // A line of max(dx, -dy) steps; a hit near a surface seen at a grazing angle clears only its first part.
    const int steps = std::max(dx, -dy);
    const int free_steps =
        beams[k].hit && beams[k].free_fraction < 1.0 ? static_cast<int>(beams[k].free_fraction * steps) : steps;
    for (int step = 0; x != x1 || y != y1; ++step) {
      if (step < free_steps)
        addLogOdds(tileOf(x, y)->log_odds[static_cast<std::size_t>(cellOffset(x, y))], o.log_odds_free, o);
      const int e2 = 2 * err;
      if (e2 >= dy) {
        err += dy;
        x += sx;
      }
      if (e2 <= dx) {
        err += dx;
        y += sy;
      }
    }
    Tile* t = tileOf(x1, y1);
    const auto i = static_cast<std::size_t>(cellOffset(x1, y1));
    if (beams[k].hit) {
      addLogOdds(t->log_odds[i], o.log_odds_hit, o);
      HitMean& h = t->mutableHits().at(i);
      ++h.n;
      const float inv = 1.0f / static_cast<float>(h.n);
      h.x += (static_cast<float>(ends[k][0]) - h.x) * inv;
      h.y += (static_cast<float>(ends[k][1]) - h.y) * inv;
    } else {
      addLogOdds(t->log_odds[i], o.log_odds_free, o);
    }
  }
}

void GridMap::cellBounds(int& min_cx, int& min_cy, int& max_cx, int& max_cy) const {
  int a = 0x7fffffff, b = 0x7fffffff, cmax = -0x7fffffff, d = -0x7fffffff;
  forEachTile([&](int tx, int ty, const Tile&) {
    a = std::min(a, tx);
    b = std::min(b, ty);
    cmax = std::max(cmax, tx + 1);
    d = std::max(d, ty + 1);
  });
  if (cmax < a) {
    min_cx = min_cy = max_cx = max_cy = 0;
    return;
  }
  min_cx = a * kTileSize;
  min_cy = b * kTileSize;
  max_cx = cmax * kTileSize;
  max_cy = d * kTileSize;
}

std::size_t GridMap::tileCount() const {
  std::size_t n = 0;
  forEachTile([&](int, int, const Tile&) { ++n; });
  return n;
}

double GridMap::probability(int cx, int cy) const {
  const auto c = cell(cx, cy);
  if (!c) return 0.5;
  return 1.0 / (1.0 + std::exp(-static_cast<double>(c->log_odds)));
}

}  // namespace gridtopo::slam
