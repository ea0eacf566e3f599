#pragma once
// Everything gridtopo-gui shows, with no GUI types: the open log, map, trajectories, ground-truth relations,
// the SLAM run and its snapshots, the topology result, the label canvas and the selection. Every open*()
// reads into temporaries first and only then replaces the current content, so a bad file (reported by the
// reader as gridtopo::InputError "file:line: field: message") leaves the session exactly as it was.
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gridtopo/eval/relations.h"
#include "gridtopo/eval/relations_metric.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/core/scan_record.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/places/model.h"
#include "gridtopo/mapping/topology_builder_options.h"
#include "gridtopo/session/label_canvas.h"
#include "gridtopo/session/live_topology.h"
#include "gridtopo/session/map_layer.h"
#include "gridtopo/session/option_table.h"
#include "gridtopo/session/render.h"
#include "gridtopo/session/slam_runner.h"
#include "gridtopo/session/topology_state.h"
#include "gridtopo/slam/slam_options.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/topology/topology_run_ini.h"

namespace gridtopo::session {

/// The place model shipped with the project, relative to its data folder (datasets/ in the source tree).
inline constexpr const char* kDefaultModel = topology::kShippedPlacesModel;

enum class FileKind { Unknown, Log, Map, Trajectory, Relations, Topology, Model, SlamIni, TopologyIni };
const char* toString(FileKind k);
/// Kind of a file from its name, and from its first bytes where names are ambiguous (.yml/.yaml: ROS map vs
/// OpenCV model; .txt: trajectory; .gz: log vs relations).
FileKind classifyFile(const std::string& path);
/// A plain image (.png/.pgm/.jpg) with no ROS .yaml beside it: the user must give its resolution.
bool mapNeedsResolution(const std::string& path);

enum class ViewMode { Slam, Topology, Labels };

struct Layers {
  bool map = true;
  bool particles = true;
  bool particle_paths = false;  ///< every particle's trajectory (through the shared tree)
  bool best_path = true;        ///< the best particle's corrected path
  bool odometry = true;         ///< odometry-only path, aligned at the start
  bool scan = true;             ///< the current scan in the world
  bool trajectories = true;     ///< trajectory files opened by the user
  bool labels = true;            ///< place labels (topology view; SLAM view: the live topology's)
  LabelStage stage = LabelStage::Corrected;
  bool region_ids = true;
  bool graph = true;             ///< the topological graph (topology view; SLAM view: the live topology's)
  bool closures = true;         ///< the loop closure's edges (accepted, and rejected ones dashed)
  /// Once the loop closure has closed a loop, the map at the optimised poses (SlamSnapshot::optimised_map) instead
  /// of the best particle's: the map after and before the optimisation.
  bool optimised_map = true;
  bool inspection = true;       ///< simulated scan of the inspected cell, highlighted particle path
  bool scale_bar = true;
};

struct NamedTrajectory {
  std::string path;
  std::vector<TimedPose> poses;
};

struct Selection {
  enum class Kind { None, Cell, Node, Particle } kind = Kind::None;
  std::optional<CellInspection> cell;
  std::optional<NodeInspection> node;
  int particle = -1;
  double particle_weight = 0;
  slam::Pose2 particle_pose;
  std::vector<cv::Point2d> particle_path;  ///< world points of the selected particle's trajectory
  std::string text;                        ///< what the inspector panel shows
};

class Session {
 public:
  Session();
  ~Session();

  // ---- files (strong guarantee: on exception nothing changes)
  /// Opens by kind (classifyFile). Maps use `map_options` (resolution/origin for plain images).
  FileKind open(const std::string& path, const io::MapReadOptions& map_options = {});
  void openLog(const std::string& path, std::size_t max_scans = 0);
  void openMap(const std::string& path, const io::MapReadOptions& options = {});
  void openTrajectory(const std::string& path);
  void openRelations(const std::string& path);
  void openTopology(const std::string& path);  ///< needs the map it was computed on to be open for labels
  void openModel(const std::string& path);
  /// Opens the place model the project ships (kDefaultModel) from the first folder of gridtopo::dataDirs() that
  /// has it ($GRIDTOPO_DATA_DIR, beside the executable, `build_time_data_dir` last). Returns its path, or "" with
  /// nothing changed when none has it; a model that cannot be read throws as openModel does.
  std::string openDefaultModel(const std::string& build_time_data_dir = "");
  void openSlamIni(const std::string& path, const std::string& section = "slam");
  void openTopologyIni(const std::string& path);
  void openLabelImage(const std::string& path);  ///< into the label canvas (starts one on the current map)
  /// Replaces the map by a `cols` x `rows` tiling of itself (the frame-rate benchmark's big map).
  void tileMap(int cols, int rows);

