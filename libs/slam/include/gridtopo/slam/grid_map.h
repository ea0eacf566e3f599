#pragma once
// The particle map: an occupancy grid in log-odds made of square tiles shared between particles and copied
// on the first write (copy-on-write), so particles that descend from one parent share every tile neither of
// them changed since. The grid grows as the robot explores (no fixed bounds). Each cell also keeps the mean of
// the beam endpoints that hit it (as GMapping does), which gives the scan matcher sub-cell accuracy.
// A tile stores its cells as two arrays (log-odds, hit means): ray tracing, which touches many cells and reads
// only their log-odds, then loads 16 cells per cache line instead of 4 (it is bound by memory latency).
// Tiles are grouped in blocks of 8 × 8 tiles, themselves shared and copied on write: a map is a small array of
// block pointers, so a particle's own state is a few kB even on a map of 10^5 tiles (with one pointer per
// tile, 30 particles held 80 MB of pointers on the Freiburg hospital).
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "gridtopo/slam/pose2.h"

namespace gridtopo::slam {

/// Base of the objects held by CowPtr: the number of CowPtrs that hold it. A copy starts unheld.
class CowShared {
 public:
  CowShared() = default;
  CowShared(const CowShared&) {}
  CowShared& operator=(const CowShared&) = delete;

 private:
  template <class T>
  friend class CowPtr;
  mutable std::atomic<std::uint32_t> owners_{0};
};

/// A counted pointer to a copy-on-write object (half the size of a std::shared_ptr: no control block). Holders
/// may write the object in place only while use_count() is 1; the object is deleted with its last holder.
template <class T>
class CowPtr {
 public:
  CowPtr() = default;
  explicit CowPtr(T* t) : p_(t) {
    if (p_) p_->owners_.fetch_add(1, std::memory_order_relaxed);
  }
  CowPtr(const CowPtr& o) : CowPtr(o.p_) {}
  CowPtr(CowPtr&& o) noexcept : p_(o.p_) { o.p_ = nullptr; }
  CowPtr& operator=(CowPtr o) noexcept {
    std::swap(p_, o.p_);
    return *this;
  }
  ~CowPtr() {
    if (p_ && p_->owners_.fetch_sub(1, std::memory_order_acq_rel) == 1) delete p_;
  }
  T* get() const { return p_; }
  T* operator->() const { return p_; }
  T& operator*() const { return *p_; }
  explicit operator bool() const { return p_ != nullptr; }
  /// Holders of the object (0 for null).
  std::uint32_t use_count() const { return p_ ? p_->owners_.load(std::memory_order_acquire) : 0; }
  /// Makes the object this pointer's own (copies it when it is shared) and returns it.
  T& makeUnique() {
    if (use_count() > 1) *this = CowPtr(new T(*p_));
    return *p_;
  }

 private:
  T* p_ = nullptr;
};

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
  /// A hit marks free only the cells of the first free_fraction of its traced line (the rest lies too close to
  /// the surface it hit: see BeamOptions::surface_clearance).
  double free_fraction = 1.0;
};

class GridMap {
 public:
  static constexpr int kTileBits = 4;
  static constexpr int kTileSize = 1 << kTileBits;  ///< cells per tile side
  static constexpr int kTileMask = kTileSize - 1;
  static constexpr int kTileCells = kTileSize * kTileSize;
  /// The hit means of a tile's cells, stored for the cells a beam ended in only (a wall crosses a tile in a line of
  /// a few dozen of its 256 cells): a bit per cell says which cells have one, and the means follow in cell order,
  /// so a cell's mean is found by the rank of its bit. About a tenth of the 3 KiB a mean for every cell took.
  class HitMeans {
   public:
    /// The mean of cell i, or null when no beam ended in it.
    const HitMean* find(std::size_t i) const {
      const std::size_t w = i >> 6;
      const std::uint64_t bit = std::uint64_t{1} << (i & 63);
      if (!(mask_[w] & bit)) return nullptr;
      return &means_[rank(w, bit)];
    }
    /// The mean of cell i, made (zero, n = 0) when it has none yet.
    HitMean& at(std::size_t i) {
      const std::size_t w = i >> 6;
      const std::uint64_t bit = std::uint64_t{1} << (i & 63);
      const std::size_t r = rank(w, bit);
      if (!(mask_[w] & bit)) {
        mask_[w] |= bit;
        for (std::size_t k = w + 1; k < before_.size(); ++k) ++before_[k];
        means_.insert(means_.begin() + static_cast<std::ptrdiff_t>(r), HitMean{});
      }
      return means_[r];
    }
    std::size_t size() const { return means_.size(); }
    /// Bytes of the means kept (for stats.txt's map figure: the size, not the vector's capacity, which depends on
    /// how the means were copied and grown, so that the figure is the same however the run was driven).
    std::size_t bytes() const { return sizeof(*this) + means_.size() * sizeof(HitMean); }

