#pragma once
// Observation likelihood p(z | m, x) and the search for its mode, as in GMapping (Grisetti et al. 2007,
// section IV): each beam end point is associated with the nearest hit mean among the occupied cells of a
// small window whose cell in front (towards the robot) is free; ln p = Σ_k max(−d_k²/(2σ²), null_log_likelihood).
// The mode is found by hill climbing from the predicted pose with step halving, which converges to sub-cell
// accuracy because the hit means are continuous.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/pose2.h"
#include "gridtopo/slam/prepared_scan.h"

namespace gridtopo::slam {

enum class MatchMethod {
  HillClimb,    ///< GMapping's search: ±step moves in x, y, θ, halving the step when no move improves
  GaussNewton,  ///< Gauss-Newton on the end point-to-hit-mean distances, then a short hill-climbing polish
};

/// What a beam's distance d to its correspondence measures.
enum class MatchResidual {
  Point,  ///< end point to hit mean (GMapping)
  /// The same, projected on the surface normal at the end point (estimated from the neighbouring beams; point
  /// where there is none). Hit means are sparse along a wall seen at a grazing angle, and point distances along it
  /// favour poses that put the end points where the previous scans' end points fell: a pull towards zero motion
  /// along corridors.
  Plane,
};

struct ScanMatcherOptions {
  MatchResidual residual = MatchResidual::Point;
  MatchMethod method = MatchMethod::HillClimb;  // Gauss-Newton is experimental (slower to converge here)
  int gn_iterations = 8;              ///< Gauss-Newton iterations (re-association at each)
  int gn_kernel = 2;                  ///< correspondence window half size (cells) during Gauss-Newton
  double polish_step_xy = 0.01;       ///< m, first step of the hill-climbing polish after Gauss-Newton
  double polish_step_theta = 0.005;   ///< rad
  int polish_refinements = 3;         ///< step halvings of the polish
  double sigma = 0.05;                ///< m, std-dev of the end point-to-obstacle distance
  int kernel = 1;                     ///< window half size in cells for the correspondence search
  double null_log_likelihood = -2.0;  ///< per-beam log-likelihood floor (no correspondence / outlier)
  /// A cell with hit means is a correspondence candidate while its log-odds exceeds this. Below 0 so that walls
  /// crossed by many grazing free rays (their cells' log-odds worn below 0 while they still hold hit means) stay
  /// matchable: with 0 the end points ahead of the true pose in a long corridor lose their correspondences and the
  /// filter falls behind (doc/slam.md, "Long corridors").
  float occupied_log_odds = -2.0f;
  /// GMapping's test: a correspondence counts only if the cell one step back along the beam is not occupied
  /// (avoids matching a wall from behind). It rejects grazing beams on walls two cells thick, which biases
  /// the match by up to half a cell, so it is off by default.
  bool free_check = false;
  double step_xy = 0.05;              ///< m, initial hill-climbing step
  double step_theta = 0.05;           ///< rad, initial hill-climbing step
  int refinements = 6;                ///< number of step halvings
  /// Coarse-to-fine: the first `coarse_levels` step sizes of the hill climb score every `coarse_beam_step`-th
  /// matching beam only; the finer levels (and the final score) use all of them. 0 = all beams throughout.
  int coarse_levels = 0;
  int coarse_beam_step = 2;
  int max_iterations = 200;           ///< safety cap on hill-climbing moves
  /// Informed / mode-only proposals: search the mode of p(z|m,x)·p(x|x_{t-1},u) (true) or of p(z|m,x) (false).
  bool use_motion_prior = false;
  /// Matching fails when fewer than this fraction of the matching beams found a correspondence.
  double min_match_fraction = 0.3;
};

struct ScanScore {
  double log_likelihood = 0.0;  ///< Σ over matching beams (not divided by the gain)
  int matched = 0;              ///< beams that found a correspondence
};

struct MatchResult {
  Pose2 pose;
  ScanScore score;
  int evaluations = 0;
  bool ok = false;  ///< enough beams matched
};

/// ln p(z | m, x) over the matching beams.
ScanScore scoreScan(const GridMap& map, const Pose2& x, const PreparedScan& scan, const ScanMatcherOptions& o);

/// The same likelihood for many poses of one scan in one map (a scan-matching search and the proposal's K
/// poses). The correspondence search depends only on the cell an end point falls in: the hit means of the
/// occupied cells of each cell's window are looked up in the map once and kept in a small hash table, and each
/// beam also keeps the windows of the last cells it fell in (a direct-mapped cache of 16 per beam). Most end
/// points of a search fall in cells seen before (the search steps back and forth by a cell or less), so most
/// evaluations read no map tile and most skip the hash table. Gives exactly scoreScan's result.
/// The map must not change while the scorer is used. Its tables are reused by the next scorer of the same thread
/// (a proposal makes one per particle and scan, two with the coarse-to-fine search; allocating and filling ≈ 150 kB
/// each time was 9 % of the hospital's CPU in `perf`); only the slots a scorer filled are emptied when it ends.
class ScanScorer {
 public:
  ScanScorer(const GridMap& map, const PreparedScan& scan, const ScanMatcherOptions& o);
  ~ScanScorer();
  ScanScorer(const ScanScorer&) = delete;
  ScanScorer& operator=(const ScanScorer&) = delete;
  ScanScore score(const Pose2& x);
  /// The same, but gives up (returns nothing) as soon as the partial sum is <= stop_at: every beam's term is
  /// <= 0, so the full sum could only be lower. The hill climb uses it to drop candidate poses that cannot beat
  /// the best one so far; a pose whose score it returns has exactly score(x).
  std::optional<ScanScore> scoreAbove(const Pose2& x, double stop_at);
  const GridMap& map() const { return map_; }
  const PreparedScan& scan() const { return scan_; }
  const ScanMatcherOptions& options() const { return o_; }

