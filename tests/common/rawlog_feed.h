#pragma once
// Feeding scan records to an MRPT map builder in the action / sensory-frame rawlog layout, for the builders' tests:
// each record's odometry increment from the previous record as a CActionRobotMovement2D, its scan as the frame.
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/slam/CMetricMapBuilder.h>

#include <vector>

#include "gridtopo/io/scan_conversion.h"
#include "gridtopo/core/scan_record.h"

namespace gridtopo::testing_feed {

inline void feedActionObservation(mrpt::slam::CMetricMapBuilder& builder, const std::vector<gridtopo::ScanRecord>& records) {
  if (records.empty()) return;
  mrpt::poses::CPose2D prev(records[0].odometry);
  for (const auto& r : records) {
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CActionRobotMovement2D mv;
    const mrpt::poses::CPose2D odo(r.odometry);
    mv.computeFromOdometry(odo - prev, mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
    prev = odo;
    acts.insert(mv);
    mrpt::obs::CSensoryFrame sf;
    auto obs = io::toMrptScan(r.scan);
    obs->timestamp = io::toMrptTime(r.scan.timestamp);
    sf.insert(obs);
    builder.processActionObservation(acts, sf);
  }
}

}  // namespace gridtopo::testing_feed
