#include "gridtopo/slam/slam_outputs.h"

#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include <filesystem>
#include <functional>
#include <sstream>
#include <utility>
#include <stdexcept>

#include "gridtopo/core/output_set.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/io/image_write.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/io/scan_conversion.h"
#include "gridtopo/slam/map_export.h"

namespace fs = std::filesystem;

namespace gridtopo::slam {

mrpt::maps::CSimpleMap simpleMapOf(const TrajectoryNodePtr& leaf, const std::vector<ScanRecord>& scans) {
  std::vector<std::size_t> indices;
  std::vector<Pose2> poses;
  scansOfPath(leaf, indices, poses);
  return simpleMapAt(indices, poses, scans);
}

mrpt::maps::CSimpleMap simpleMapAt(const std::vector<std::size_t>& scan_indices, const std::vector<Pose2>& poses,
                                   const std::vector<ScanRecord>& scans) {
  mrpt::maps::CSimpleMap sm;
  for (std::size_t k = 0; k < std::min(scan_indices.size(), poses.size()); ++k) {
    auto sf = mrpt::obs::CSensoryFrame::Create();
    sf->insert(io::toMrptScan(scans.at(scan_indices[k]).scan));
    const Pose2& p = poses[k];
    sm.insert(std::make_shared<mrpt::poses::CPose3DPDFGaussian>(mrpt::poses::CPose3D(p.x, p.y, 0, p.theta, 0, 0)), sf);
  }
  return sm;
}

namespace {
// The output set of `result` without its simple map: the map as MRPT's occupancy grid (`result.map` freed once
// converted, the memory given back) and the texts.
SlamOutputs exportWithoutSimpleMap(SlamResult& result) {
  SlamOutputs o;
  o.grid = toOccupancyGrid(result.map);
  result.map = GridMap(result.map.resolution());
  releaseFreedMemory();
  o.trajectory = std::move(result.trajectory);
  o.closures = std::move(result.closures);
  o.trajectory_header = std::move(result.trajectory_header);
  o.stats = std::move(result.stats);
  o.options_ini = std::move(result.options_ini);
  return o;
}

mrpt::maps::CSimpleMap simpleMapOfResult(const SlamResult& result) {
  return result.scans ? simpleMapAt(result.scan_indices, result.scan_poses, *result.scans) : mrpt::maps::CSimpleMap{};
}

// addSlamOutputs with the simple map's file written by `write_simplemap` (after the pictures).
void addOutputs(OutputSet& out, const std::string& dir, const SlamOutputs& o,
                const std::function<void(const std::string&)>& write_simplemap);
}  // namespace

SlamOutputs exportSlamResult(SlamResult&& result) {
  SlamOutputs o = exportWithoutSimpleMap(result);
  o.simplemap = simpleMapOfResult(result);
  return o;
}

void writeSlamResult(const std::string& dir, SlamResult&& result) {
  // The simple map (a copy of every processed scan as MRPT's observation) is made when its file is written, after
  // the pictures are written and freed: the two are never in memory together.
  const SlamOutputs o = exportWithoutSimpleMap(result);
  OutputSet out(dir);
  addOutputs(out, dir, o, [&](const std::string& p) { io::writeSimplemap(simpleMapOfResult(result), p); });
  out.commit();
}

void writeSlamOutputs(const std::string& dir, const SlamOutputs& o) {
  OutputSet out(dir);
  addSlamOutputs(out, dir, o);
  out.commit();
}

void addSlamOutputs(OutputSet& out, const std::string& dir, const SlamOutputs& o) {
  addOutputs(out, dir, o, [&](const std::string& p) { io::writeSimplemap(o.simplemap, p); });
}

namespace {
void addOutputs(OutputSet& out, const std::string& dir, const SlamOutputs& o,
                const std::function<void(const std::string&)>& write_simplemap) {
  const fs::path d(dir);
  out.write((d / "trajectory.txt").string(),
            [&](const std::string& p) { io::writeTrajectory(p, o.trajectory, o.trajectory_header); });
  out.write((d / "stats.txt").string(), [&](const std::string& p) { writeTextFileAtomically(p, o.stats); });
  out.write((d / "map.png").string(), [&](const std::string& p) { io::writeMapPng(o.grid, p); });
  out.write((d / "map_trajectory.png").string(), [&](const std::string& p) {
    io::writePng(renderMap(o.grid, o.trajectory, o.closures), p);
  });
  out.write((d / "map.gridmap.gz").string(), [&](const std::string& p) { io::writeGridmapGz(o.grid, p); });
  {
    // The ROS pair names its image inside the YAML: both staged under their final names in the set's stage folder.
    const std::string pgm = out.add((d / "map.pgm").string()), yaml = out.add((d / "map.yaml").string());
    const fs::path stage_dir = fs::path(pgm).parent_path();
    if (fs::path(pgm).filename() != "map.pgm" || fs::path(yaml) != stage_dir / "map.yaml")
      throw std::logic_error("addSlamOutputs: the OutputSet must be a folder transaction around " + dir);
    try {
      io::writeRosMap(o.grid, (stage_dir / "map").string());
    } catch (const std::exception& e) {
      std::string what = e.what();
      for (std::size_t pos; (pos = what.find(stage_dir.string())) != std::string::npos;)
        what.replace(pos, stage_dir.string().size(), d.string());
      throw std::runtime_error(what);
    }
  }
  out.write((d / "map.simplemap").string(), write_simplemap);
  out.write((d / "options.ini").string(), [&](const std::string& p) { writeTextFileAtomically(p, o.options_ini); });
}
}  // namespace

}  // namespace gridtopo::slam

// writeSlamResult for libgridtopo_slam_core's writeSlamResultLoadingExport, which loads this library (gridtopo-slam).
extern "C" void gridtopo_slam_write_result(const std::string& dir, gridtopo::slam::SlamResult& result) {
  gridtopo::slam::writeSlamResult(dir, std::move(result));
}
