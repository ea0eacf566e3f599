#include "gridtopo/session/live_topology.h"

#include <sched.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <stdexcept>

#include "gridtopo/mapping/topology_builder.h"
#include "gridtopo/slam/map_export.h"

namespace gridtopo::session {

namespace {
// Thrown from the pipeline's progress callback to abandon a computation; not a std::exception, so nothing on the
// way treats it as an input error.
struct Cancelled {};
}  // namespace

std::string liveTopologyCaption(const LiveTopologyResult& r) {
  std::string text = "topology of scan " + std::to_string(r.scans_fed) + " (" + std::to_string(r.steps) + " updates): ";
  if (!r.data) return text + r.error;
  return text + std::to_string(r.data->topo.graph.nodes.size()) + " regions, " +
         std::to_string(r.data->topo.graph.edges.size()) + " edges";
}

struct LiveTopology::Queue {
  struct Request {
    slam::GridMap map;
    std::size_t steps = 0, scans_fed = 0;
    std::vector<cv::Point2d> path;
  };
  mutable std::mutex mu;
  mutable std::condition_variable cv;
  std::optional<Request> pending;
  bool busy = false, quit = false;
  std::atomic<bool> cancel{false};
  std::size_t last_steps = 0, requests = 0, dropped = 0, computed = 0;
  std::uint64_t sequence = 0;
  std::shared_ptr<const LiveTopologyResult> latest;

  void request(const slam::GridMap& map, std::size_t steps, std::size_t scans_fed, std::vector<cv::Point2d> path) {
    {
      std::lock_guard<std::mutex> lk(mu);
      if (quit || steps == last_steps) return;
      last_steps = steps;
      ++requests;
      if (pending) ++dropped;
      pending = Request{map, steps, scans_fed, std::move(path)};  // shares the tiles
    }
    cv.notify_all();
  }
};

LiveTopology::LiveTopology(std::shared_ptr<const places::PlacesModel> model, const topology::TopologyOptions& options,
                           std::function<void(std::shared_ptr<const LiveTopologyResult>)> on_result)
    : model_(std::move(model)), options_(options), on_result_(std::move(on_result)), queue_(std::make_shared<Queue>()) {
  if (!model_) throw std::invalid_argument("LiveTopology: a place model is required");
  worker_ = std::thread([this] { run(); });
}

LiveTopology::~LiveTopology() {
  {
    std::lock_guard<std::mutex> lk(queue_->mu);
    queue_->quit = true;
    queue_->pending.reset();
  }
  queue_->cancel = true;
  queue_->cv.notify_all();
  if (worker_.joinable()) worker_.join();
}

void LiveTopology::request(const slam::GridMap& best_map, std::size_t steps, std::size_t scans_fed,
                           std::vector<cv::Point2d> path) {
  queue_->request(best_map, steps, scans_fed, std::move(path));
}

SlamRunner::BestMapListener LiveTopology::listener() const {
  std::weak_ptr<Queue> weak = queue_;
  return [weak](const slam::GridMap& map, std::size_t steps, std::size_t scans_fed, std::vector<cv::Point2d> path) {
    if (const auto q = weak.lock()) q->request(map, steps, scans_fed, std::move(path));
  };
}

std::shared_ptr<const LiveTopologyResult> LiveTopology::latest() const {
  std::lock_guard<std::mutex> lk(queue_->mu);
  return queue_->latest;
}

bool LiveTopology::waitIdle(std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lk(queue_->mu);
  return queue_->cv.wait_for(lk, timeout, [&] { return !queue_->pending && !queue_->busy; });
}

bool LiveTopology::busy() const {
  std::lock_guard<std::mutex> lk(queue_->mu);
  return queue_->busy;
}

std::size_t LiveTopology::requests() const {
  std::lock_guard<std::mutex> lk(queue_->mu);
  return queue_->requests;
}

std::size_t LiveTopology::dropped() const {
  std::lock_guard<std::mutex> lk(queue_->mu);
  return queue_->dropped;
}

std::size_t LiveTopology::computed() const {
  std::lock_guard<std::mutex> lk(queue_->mu);
  return queue_->computed;
}

void LiveTopology::run() {
  // Below the SLAM worker: Linux schedules this thread (and the pipeline's threads, started from it, inherit the
  // policy) only on CPU time no normal thread wants.
  const sched_param idle{};
  ::sched_setscheduler(static_cast<pid_t>(::syscall(SYS_gettid)), SCHED_IDLE, &idle);
  Queue& q = *queue_;
  for (;;) {
    Queue::Request req;
    {
      std::unique_lock<std::mutex> lk(q.mu);
      q.cv.wait(lk, [&] { return q.quit || q.pending; });
      if (q.quit) return;
      req = std::move(*q.pending);
      q.pending.reset();
      q.busy = true;
    }
    auto result = std::make_shared<LiveTopologyResult>();
    result->steps = req.steps;
    result->scans_fed = req.scans_fed;
    const auto t0 = std::chrono::steady_clock::now();
    bool cancelled = false;
    try {
      // The builder's update step on the map as the SLAM saves it (slam::toOccupancyGrid).
      const mrpt::maps::COccupancyGridMap2D grid = slam::toOccupancyGrid(req.map);
      req.map = slam::GridMap();  // release the shared tiles early: the filter copies fewer on write
      mapping::MapTopology t = mapping::topologyOfBuiltMap(
          grid, static_cast<unsigned>(req.steps), *model_, options_,
          [&q](const std::string& stage, std::size_t, std::size_t) {
            // Safe points only: the scan simulation reports from inside its thread pool.
            if (stage != "scans" && q.cancel) throw Cancelled{};
          },
          std::move(req.path));
      auto data = std::make_shared<TopologyData>();
      data->map = mapLayerFromImage(t.map);
      data->occ = std::move(t.occ);
      data->has_labelling = true;
      data->model = model_;
      data->labelling = std::move(t.labelling);
      data->topo = std::move(t.topo);
      result->seconds = data->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      result->data = std::move(data);
    } catch (const Cancelled&) {
      cancelled = true;
    } catch (const std::exception& e) {
      result->error = e.what();
      result->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    if (!cancelled) {
      {
        std::lock_guard<std::mutex> lk(q.mu);
        result->sequence = ++q.sequence;
        ++q.computed;
        q.latest = result;
      }
      if (on_result_) on_result_(result);  // before idle: waitIdle() returns after it
    }
    {
      std::lock_guard<std::mutex> lk(q.mu);
      q.busy = false;
    }
    q.cv.notify_all();
  }
}

}  // namespace gridtopo::session
