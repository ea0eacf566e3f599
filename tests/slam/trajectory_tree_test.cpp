#include <gtest/gtest.h>

#include "gridtopo/slam/trajectory_tree.h"

using namespace gridtopo::slam;

TEST(TrajectoryTree, DescendantsShareTheirHistory) {
  auto root = std::make_shared<const TrajectoryNode>(Pose2{0, 0, 0}, 0, nullptr);
  TrajectoryNodePtr a = root;
  for (int i = 1; i <= 100; ++i) a = std::make_shared<const TrajectoryNode>(Pose2{i * 0.1, 0, 0}, i, a);
  // Resampling duplicates the leaf pointer; each copy then grows its own branch.
  TrajectoryNodePtr b = a, c = a;
  b = std::make_shared<const TrajectoryNode>(Pose2{10.1, 0.1, 0}, 101, b);
  c = std::make_shared<const TrajectoryNode>(Pose2{10.1, -0.1, 0}, 101, c);
  EXPECT_EQ(b->parent.get(), c->parent.get());  // the same node, not a copy
  const auto pb = pathOf(b), pc = pathOf(c);
  ASSERT_EQ(pb.size(), 102u);
  for (std::size_t i = 0; i < 101; ++i) EXPECT_EQ(pb[i], pc[i]);
  EXPECT_NE(pb[101], pc[101]);
  EXPECT_EQ(pb.front()->scan_index, 0u);
  EXPECT_DOUBLE_EQ(pb[50]->pose.x, 5.0);
  EXPECT_EQ(a.use_count(), 3);  // a, and the parents of b and c
}

TEST(TrajectoryTree, DeadBranchesAreFreed) {
  std::weak_ptr<const TrajectoryNode> dead;
  TrajectoryNodePtr keep;
  {
    auto root = std::make_shared<const TrajectoryNode>(Pose2{}, 0, nullptr);
    auto branch = std::make_shared<const TrajectoryNode>(Pose2{1, 0, 0}, 1, root);
    dead = branch;
    keep = std::make_shared<const TrajectoryNode>(Pose2{0, 1, 0}, 1, root);
  }
  EXPECT_TRUE(dead.expired());
  EXPECT_NE(keep->parent, nullptr);
}

TEST(TrajectoryTree, ReleasingAMillionNodeChainDoesNotOverflowTheStack) {
  TrajectoryNodePtr leaf;
  for (int i = 0; i < 1000000; ++i) leaf = std::make_shared<const TrajectoryNode>(Pose2{}, i, leaf);
  leaf.reset();
  SUCCEED();
}
