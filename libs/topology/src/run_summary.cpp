#include "gridtopo/topology/run_summary.h"

#include <sstream>

#include "gridtopo/core/process_memory.h"

namespace gridtopo::topology {

std::string resolutionWarning(double resolution, const places::PlacesModel& model) {
  if (!(resolution > model.scan.lattice_spacing * 1.5 && model.scan.lattice_spacing > 0)) return "";
  std::ostringstream o;
  o << "warning: map resolution " << resolution << " m is coarser than the model's lattice ("
    << model.scan.lattice_spacing << " m); results may differ from training\n";
  return o.str();
}

std::string runSummary(const MapTopology& run, const std::string& source, double seconds) {
  const auto& lab = run.labelling;
  int counts[places::kNumLabels] = {0, 0, 0};
  for (const auto& n : run.topo.graph.nodes) counts[n.label]++;
  std::ostringstream o;
  const PreparedMap& p = run.prepared;
  const double res2 = run.occ.resolution * run.occ.resolution;
  o << source << ": " << run.occ.cols() << "x" << run.occ.rows() << " cells, places " << p.place_cells * res2
    << " of " << p.free_cells * res2 << " m^2 free (not places: robot does not fit " << p.removed_robot_fit * res2
    << ", seen only from afar " << p.removed_far * res2 << ", unreachable " << p.removed_unreachable * res2
    << " m^2), " << lab.lattice.samples.size()
    << " classified, relaxation " << lab.relaxation.iterations << " iterations; " << counts[0] << " rooms, "
    << counts[1] << " corridors, " << counts[2] << " doorways, " << run.topo.graph.edges.size() << " edges, "
    << segmentCount(run.topo.segmentation) << " segments, " << run.topo.door_passages.size()
    << " door passages, " << run.topo.room_entries.size() << " room entries, " << run.topo.open_spaces.size()
    << " open spaces joined and " << run.topo.thoroughfares.size() << " thoroughfares of the path; " << seconds
    << " s (prepare " << run.seconds_prepare
    << ", scans " << lab.seconds_scans << ", features " << lab.seconds_features << ", classify "
    << lab.seconds_classify << ", relax " << lab.seconds_relax << ", graph " << run.seconds_graph << ")";
  if (const std::size_t peak = processMemory().peak_kb) o << ", peak RSS " << (peak + 512) / 1024 << " MB";
  o << "\n";
  return o.str();
}

}  // namespace gridtopo::topology
