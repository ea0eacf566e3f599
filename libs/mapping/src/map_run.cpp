#include "gridtopo/mapping/map_run.h"

#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>

#include <chrono>
#include <filesystem>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/io/scan_conversion.h"
#include "gridtopo/places/model.h"
#include "gridtopo/mapping/rbpf_map_builder.h"
#include "gridtopo/slam/slam_outputs.h"
#include "gridtopo/slam/slam_run_ini.h"
#include "gridtopo/topology/topology_outputs.h"
#include "gridtopo/topology/topology_run_ini.h"

namespace fs = std::filesystem;

namespace gridtopo::mapping {

namespace {
double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

std::string slamOutputDir(const MapRunSpec& spec) { return (fs::path(spec.output) / "slam").string(); }
std::string topologyOutputDir(const MapRunSpec& spec) { return (fs::path(spec.output) / "topology").string(); }

MapRunSummary runMapping(const MapRunSpec& spec, const MapRunHooks& hooks) {
  checkMapRunSpec(spec);
  checkOutputFolder(spec.output);  // an unusable -o is said now, not after the run
  const auto t0 = std::chrono::steady_clock::now();
  MapRunSummary summary;
  io::ScanLogInfo info;
  std::vector<ScanRecord> records = io::readScanLog(spec.input, {}, info);
  for (const auto& w : info.warnings)
    if (hooks.warning) hooks.warning(w);
  for (const auto& n : info.notes)
    if (hooks.note) hooks.note(n);
  if (spec.max_scans > 0 && spec.max_scans < records.size()) records.resize(spec.max_scans);
  if (records.empty()) throw InputError(spec.input, "the log holds no laser scans");
  const auto model = std::make_shared<const places::PlacesModel>(places::PlacesModel::load(spec.model));
  summary.seconds_read = secondsSince(t0);

  // The two builders: the topology one wraps the SLAM one and is the only one fed.
  const auto t_map = std::chrono::steady_clock::now();
  auto slam_builder = std::make_shared<mapping::CMetricMapBuilderGridRbpf>(spec.slam);
  CMetricMapBuilderTopology builder(model, spec.topology, spec.builder, slam_builder);
  builder.onTopologyUpdated = hooks.topologyUpdated;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const ScanRecord& r = records[i];
    if (r.has_odometry) {
      auto odo = mrpt::obs::CObservationOdometry::Create();
      odo->odometry = mrpt::poses::CPose2D(r.odometry);
      odo->timestamp = io::toMrptTime(r.scan.timestamp);
      builder.processObservation(odo);
    }
    builder.processObservation(io::toMrptScan(r.scan));
    if (hooks.progress && ((i + 1) % 64 == 0 || i + 1 == records.size())) hooks.progress(i + 1, records.size());
  }
  summary.scans = records.size();
  records.clear();
  records.shrink_to_fit();
  summary.steps = slam_builder->filter().stepsProcessed();
  const unsigned final_size = builder.getCurrentlyBuiltMapSize();

  slam::SlamRunSpec slam_spec;
  slam_spec.input = spec.input;
  slam_spec.output = slamOutputDir(spec);
  slam_spec.max_scans = spec.max_scans;
  slam_spec.options = spec.slam;
  topology::TopologyRunSpec topo_spec;
  topo_spec.map = (fs::path(slam_spec.output) / "map.gridmap.gz").string();
  topo_spec.model = spec.model;
  topo_spec.output = topologyOutputDir(spec);
  topo_spec.trajectory = (fs::path(slam_spec.output) / "trajectory.txt").string();
  topo_spec.options = spec.topology;
  // The SLAM's outputs first, in its memory-saving order (every particle freed but the best), then the final map's
  // topology from that map unless the schedule has just computed it: the peak memory is the filter's or the
  // final map's with its topology, never both.
  const slam::SlamOutputs slam_out = slam_builder->finishRun(
      {"gridtopo-map " + spec.input, "one pose per laser scan, best particle"}, slam::slamRunIni(slam_spec));
  // The final topology is gridtopo-topology's on OUT/slam/map.gridmap.gz with -t OUT/slam/trajectory.txt: the
  // map preparation weighs every scan's pose (the schedule's updates had the simple map's, the processed scans').
  std::vector<cv::Point2d> path;
  path.reserve(slam_out.trajectory.size());
  for (const TimedPose& p : slam_out.trajectory) path.emplace_back(p.pose.x, p.pose.y);
  builder.updateTopologyOf(slam_out.grid, final_size, std::move(path));
  summary.topology = builder.currentTopology();
  summary.topology_updates = builder.topologyUpdates();
  summary.seconds_mapping = secondsSince(t_map);

  // Both output sets and the run's INI, committed together. Each set's options.ini reproduces its half alone:
  // gridtopo-slam OUT/slam/options.ini, gridtopo-topology OUT/topology/options.ini (on OUT/slam/map.gridmap.gz).
  const MapTopology& t = *summary.topology;
  OutputSet set(spec.output);  // one transaction for OUT: slam/, topology/ and options.ini swapped in together
  slam::addSlamOutputs(set, slam_spec.output, slam_out);
  topology::addTopologyOutputs(set, topo_spec.output, t.occ, t.topo, t.labelling.labels, spec.topology.overlay_scale,
                               topology::topologyRunIni(topo_spec));
  set.write((fs::path(spec.output) / "options.ini").string(),
            [&](const std::string& p) { writeTextFileAtomically(p, mapRunIni(spec)); });
  set.commit();
  summary.seconds_total = secondsSince(t0);
  return summary;
}

}  // namespace gridtopo::mapping
