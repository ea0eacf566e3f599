#pragma once
// The particle map: an occupancy grid in log-odds made of square tiles shared between particles and copied
// on the first write (copy-on-write), so particles that descend from one parent share every tile neither of
// them changed since. The grid grows as the robot explores (no fixed bounds). Each cell also keeps the mean of
// the beam endpoints that hit it (as GMapping does), which gives the scan matcher sub-cell accuracy.
// A tile stores its cells as two arrays (log-odds, hit means): ray tracing, which touches many cells and reads
// only their log-odds, then loads 16 cells per cache line instead of 4 (it is bound by memory latency).
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "gridtopo/slam/pose2.h"

namespace gridtopo::slam {

/// A cell's state (by value; see GridMap::cell).
struct Cell {
  float log_odds = 0.0f;  ///< ln(p / (1 - p)); 0 = unknown
  float hit_x = 0.0f;     ///< mean world x of the beam end points that hit this cell
  float hit_y = 0.0f;     ///< mean world y of those end points
  std::uint32_t hits = 0;
};

/// Mean of the beam end points that hit a cell.
struct HitMean {
  float x = 0.0f, y = 0.0f;  ///< world coordinates
  std::uint32_t n = 0;       ///< number of hits
};

struct MapUpdateOptions {
  float log_odds_hit = 0.85f;    ///< added to a cell where a beam ends
  float log_odds_free = -0.3f;   ///< added to every cell a beam crosses before its end
  float log_odds_min = -4.0f;    ///< clamp
  float log_odds_max = 4.0f;     ///< clamp
};

/// A beam ready to insert: its end in the sensor frame and whether it ends on an obstacle.
struct MapBeam {
  double ex, ey;  ///< end point in the robot frame (metres)
  bool hit;       ///< true: obstacle at the end; false: free space up to the end (no return / clipped)
};

class GridMap {
 public:
  static constexpr int kTileBits = 4;
  static constexpr int kTileSize = 1 << kTileBits;  ///< cells per tile side
  static constexpr int kTileMask = kTileSize - 1;
  static constexpr int kTileCells = kTileSize * kTileSize;
  using HitMeans = std::array<HitMean, kTileCells>;
  /// A tile's hit means exist only once a beam has ended in it: tiles that long beams only cross (most of the
  /// area of a large building seen with a long-range laser) hold their 1 KiB of log-odds and nothing else.
  /// The hit means are shared between the copies of a tile and copied on their own first write: a beam that
  /// only crosses a tile changes its log-odds, so the copy a particle makes then shares the parent's 3 KiB of
  /// hit means (most tiles a scan writes are crossed, not hit).
  struct Tile {
    std::array<float, kTileCells> log_odds{};  ///< row-major (y, x) within the tile
    std::shared_ptr<HitMeans> hits;            ///< null until the first hit in the tile; shared between copies
    Tile() = default;
    Tile(const Tile& o) = default;  // shares the hit means
    Tile& operator=(const Tile&) = delete;
    /// The hit mean of a cell; null when no beam ever ended in this tile.
    const HitMean* hit(std::size_t i) const { return hits ? &(*hits)[i] : nullptr; }
    /// The hit means made writable: allocated at the first hit, copied first when another tile shares them.
    HitMeans& mutableHits();
  };
  /// Index of a cell within its tile.
  static int cellOffset(int cx, int cy) { return ((cy & kTileMask) << kTileBits) | (cx & kTileMask); }

  explicit GridMap(double resolution = 0.05);

  double resolution() const { return res_; }
  int cellIndex(double w) const {
    const double v = w * inv_res_;
    const int i = static_cast<int>(v);  // truncation; fix up negatives (std::floor is a libm call on x86-64)
    return i - (v < static_cast<double>(i));
  }
  double cellCenter(int c) const { return (c + 0.5) * res_; }

  /// The tile holding a cell, or nullptr when none was allocated there (never observed).
  const Tile* tileAt(int cx, int cy) const {
    const int tx = (cx >> kTileBits) - tx0_, ty = (cy >> kTileBits) - ty0_;
    if (static_cast<unsigned>(tx) >= static_cast<unsigned>(ntx_) ||
        static_cast<unsigned>(ty) >= static_cast<unsigned>(nty_))
      return nullptr;
    return tiles_[static_cast<std::size_t>(ty) * ntx_ + tx].get();
  }
  /// The cell at integer cell coordinates, or nothing when its tile was never allocated (never observed).
  std::optional<Cell> cell(int cx, int cy) const {
    const Tile* t = tileAt(cx, cy);
    if (!t) return std::nullopt;
    const int i = cellOffset(cx, cy);
    const HitMean* h = t->hit(static_cast<std::size_t>(i));
    return h ? Cell{t->log_odds[static_cast<std::size_t>(i)], h->x, h->y, h->n}
             : Cell{t->log_odds[static_cast<std::size_t>(i)], 0.0f, 0.0f, 0};
  }
  /// The cell's log-odds, made writable: grows the grid if needed and copies a shared tile first.
  float& mutableLogOdds(int cx, int cy);

  /// Inserts one scan taken with the robot at `robot` and the laser at `sensor` (robot frame): every beam
  /// marks the cells it crosses free (Bresenham) and, for a hit, its last cell occupied.
  void insertScan(const Pose2& robot, const Pose2& sensor, const std::vector<MapBeam>& beams,
                  const MapUpdateOptions& o);

  /// Bounding box of allocated tiles in cell coordinates [min, max); empty map: all zeros.
  void cellBounds(int& min_cx, int& min_cy, int& max_cx, int& max_cy) const;
  std::size_t tileCount() const;  ///< allocated tiles
  const std::vector<std::shared_ptr<Tile>>& tiles() const { return tiles_; }
  /// Occupancy probability of a cell (0.5 when unknown).
  double probability(int cx, int cy) const;

 private:
  void ensureTileRange(int tx_min, int ty_min, int tx_max, int ty_max);  // inclusive tile coordinates
  Tile* writableTile(int cx, int cy);

  double res_, inv_res_;
  int tx0_ = 0, ty0_ = 0, ntx_ = 0, nty_ = 0;
  std::vector<std::shared_ptr<Tile>> tiles_;
};

}  // namespace gridtopo::slam