  // ---- what is open
  const MapLayer& map() const { return map_; }
  bool hasLog() const { return scans_ != nullptr; }
  const std::vector<ScanRecord>& scans() const { return *scans_; }
  const std::string& logPath() const { return log_path_; }
  /// What the reader decided against the open log's word (CARMEN: units of PARAMs, contradicted max range, ...).
  const std::vector<std::string>& logWarnings() const { return log_warnings_; }
  const std::vector<NamedTrajectory>& trajectories() const { return trajectories_; }
  const std::vector<eval::Relation>& relations() const { return relations_; }
  const std::string& relationsPath() const { return relations_path_; }
  const std::shared_ptr<const places::PlacesModel>& model() const { return model_; }
  const std::string& modelPath() const { return model_path_; }
  /// Which model is loaded: "place model: PATH" (" (default)" after openDefaultModel), or "no place model".
  std::string modelDescription() const;

  // ---- SLAM
  slam::SlamOptions& slamOptions() { return slam_options_; }
  const std::string& slamIniPath() const { return slam_ini_path_; }
  /// The options as a property-grid table, sections [slam] and [loop_closure] (from slam::slamOptionSchema and
  /// slam::loopClosureOptionSchema: type, default, range, unit, help).
  OptionTable slamOptionTable() const;
  /// Applies an edited table (validated; throws InputError naming the key, options unchanged on error).
  void setSlamOptions(const OptionTable& table);
  /// Starts a new run on the open log (paused). Throws if no log is open or the options are invalid.
  void startSlam(const RunnerOptions& options = {});
  SlamRunner* runner() { return runner_.get(); }
  const SlamRunner* runner() const { return runner_.get(); }
  void stopSlam();
  /// Odometry-only path of the scans fed so far, aligned with the filter's first pose.
  std::vector<cv::Point2d> odometryPath(const SlamSnapshot& s) const;
  /// Relations error of the snapshot's trajectory (cached per trajectory); nullopt without relations.
  std::optional<eval::RelationsResult> relationsError(const SlamSnapshot& s);
  /// Writes map.png, map.pgm + map.yaml, map.gridmap.gz, map.simplemap, trajectory.txt, stats.txt, options.ini
  /// of the run so far (it must be paused or over), through the SlamRun gridtopo-slam uses; options.ini is the
  /// RUN.ini (slam::slamRunIni) that reruns the scans fed so far with `gridtopo-slam OUT/options.ini`.
  void saveSlamOutputs(const std::string& dir);
  /// Makes the SLAM's current map the session map (for the topology view and the label painter), through the same
  /// conversion as the saved map (slam::toOccupancyGrid + io::gridToImage): the best particle's, or once the loop
  /// closure has closed a loop the optimised one (SlamSnapshot::resultMap, as saveSlamOutputs writes it).
  void useSlamMap();

  // ---- live topology: the labels and the graph of the SLAM's best map while it grows (issue 14)
  /// Turns it on or off. On: the current run (and every run started later) hands its best map to a LiveTopology
  /// every `schedule.update_every` processed scans (0: only when the run pauses or ends), which computes it on its
  /// own thread with the session's model and topology options as they are now (mapping::topologyOfBuiltMap, as
  /// gridtopo-map); a paused run's current map is requested at once. Throws std::runtime_error when turning it on
  /// without a place model (nothing changes then).
  void setLiveTopology(bool on, const mapping::TopologyBuilderOptions& schedule = {});
  bool liveTopologyOn() const { return live_on_; }
  const mapping::TopologyBuilderOptions& liveTopologySchedule() const { return live_schedule_; }
  /// The live topology of the current run (null when off or without a run).
  const LiveTopology* liveTopology() const { return live_.get(); }
  /// Its last result (null when none yet).
  std::shared_ptr<const LiveTopologyResult> liveTopologyResult() const;

