#include "gridtopo/slam/trajectory_tree.h"

#include <algorithm>

namespace gridtopo::slam {

TrajectoryNode::~TrajectoryNode() {
  std::shared_ptr<const TrajectoryNode> p = std::move(parent);
  while (p && p.use_count() == 1) {
    // We hold the last reference: detach its parent before it dies, so its destructor does not recurse.
    std::shared_ptr<const TrajectoryNode> next = std::move(const_cast<TrajectoryNode&>(*p).parent);
    p = std::move(next);
  }
}

std::vector<const TrajectoryNode*> pathOf(const TrajectoryNodePtr& leaf) {
  std::vector<const TrajectoryNode*> out;
  for (const TrajectoryNode* n = leaf.get(); n; n = n->parent.get()) out.push_back(n);
  std::reverse(out.begin(), out.end());
  return out;
}

void scansOfPath(const TrajectoryNodePtr& leaf, std::vector<std::size_t>& scan_indices, std::vector<Pose2>& poses) {
  scan_indices.clear();
  poses.clear();
  for (const TrajectoryNode* n : pathOf(leaf)) {
    scan_indices.push_back(n->scan_index);
    poses.push_back(n->pose);
  }
}

}  // namespace gridtopo::slam
