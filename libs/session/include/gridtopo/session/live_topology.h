#pragma once
// The live topology of a SLAM run (issue 14): the semantic and topological map of the SLAM's current best map,
// recomputed on a thread of its own while the filter runs. A SlamRunner hands it the best particle's map every
// `[topology_builder] update_every` processed scans and when the run pauses or ends (SlamRunner::
// setBestMapListener); the map is copy-on-write, so taking it costs the filter nothing but a few pointer copies.
// At most one computation is in flight: a request that arrives meanwhile replaces the one waiting, so intermediate
// maps are dropped when the topology is slower than the SLAM, and the last map is always computed. The
// computation is the topology map builder's update step (mapping::topologyOfBuiltMap, the call gridtopo-map's
// CMetricMapBuilderTopology makes), so the result for a given scan count is the same whatever the timing. Each
// result is published as an immutable snapshot. The thread runs under Linux's SCHED_IDLE policy, so on a machine
// with few cores the SLAM keeps its pace and the topology takes the idle time.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "gridtopo/places/model.h"
#include "gridtopo/session/slam_runner.h"
#include "gridtopo/session/topology_state.h"
#include "gridtopo/slam/grid_map.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::session {

/// One computed live topology (immutable once published).
struct LiveTopologyResult {
  std::uint64_t sequence = 0;  ///< 1 for the first result, then +1 per result
  std::size_t steps = 0;       ///< the filter's processed scans in the map it was computed on
  std::size_t scans_fed = 0;   ///< the scans of the log fed to the filter by then (the last one is scan scans_fed)
  /// The labels, regions and graph, with the map they are aligned with (TopologyData::map, a SLAM grid of `steps`
  /// scans); null when the computation failed.
  std::shared_ptr<const TopologyData> data;
  std::string error;     ///< why it failed (e.g. "the map has no free cell" early in a run); empty on success
  double seconds = 0.0;  ///< wall time of the computation
};

/// What the views say about a result: "topology of scan 1234 (500 updates): 12 regions, 15 edges", or the error.
std::string liveTopologyCaption(const LiveTopologyResult& r);

class LiveTopology {
 public:

  /// Throws std::invalid_argument without a model. `on_result` (optional) is called on the topology thread after
  /// each result is published.
  LiveTopology(std::shared_ptr<const places::PlacesModel> model, const topology::TopologyOptions& options,
               std::function<void(std::shared_ptr<const LiveTopologyResult>)> on_result = {});
  /// Drops the waiting request, cancels the computation in flight at its next safe point (after the scan
  /// simulation, before the features' classification, before the regions) and joins the thread.
  ~LiveTopology();
  LiveTopology(const LiveTopology&) = delete;
  LiveTopology& operator=(const LiveTopology&) = delete;

  /// Asks for the topology of `best_map` after `steps` processed scans, `scans_fed` scans of the log (any thread;
  /// cheap: the map's tiles are shared). Replaces a request that is still waiting; ignored for the `steps` of the
  /// last request.
  /// `path`: where the robot was (world metres; the map preparation weighs it), empty when unknown.
  void request(const slam::GridMap& best_map, std::size_t steps, std::size_t scans_fed,
               std::vector<cv::Point2d> path = {});
  /// A listener for SlamRunner::setBestMapListener that makes requests. It holds the LiveTopology weakly: called
  /// after the LiveTopology is gone, it does nothing.
  SlamRunner::BestMapListener listener() const;

  /// The last result (null before the first).
  std::shared_ptr<const LiveTopologyResult> latest() const;
  /// Blocks until no request waits and none is computed, or `timeout` passes. True if so.
  bool waitIdle(std::chrono::milliseconds timeout = std::chrono::milliseconds(600000)) const;
  /// True while a computation runs.
  bool busy() const;
  /// Requests made, requests replaced before they were computed, computations finished (with or without error).
  std::size_t requests() const;
  std::size_t dropped() const;
  std::size_t computed() const;

 private:
  struct Queue;  // shared with the listeners (weakly)
  void run();

  std::shared_ptr<const places::PlacesModel> model_;
  topology::TopologyOptions options_;
  std::function<void(std::shared_ptr<const LiveTopologyResult>)> on_result_;
  std::shared_ptr<Queue> queue_;
  std::thread worker_;
};

}  // namespace gridtopo::session
