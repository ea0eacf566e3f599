#pragma once
// One gridtopo-map run: log -> SLAM -> topology in one process through the two MRPT map builders. The log's scans go
// to a CMetricMapBuilderTopology wrapping mapping::CMetricMapBuilderGridRbpf as MRPT observations (the observation-only
// rawlog layout: CObservationOdometry, then CObservation2DRangeScan), the topology is recomputed on the builder's
// schedule and once more on the final map, and the outputs land in OUT/slam (slam::addSlamOutputs: what
// gridtopo-slam writes), OUT/topology (topology::addTopologyOutputs: what gridtopo-topology writes) and
// OUT/options.ini (mapRunIni), all in one OutputSet: the whole set or nothing.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "gridtopo/mapping/map_run_ini.h"
#include "gridtopo/mapping/topology_builder.h"

namespace gridtopo::mapping {

/// What the caller hears during a run; every hook may be empty.
struct MapRunHooks {
  std::function<void(const std::string&)> warning, note;        ///< the log reader's warnings and notes
  std::function<void(std::size_t fed, std::size_t total)> progress;  ///< every 64 scans and at the end
  std::function<void(const MapTopology&)> topologyUpdated;      ///< each recomputation, scheduled or final
};

struct MapRunSummary {
  std::size_t scans = 0;             ///< scans fed to the builders
  std::size_t steps = 0;             ///< scans the filter processed (the SLAM map's size)
  std::size_t topology_updates = 0;  ///< recomputations of the topology, the final one included
  std::shared_ptr<const MapTopology> topology;  ///< the final map's
  double seconds_read = 0, seconds_mapping = 0, seconds_total = 0;
};

/// The outputs' places: OUT/slam, OUT/topology.
std::string slamOutputDir(const MapRunSpec& spec);
std::string topologyOutputDir(const MapRunSpec& spec);

/// Runs `spec` (checked with checkMapRunSpec first) and writes its outputs. InputError for bad input (an unreadable
/// or empty log, a bad model, a map without free cells).
MapRunSummary runMapping(const MapRunSpec& spec, const MapRunHooks& hooks = {});

}  // namespace gridtopo::mapping
