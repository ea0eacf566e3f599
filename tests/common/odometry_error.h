#pragma once
// Odometry errors the simulator does not make itself, for the SLAM tests.
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/pose2.h"

namespace gridtopo::testing_scene {

/// A systematic translation scale error on the odometry: every increment's translation times (1 + scale_error).
inline void scaleOdometry(sim::SimLog& log, double scale_error) {
  slam::Pose2 prev_in{}, out{};
  for (std::size_t i = 0; i < log.records.size(); ++i) {
    auto& o = log.records[i].odometry;
    const slam::Pose2 in{o.x, o.y, o.phi};
    if (i == 0) {
      out = in;
    } else {
      slam::Pose2 u = slam::relative(prev_in, in);
      u.x *= 1 + scale_error;
      u.y *= 1 + scale_error;
      out = slam::compose(out, u);
    }
    prev_in = in;
    o = {out.x, out.y, out.theta};
  }
}

}  // namespace gridtopo::testing_scene