  // ---- topology
  topology::TopologyOptions& topologyOptions() { return topology_options_; }
  /// The topology options ([topology], [relaxation], [correction]) as a property-grid table, from their key tables.
  OptionTable topologyOptionTable() const;
  /// Applies an edited table (validated; throws InputError naming the section and key, options unchanged on error);
  /// the next topology computation (runTopology, the GUI's Topology > Run) uses them.
  void setTopologyOptions(const OptionTable& table);
  const TopologyData* topology() const { return topology_.get(); }
  void setTopology(TopologyData t);
  /// Synchronous labelling + topology of the current map with the current model (the GUI runs it in a thread
  /// on copies: see computeTopology()).
  void runTopology();

  // ---- label painting
  LabelCanvas& canvas() { return canvas_; }
  const LabelCanvas& canvas() const { return canvas_; }
  /// Starts a blank canvas on the current map (throws if none).
  void startLabelling();

  // ---- selection (world coordinates; `radius_m` is the pick tolerance for particles and nodes)
  const Selection& select(ViewMode mode, double x, double y, double radius_m);
  const Selection& selection() const { return selection_; }
  void clearSelection() { selection_ = {}; }
  /// Hover text: world coordinates and the occupancy of the cell under (x, y).
  std::string hoverText(ViewMode mode, double x, double y) const;

  // ---- view
  /// Draws the view of `mode` into `screen` (BGR, its size is the window's).
  void render(cv::Mat& screen, ViewMode mode, const ViewTransform& v, const Layers& layers);
  /// World bounding box of what `mode` shows (for fit-to-map); false when there is nothing.
  bool bounds(ViewMode mode, double& xmin, double& ymin, double& xmax, double& ymax) const;
  /// While the SLAM runs, the map image is rebuilt at most this often (s); particles, paths and the scan are
  /// drawn from every snapshot. Keeps the GUI's share of the CPU small on 2-core machines.
  double live_map_interval = 0.25;
  /// Latest SLAM snapshot (null without a run).
  std::shared_ptr<const SlamSnapshot> slamSnapshot() const;

 private:
  const MapLayer& labelsMap() const;

  MapLayer map_;
  std::shared_ptr<const std::vector<ScanRecord>> scans_;
  std::string log_path_;
  std::vector<std::string> log_warnings_;
  std::vector<NamedTrajectory> trajectories_;
  std::vector<eval::Relation> relations_;
  std::string relations_path_;
  std::shared_ptr<const places::PlacesModel> model_;
  std::string model_path_;
  bool model_is_default_ = false;
  slam::SlamOptions slam_options_;
  std::string slam_ini_path_;
  topology::TopologyOptions topology_options_;
  std::unique_ptr<SlamRunner> runner_;
  void attachLiveTopology();  // a new LiveTopology on runner_ (live_on_ and runner_ set)
  bool live_on_ = false;
  mapping::TopologyBuilderOptions live_schedule_;
  std::unique_ptr<LiveTopology> live_;
  std::unique_ptr<TopologyData> topology_;
  LabelCanvas canvas_;
  Selection selection_;

  // caches
  std::uint64_t relations_cache_key_ = ~0ull;
  std::optional<eval::RelationsResult> relations_cache_;
  std::uint64_t slam_raster_version_ = ~0ull;
  bool slam_raster_optimised_ = false;  ///< slam_raster_ shows the snapshot's optimised map
  MapRaster slam_raster_;
  std::chrono::steady_clock::time_point slam_raster_time_{};
  MapLayer slam_layer_;
  std::uint64_t live_raster_sequence_ = 0;
  int live_raster_key_ = -1;
  MapRaster live_raster_;
  int topo_raster_key_ = -1;
  std::uint64_t topo_generation_ = 0, map_generation_ = 0;
  MapRaster topo_raster_, map_raster_, label_raster_;
  std::uint64_t map_raster_generation_ = ~0ull, label_raster_generation_ = ~0ull, label_generation_ = 0;
  std::uint64_t topo_raster_generation_ = ~0ull;

 public:
  /// Call after modifying the canvas so the view redraws it.
  void canvasChanged() { ++label_generation_; }
};

}  // namespace gridtopo::session