 private:
  struct Slot {
    std::uint64_t key;     // packed cell coordinates; kEmpty when unused
    std::uint32_t offset;  // into hits_ (pairs)
    std::uint32_t count;   // occupied cells in the window
  };
  // The key of cell (INT_MIN, INT_MIN), which no end point reaches (cellKey(-1, -1) is all ones: not usable).
  static constexpr std::uint64_t kEmpty = 0x8000000080000000ULL;
  const Slot& window(int cx, int cy);  // finds or fills the window of a cell
  void grow();
  template <bool kStop>
  bool scoreImpl(const Pose2& x, double stop_at, ScanScore& out);

  const GridMap& map_;
  const PreparedScan& scan_;
  const ScanMatcherOptions& o_;
  // The tables below, taken from the thread's pool of unused ones (empty) and given back (emptied) at the end.
  struct Tables;
  static std::vector<std::unique_ptr<Tables>>& threadPool();
  static std::unique_ptr<Tables> takeTables();
  std::unique_ptr<Tables> tables_;
  std::vector<Slot>& table_;         // open addressing, linear probing, power-of-two size
  std::vector<std::uint32_t>& filled_;  // the table's slots in use, to empty them at the end
  std::size_t used_ = 0;
  int shift_ = 0;                    // 64 - log2(table size)
  std::vector<double>& hits_;        // hit means (x, y) of the windows' occupied cells, in scoreScan's order
  // Per beam, a direct-mapped cache of the windows of the cells its end point visited, indexed by the low bits
  // of the cell coordinates: the end point of one beam stays within a few cells during a search, so a 4 × 4
  // block of cells has no collisions and most look-ups skip the hash table.
  static constexpr int kNearBits = 2;
  static constexpr int kNearMask = (1 << kNearBits) - 1;
  static constexpr std::size_t kNearSlots = std::size_t{1} << (2 * kNearBits);
  std::vector<Slot>& near_;
};

/// Optional prior multiplied into the matched objective: the search then finds the mode of
/// p(z|m,x)^likelihood_scale · prior(x) — with the motion model as prior, the mode of the informed proposal's
/// target distribution rather than of the likelihood alone.
struct MatchPrior {
  double likelihood_scale = 1.0;                ///< e.g. 1 / gain
  std::function<double(const Pose2&)> log_prior;  ///< ln prior(x)
};

/// Searches from `start` for the mode of the likelihood (or of likelihood × prior when `prior` is given).
MatchResult matchScan(const GridMap& map, const Pose2& start, const PreparedScan& scan,
                      const ScanMatcherOptions& o, const MatchPrior* prior = nullptr);
/// The same search with the scorer's map, scan and options (its cache is kept for further scoring).
MatchResult matchScan(ScanScorer& scorer, const Pose2& start, const MatchPrior* prior = nullptr);

}  // namespace gridtopo::slam