   private:
    std::size_t rank(std::size_t w, std::uint64_t bit) const {
      return before_[w] + static_cast<std::size_t>(__builtin_popcountll(mask_[w] & (bit - 1)));
    }
    std::array<std::uint64_t, kTileCells / 64> mask_{};
    std::array<std::uint8_t, kTileCells / 64> before_{};  ///< hit cells in the words before each word
    std::vector<HitMean> means_;  ///< in cell order
  };
  /// A tile's hit means exist only once a beam has ended in it: tiles that long beams only cross (most of the
  /// area of a large building seen with a long-range laser) hold their 1 KiB of log-odds and nothing else.
  /// The hit means are shared between the copies of a tile and copied on their own first write: a beam that
  /// only crosses a tile changes its log-odds, so the copy a particle makes then shares the parent's hit means
  /// (most tiles a scan writes are crossed, not hit).
  struct Tile : CowShared {
    std::array<float, kTileCells> log_odds{};  ///< row-major (y, x) within the tile
    std::shared_ptr<HitMeans> hits;            ///< null until the first hit in the tile; shared between copies
    Tile() = default;
    Tile(const Tile& o) = default;  // shares the hit means
    Tile& operator=(const Tile&) = delete;
    /// The hit mean of a cell; null when no beam ever ended in it.
    const HitMean* hit(std::size_t i) const { return hits ? hits->find(i) : nullptr; }
    /// The hit means made writable: allocated at the first hit, copied first when another tile shares them.
    HitMeans& mutableHits();
  };
  static constexpr int kBlockBits = 3;  ///< a block is 2^3 × 2^3 tiles
  static constexpr int kBlockSize = 1 << kBlockBits;
  static constexpr int kBlockMask = kBlockSize - 1;
  static constexpr int kBlockCellBits = kBlockBits + kTileBits;
  /// Tiles of a block, row-major; a block is shared between maps and copied on write like a tile (a tile's
  /// use count is then the number of blocks that hold it).
  struct Block : CowShared {
    std::array<CowPtr<Tile>, kBlockSize * kBlockSize> tiles;
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
    const int bx = (cx >> kBlockCellBits) - bx0_, by = (cy >> kBlockCellBits) - by0_;
    if (static_cast<unsigned>(bx) >= static_cast<unsigned>(nbx_) ||
        static_cast<unsigned>(by) >= static_cast<unsigned>(nby_))
      return nullptr;
    const Block* b = blocks_[static_cast<std::size_t>(by) * nbx_ + bx].get();
    return b ? b->tiles[static_cast<std::size_t>(tileInBlock(cx, cy))].get() : nullptr;
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
  /// The allocated blocks (null: no tile there), row-major over the block grid.
  const std::vector<CowPtr<Block>>& blocks() const { return blocks_; }
  /// Calls f(tile_x, tile_y, tile) for every allocated tile.
  template <class F>
  void forEachTile(F&& f) const {
    for (int by = 0; by < nby_; ++by)
      for (int bx = 0; bx < nbx_; ++bx)
        if (const Block* b = blocks_[static_cast<std::size_t>(by) * nbx_ + bx].get())
          for (int i = 0; i < kBlockSize * kBlockSize; ++i)
            if (const Tile* t = b->tiles[static_cast<std::size_t>(i)].get())
              f(((bx + bx0_) << kBlockBits) + (i & kBlockMask), ((by + by0_) << kBlockBits) + (i >> kBlockBits), *t);
  }
  /// Occupancy probability of a cell (0.5 when unknown).
  double probability(int cx, int cy) const;

 private:
  static int tileInBlock(int cx, int cy) {
    return (((cy >> kTileBits) & kBlockMask) << kBlockBits) | ((cx >> kTileBits) & kBlockMask);
  }
  void ensureBlockRange(int bx_min, int by_min, int bx_max, int by_max);  // inclusive block coordinates
  Tile* writableTile(int cx, int cy);

  double res_, inv_res_;
  int bx0_ = 0, by0_ = 0, nbx_ = 0, nby_ = 0;
  std::vector<CowPtr<Block>> blocks_;
};

}  // namespace gridtopo::slam
