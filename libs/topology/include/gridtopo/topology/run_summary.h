#pragma once
// What gridtopo-topology prints about a run: a warning when the map is coarser than the model's lattice, and the
// one-line summary (cells, classified samples, relaxation, node counts, edges, segments, times).
#include <string>

#include "gridtopo/places/model.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::topology {

/// "warning: map resolution ..." (with its newline) when `resolution` is more than 1.5 times the model's lattice
/// spacing, else "".
std::string resolutionWarning(double resolution, const places::PlacesModel& model);

/// "SOURCE: COLSxROWS cells, N classified, relaxation I iterations; R rooms, C corridors, D doorways, E edges,
/// S segments; T s (prepare ..., scans ..., features ..., classify ..., relax ..., graph ...), peak RSS P MB" with
/// its newline (T the caller's `seconds`, the steps' seconds from `run`, P the process's peak resident memory so far).
std::string runSummary(const MapTopology& run, const std::string& source, double seconds);

}  // namespace gridtopo::topology
