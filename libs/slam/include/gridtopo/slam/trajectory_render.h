#pragma once
// The map re-rendered from a final trajectory at any resolution (Grisetti, Stachniss, Burgard 2007, Fig. 2: the
// Intel map "at a resolution of 1 cm", which shows no visible error). The filter's grid is 5 cm, but its
// trajectory is continuous: every scan of the log inserted at its pose of the trajectory into a fresh, finer grid
// (the SLAM's own beam preparation and inverse sensor model) shows any misalignment of the scans -- a doubled or
// blurred wall -- that the coarse grid hides. A window restricts the work to the scans taken near it and the beams
// to their part inside it, so a 1 cm cut-out of a large building costs seconds.
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <vector>

#include <opencv2/core.hpp>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/slam/prepared_scan.h"

namespace gridtopo::slam {

/// An axis-aligned rectangle of the world frame (metres), x0 < x1, y0 < y1.
struct MapWindow {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  static MapWindow around(double cx, double cy, double width, double height) {
    return {cx - width / 2, cy - height / 2, cx + width / 2, cy + height / 2};
  }
  bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

/// Where the trajectory first comes back to a place it left long before: poses `earlier` < `later`.
struct LoopClosure {
  std::size_t earlier = 0, later = 0;  ///< indices into the trajectory
  double distance = 0;                 ///< m between the two poses
  double travelled = 0;                ///< m driven from `earlier` to `later`
};

/// The first loop closure of a trajectory: the smallest `later` that lies within `radius` of a pose `earlier`
/// after which the robot drove at least `min_travel` metres. nullopt if the trajectory never comes back.
std::optional<LoopClosure> firstLoopClosure(const std::vector<TimedPose>& trajectory, double radius = 0.5,
                                            double min_travel = 30.0);

struct TrajectoryRenderOptions {
  double resolution = 0.01;  ///< m per cell of the rendered grid
  BeamOptions beams;         ///< as the SLAM prepares its scans (SlamOptions::beams)
  MapUpdateOptions map;      ///< its inverse sensor model (SlamOptions::map)
  /// Render only this window: scans whose laser lies more than `reach` metres outside it are skipped, the others'
  /// beams are cut at its border (a beam that leaves it marks free space up to the border).
  std::optional<MapWindow> window;
  double reach = 8.0;
  /// Insert only the scans of poses [first_pose, end_pose) (e.g. those before and after a loop closure).
  std::size_t first_pose = 0;
  std::size_t end_pose = static_cast<std::size_t>(-1);
};

/// A trajectory whose poses do not belong to the log's scans (a pose's timestamp is not its scan's).
struct TrajectoryMismatch : std::runtime_error {
  using std::runtime_error::runtime_error;
  std::size_t pose_index = 0;
};

/// The grid of every scan of `scans` inserted at its pose of `trajectory`. The trajectory has one pose per scan
/// fed to the SLAM (trajectory.txt), in the log's order: pose k belongs to scan k, whose timestamp it must carry;
/// a shorter trajectory (a run with --max-scans) renders its first scans. Throws TrajectoryMismatch otherwise.
/// `inserted` (optional) receives the number of scans inserted.
GridMap mapFromTrajectory(const std::vector<ScanRecord>& scans, const std::vector<TimedPose>& trajectory,
                          const TrajectoryRenderOptions& options, std::size_t* inserted = nullptr);

/// The window covering the allocated tiles of `map`.
MapWindow boundsOf(const GridMap& map);

/// 8-bit grey picture of `window` of `map` at the map's resolution: occupancy probability p as 255·(1 - p) (free
/// white, occupied black, unknown 128); row 0 is the top (largest y).
cv::Mat renderWindow(const GridMap& map, const MapWindow& window);

/// How well the walls of two renderings of one window agree (e.g. the scans before a loop closure and those after
/// it): for every occupied cell (p >= occupied) of `b`, the distance to the nearest occupied cell of `a`, over the
/// cells of `b` that `a` has seen (known in `a`), so that parts only `b` saw do not count.
struct WallAgreement {
  std::size_t cells = 0;  ///< occupied cells of b compared
  double median = 0;      ///< m
  double p90 = 0;         ///< m, 90th percentile
  double within_2cells = 0;  ///< fraction of the cells within two cells of a wall of a
};
WallAgreement wallAgreement(const GridMap& a, const GridMap& b, const MapWindow& window, double occupied = 0.65);

/// The paper's Fig. 2 cut-out in one call: the window of `size` metres around the trajectory's first loop closure
/// (firstLoopClosure with `radius` and `min_travel`), rendered from every scan, and the agreement of the walls seen
/// from the closure on (poses [later, end)) with those mapped before it (poses [0, later)). nullopt when the
/// trajectory has no loop closure.
struct LoopClosureRendering {
  LoopClosure closure;
  MapWindow window;
  WallAgreement agreement;
  GridMap map;  ///< every scan near the window
};
std::optional<LoopClosureRendering> renderLoopClosure(const std::vector<ScanRecord>& scans,
                                                      const std::vector<TimedPose>& trajectory,
                                                      const TrajectoryRenderOptions& options, double size,
                                                      double radius = 0.5, double min_travel = 30.0);

}  // namespace gridtopo::slam
