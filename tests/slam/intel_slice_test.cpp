#include <gtest/gtest.h>

#include "gridtopo/eval/relations.h"
#include "gridtopo/eval/relations_metric.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/rbpf_slam.h"

using namespace gridtopo;

// The first 2500 scans of the Intel Research Lab log (about 9 minutes of driving through the upper corridor and
// its rooms), scored with the Freiburg relations that fall inside the slice.
TEST(IntelSlice, SmallErrorOnTheRelationsOfTheSlice) {
  auto records = io::readScanLog(std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz");
  ASSERT_GT(records.size(), 13000u);
  records.resize(2500);
  slam::SlamOptions o;  // defaults (= config-ini/slam.ini)
  o.particles = 10;
  slam::RbpfSlam filter(o);
  for (const auto& r : records) filter.processScan(r);
  const auto traj = filter.trajectory();
  ASSERT_EQ(traj.size(), records.size());
  const double t_end = records.back().scan.timestamp;
  std::vector<eval::Relation> inside;
  for (const auto& rel : eval::readRelations(std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.relations.gz"))
    if (rel.t1 <= t_end && rel.t2 <= t_end) inside.push_back(rel);
  ASSERT_GT(inside.size(), 300u);
  const auto res = eval::evaluateRelations(traj, inside, nullptr);
  std::printf("intel slice: %zu scans, %zu steps, %zu relations: %.4f +- %.4f m, %.3f deg, max %.3f m\n",
              records.size(), filter.stepsProcessed(), inside.size(), res.translational.mean, res.translational.std,
              res.rotational.mean, res.translational.max);
  // Odometry alone on the same relations, for scale.
  std::vector<TimedPose> odo(records.size());
  for (std::size_t i = 0; i < odo.size(); ++i) odo[i] = {records[i].scan.timestamp, records[i].odometry};
  const auto ro = eval::evaluateRelations(odo, inside, nullptr);
  std::printf("odometry: %.4f m, %.3f deg\n", ro.translational.mean, ro.rotational.mean);
  EXPECT_LT(res.translational.mean, 0.04);
  EXPECT_LT(res.rotational.mean, 0.8);
  EXPECT_LT(res.translational.max, 0.5);
  EXPECT_LT(res.translational.mean, 0.5 * ro.translational.mean);
}
