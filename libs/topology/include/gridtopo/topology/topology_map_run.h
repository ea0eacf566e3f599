#pragma once
// gridtopo-topology's run of one map file: the place model and the map read, the topology computed
// (topologyOfMap) with a progress bar, the output set written with the run's loadable INI, and the run's summary.
#include <ostream>

#include "gridtopo/topology/topology_run_ini.h"

namespace gridtopo::topology {

/// Runs `spec`: loads spec.model and spec.map (a warning on `log` when the map's resolution is far coarser than the
/// model's lattice), computes the topology with a progress bar on stderr (none when `quiet`), writes the outputs to
/// spec.output with topologyRunIni(spec) as options.ini, and ends with runSummary on `log`.
void runTopologyOnMapFile(const TopologyRunSpec& spec, bool quiet, std::ostream& log);

}  // namespace gridtopo::topology
