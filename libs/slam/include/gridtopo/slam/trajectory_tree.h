#pragma once
// Particle trajectories as a tree: each particle points at its newest node; nodes point at their parent.
// Resampling copies a pointer, never a path, so descendants of one particle share its whole history.
#include <cstddef>
#include <memory>
#include <vector>

#include "gridtopo/slam/pose2.h"

namespace gridtopo::slam {

struct TrajectoryNode {
  Pose2 pose;  ///< the particle's pose: the sample its map was updated with
  /// The pose reported in the trajectory: the mean of the proposal the pose was drawn from (the Rao-Blackwellized
  /// estimate of the pose given the particle's past, which lacks the sample's own noise), or the pose itself.
  Pose2 estimate;
  std::size_t scan_index = 0;  ///< index of the scan (in input order) this pose belongs to
  /// Whether the pose came from the scan match (false: the match failed and the pose was drawn from the odometry
  /// motion model). The loop closure's motion edge into it is as uncertain as that.
  bool matched = true;
  std::shared_ptr<const TrajectoryNode> parent;

  TrajectoryNode(const Pose2& p, std::size_t scan, std::shared_ptr<const TrajectoryNode> par)
      : pose(p), estimate(p), scan_index(scan), parent(std::move(par)) {}
  TrajectoryNode(const Pose2& p, const Pose2& est, std::size_t scan, std::shared_ptr<const TrajectoryNode> par)
      : pose(p), estimate(est), scan_index(scan), parent(std::move(par)) {}
  TrajectoryNode(const TrajectoryNode&) = delete;
  TrajectoryNode& operator=(const TrajectoryNode&) = delete;
  /// Releases long chains iteratively (a recursive release of a 10⁵-node path would overflow the stack).
  ~TrajectoryNode();
};

using TrajectoryNodePtr = std::shared_ptr<const TrajectoryNode>;

/// The path from the root to `leaf`, oldest first.
std::vector<const TrajectoryNode*> pathOf(const TrajectoryNodePtr& leaf);
/// The processed scans along the path to `leaf`, root first: their scan indices and poses (pathOf's nodes).
void scansOfPath(const TrajectoryNodePtr& leaf, std::vector<std::size_t>& scan_indices, std::vector<Pose2>& poses);

}  // namespace gridtopo::slam
