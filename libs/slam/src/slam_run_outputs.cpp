// SlamRun's members that give MRPT's types (slam_run.h): in libgridtopo_slam, over libgridtopo_slam_core's result.
#include <mrpt/maps/CSimpleMap.h>

#include "gridtopo/slam/slam_outputs.h"
#include "gridtopo/slam/slam_run.h"

namespace gridtopo::slam {

mrpt::maps::CSimpleMap SlamRun::simpleMap() const {
  std::vector<std::size_t> indices;
  std::vector<Pose2> poses;
  simpleMapScans(indices, poses);
  return simpleMapAt(indices, poses, scans());
}

SlamOutputs SlamRun::outputs(const std::vector<std::string>& trajectory_header, const std::string& options_ini) const {
  return exportSlamResult(result(trajectory_header, options_ini));
}

SlamOutputs SlamRun::finish(const std::vector<std::string>& trajectory_header, const std::string& options_ini) {
  return exportSlamResult(finishResult(trajectory_header, options_ini));
}

void SlamRun::finishAndWrite(const std::string& dir, const std::vector<std::string>& trajectory_header,
                             const std::string& options_ini) {
  writeSlamResult(dir, finishResult(trajectory_header, options_ini));
}

}  // namespace gridtopo::slam
