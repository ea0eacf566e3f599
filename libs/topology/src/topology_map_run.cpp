#include "gridtopo/topology/topology_map_run.h"

#include <algorithm>
#include <chrono>

#include "gridtopo/core/output_set.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/places/model.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/topology/run_summary.h"
#include "gridtopo/topology/topology_outputs.h"

namespace gridtopo::topology {

void runTopologyOnMapFile(const TopologyRunSpec& spec, bool quiet, std::ostream& log) {
  checkOutputFolder(spec.output);  // an unusable -o is said now, not after the run
  const TopologyOptions& opt = spec.options;
  const auto t0 = std::chrono::steady_clock::now();
  const places::PlacesModel model = places::PlacesModel::load(spec.model);

  io::MapReadOptions ro;
  ro.resolution = opt.resolution;
  MapImage map = io::readMap(spec.map, ro);
  if (!spec.trajectory.empty())
    for (const TimedPose& p : io::readTrajectory(spec.trajectory)) map.path.emplace_back(p.pose.x, p.pose.y);
  log << resolutionWarning(map.resolution, model);

  ProgressBar bar(100, "topology", "%", quiet ? 0 : -1);
  auto run = topologyOfMap(std::move(map), model, opt, [&](const std::string& stage, std::size_t d, std::size_t n) {
    if (stage == "scans") bar.update(d * 80 / std::max<std::size_t>(n, 1), stage);
    else bar.update(stage == "regions" ? 90 : 85, stage);
  }, false, true);
  bar.update(100, "exports");
  bar.finish();

  // The heap's free blocks go back to the system (apps/topology keeps them for reuse while the stages run): the
  // overlay, a large image at its scale, then takes pages afresh instead of adding to the stages' high-water mark.
  releaseFreedMemory();
  writeTopologyOutputs(spec.output, run.occ, run.topo, run.labelling.labels, opt.overlay_scale, topologyRunIni(spec));
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  log << runSummary(run, spec.map, secs);
}

}  // namespace gridtopo::topology
