#include "gridtopo/session/session.h"

#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <unordered_set>

#include "gridtopo/core/data_dir.h"
#include "gridtopo/core/error.h"
#include "gridtopo/eval/odometry_track.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/slam_run_ini.h"
#include "gridtopo/session/topology_drawing.h"
#include "gridtopo/topology/topology_run_ini.h"

namespace gridtopo::session {

namespace fs = std::filesystem;

const char* toString(FileKind k) {
  switch (k) {
    case FileKind::Unknown: return "unknown";
    case FileKind::Log: return "log";
    case FileKind::Map: return "map";
    case FileKind::Trajectory: return "trajectory";
    case FileKind::Relations: return "relations";
    case FileKind::Topology: return "topology";
    case FileKind::Model: return "model";
    case FileKind::SlamIni: return "SLAM INI";
    case FileKind::TopologyIni: return "topology INI";
  }
  return "?";
}

namespace {
bool endsWith(const std::string& s, const std::string& e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}
std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
std::string head(const std::string& path, std::size_t n = 4096) {
  std::ifstream in(path, std::ios::binary);
  std::string s(n, '\0');
  in.read(&s[0], static_cast<std::streamsize>(n));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}
slam::Pose2 toPose2(const mrpt::math::TPose2D& p) { return {p.x, p.y, p.phi}; }
}  // namespace

FileKind classifyFile(const std::string& path) {
  const std::string l = lower(fs::path(path).filename().string());
  if (endsWith(l, ".rawlog")) return FileKind::Log;
  if (endsWith(l, ".gridmap") || endsWith(l, ".gridmap.gz")) return FileKind::Map;
  if (endsWith(l, ".relations") || endsWith(l, ".relations.gz")) return FileKind::Relations;
  for (const char* e : {".clf", ".clf.gz", ".log", ".log.gz"})
    if (endsWith(l, e)) return FileKind::Log;
  for (const char* e : {".png", ".pgm", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff"})
    if (endsWith(l, e)) return FileKind::Map;
  if (endsWith(l, ".yaml") || endsWith(l, ".yml")) {
    const std::string h = head(path);
    if (h.find("gridtopo-places-model") != std::string::npos) return FileKind::Model;
    if (h.find("image:") != std::string::npos) return FileKind::Map;
    return FileKind::Unknown;
  }
  if (endsWith(l, ".json")) {
    const std::string h = head(path);
    if (h.find("gridtopo-places-model") != std::string::npos) return FileKind::Model;
    return FileKind::Topology;
  }
  if (endsWith(l, ".graphml")) return FileKind::Topology;
  if (endsWith(l, ".ini") || endsWith(l, ".cfg")) {
    const std::string h = head(path, 1 << 16);
    if (h.find("[slam]") != std::string::npos) return FileKind::SlamIni;
    if (h.find("[topology]") != std::string::npos || h.find("[correction]") != std::string::npos)
      return FileKind::TopologyIni;
    return FileKind::SlamIni;
  }
  if (endsWith(l, ".txt") || endsWith(l, ".traj") || endsWith(l, ".trajectory")) return FileKind::Trajectory;
  if (endsWith(l, ".gz")) return FileKind::Log;
  return FileKind::Unknown;
}

bool mapNeedsResolution(const std::string& path) {
  const std::string l = lower(path);
  bool image = false;
  for (const char* e : {".png", ".pgm", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff"}) image = image || endsWith(l, e);
  if (!image) return false;
  for (const char* e : {".yaml", ".yml"})
    if (fs::is_regular_file(fs::path(path).replace_extension(e))) return false;
  return true;
}

Session::Session() = default;
Session::~Session() = default;

FileKind Session::open(const std::string& path, const io::MapReadOptions& map_options) {
  if (!fs::exists(path)) throw InputError(path, "no such file");
  if (fs::is_directory(path)) {
    // A gridtopo-topology output directory.
    if (fs::is_regular_file(fs::path(path) / "topology.json")) {
      openTopology((fs::path(path) / "topology.json").string());
      return FileKind::Topology;
    }
    throw InputError(path, "is a directory");
  }
  const FileKind k = classifyFile(path);
  switch (k) {
    case FileKind::Log: openLog(path); break;
    case FileKind::Map: openMap(path, map_options); break;
    case FileKind::Trajectory: openTrajectory(path); break;
    case FileKind::Relations: openRelations(path); break;
    case FileKind::Topology: openTopology(path); break;
    case FileKind::Model: openModel(path); break;
    case FileKind::SlamIni: openSlamIni(path); break;
    case FileKind::TopologyIni: openTopologyIni(path); break;
    case FileKind::Unknown:
      throw InputError(path, "unknown file type (expected a log .clf/.log/.gz/.rawlog, a map .png/.pgm/.yaml/"
                             ".gridmap(.gz), a trajectory .txt, .relations, topology .json/.graphml, a model or an INI)");
  }
  return k;
}

void Session::openLog(const std::string& path, std::size_t max_scans) {
  io::ScanLogInfo info;
  auto scans = io::readScanLog(path, {}, info);
  if (max_scans && scans.size() > max_scans) scans.resize(max_scans);
  if (scans.empty()) throw InputError(path, "the log holds no laser scans");
  runner_.reset();
  live_.reset();
  log_warnings_ = std::move(info.warnings);
  scans_ = std::make_shared<const std::vector<ScanRecord>>(std::move(scans));
  log_path_ = path;
  relations_cache_key_ = ~0ull;
  slam_raster_version_ = ~0ull;
}

void Session::openMap(const std::string& path, const io::MapReadOptions& options) {
  MapLayer m = mapLayerFromImage(io::readMap(path, options));
  if (m.empty()) throw InputError(path, "the map is empty");
  map_ = std::move(m);
  ++map_generation_;
  topology_.reset();
  ++topo_generation_;
  canvas_ = LabelCanvas();
  ++label_generation_;
  selection_ = {};
}

void Session::openTrajectory(const std::string& path) {
  auto poses = io::readTrajectory(path);
  if (poses.empty()) throw InputError(path, "the trajectory has no pose");
  trajectories_.push_back({path, std::move(poses)});
}

void Session::openRelations(const std::string& path) {
  auto r = eval::readRelations(path);
  if (r.empty()) throw InputError(path, "no relation in the file");
  relations_ = std::move(r);
  relations_path_ = path;
  relations_cache_key_ = ~0ull;
}

void Session::openTopology(const std::string& path) {
  TopologyData t = loadTopologyOutput(path, map_, topology_options_);
  setTopology(std::move(t));
}

void Session::openModel(const std::string& path) {
  model_ = std::make_shared<const places::PlacesModel>(places::PlacesModel::load(path));
  model_path_ = path;
  model_is_default_ = false;
}

std::string Session::openDefaultModel(const std::string& build_time_data_dir) {
  const std::string path = findDataFile(kDefaultModel, build_time_data_dir);
  if (path.empty()) return path;
  openModel(path);
  model_is_default_ = true;
  return path;
}

std::string Session::modelDescription() const {
  if (!model_) return "no place model";
  return "place model: " + model_path_ + (model_is_default_ ? " (default)" : "");
}

// The GUI reads option INIs as strictly as the apps' -c (IniFile: unknown sections and keys refused with file,
// line and a "did you mean"; non-text files refused; the section required).
void Session::openSlamIni(const std::string& path, const std::string& section) {
  slam_options_ = slam::loadSlamOptionsIni(path, section);
  slam_ini_path_ = path;
}

void Session::openTopologyIni(const std::string& path) {
  topology_options_ = topology::loadTopologyOptionsIni(path);  // "" gives the defaults
}

void Session::openLabelImage(const std::string& path) {
  if (map_.empty()) throw InputError(path, "open the map the labels were painted on first");
  LabelCanvas c;
  c.reset(map_.grey, topology_options_.freeThresholdFor(map_.kind));
  c.load(path);
  canvas_ = std::move(c);
  ++label_generation_;
}

void Session::tileMap(int cols, int rows) {
  if (map_.empty()) throw std::runtime_error("open a map first");
  map_ = tiledMap(map_, cols, rows);
  ++map_generation_;
  topology_.reset();
  ++topo_generation_;
  canvas_ = LabelCanvas();
  ++label_generation_;
}

// ---------------------------------------------------------------- SLAM

OptionTable Session::slamOptionTable() const {
  // [loop_closure] too: setSlamOptions rebuilds the options from the table alone, so a section left out of it would
  // fall back to its defaults at the next run (the loop closure of a loaded INI silently off).
  return OptionTable::fromSections(
      {{"slam", slam::slamOptionSchema().describe(slam_options_)},
       {"loop_closure", slam::loopClosureOptionSchema().describe(slam_options_.loop_closure)}});
}

void Session::setSlamOptions(const OptionTable& table) {
  slam::SlamOptions o;
  table.applyTo(o, "slam");
  slam_options_ = o;
}

void Session::startSlam(const RunnerOptions& options) {
  if (!scans_) throw InputError("<log>", "open a log first");
  runner_.reset();
  live_.reset();
  runner_ = std::make_unique<SlamRunner>(scans_, slam_options_, options);
  if (live_on_) attachLiveTopology();
  slam_raster_version_ = ~0ull;
  relations_cache_key_ = ~0ull;
  selection_ = {};
}

void Session::stopSlam() {
  if (runner_) runner_->stop();
}

void Session::setLiveTopology(bool on, const mapping::TopologyBuilderOptions& schedule) {
  if (on && !model_) throw std::runtime_error("live topology needs a place model (Topology > Open place model)");
  if (runner_) runner_->setBestMapListener(0, {});
  live_.reset();
  live_on_ = on;
  live_schedule_ = schedule;
  if (live_on_ && runner_) attachLiveTopology();
}

namespace {
std::vector<cv::Point2d> pathOfPoses(const std::vector<TimedPose>& poses) {
  std::vector<cv::Point2d> path;
  path.reserve(poses.size());
  for (const TimedPose& p : poses) path.emplace_back(p.pose.x, p.pose.y);
  return path;
}
}  // namespace

void Session::attachLiveTopology() {
  live_ = std::make_unique<LiveTopology>(model_, topology_options_);
  runner_->setBestMapListener(live_schedule_.update_every, live_->listener());
  // Turned on while the run is paused: the map it holds now.
  const auto s = runner_->snapshot();
  // The listener's map: the run's result at the end of the log, the best particle's before.
  if (s && s->state != RunState::Running && s->steps > 0)
    live_->request(s->scans_fed == s->scans_total ? s->resultMap() : s->best_map, s->steps, s->scans_fed,
                   pathOfPoses(s->trajectory));
}

std::shared_ptr<const LiveTopologyResult> Session::liveTopologyResult() const {
  return live_ ? live_->latest() : nullptr;
}

std::shared_ptr<const SlamSnapshot> Session::slamSnapshot() const {
  return runner_ ? runner_->snapshot() : nullptr;
}

std::vector<cv::Point2d> Session::odometryPath(const SlamSnapshot& s) const {
  std::vector<cv::Point2d> out;
  if (!scans_ || s.particles.empty() || s.scans_fed == 0) return out;
  // The filter's first pose (root of the best particle's path) is the odometry of the first scan it processed.
  const slam::TrajectoryNode* root = s.particles[s.best].node.get();
  if (!root) return out;
  while (root->parent) root = root->parent.get();
  const auto& sc = *scans_;
  if (root->scan_index >= sc.size() || !sc[root->scan_index].has_odometry) return out;
  const slam::Pose2 o0 = toPose2(sc[root->scan_index].odometry);
  out.reserve(s.scans_fed);
  for (std::size_t i = 0; i < s.scans_fed && i < sc.size(); ++i) {
    if (!sc[i].has_odometry) continue;
    const slam::Pose2 p = slam::compose(root->pose, slam::relative(o0, toPose2(sc[i].odometry)));
    out.emplace_back(p.x, p.y);
  }
  return out;
}

std::optional<eval::RelationsResult> Session::relationsError(const SlamSnapshot& s) {
  if (relations_.empty() || s.trajectory.empty()) return std::nullopt;
  const std::uint64_t key = s.trajectory_scans;
  if (key == relations_cache_key_) return relations_cache_;
  relations_cache_key_ = key;
  relations_cache_.reset();
  // Only relations inside the part of the log already processed.
  const double t_end = s.trajectory.back().timestamp;
  std::vector<eval::Relation> rel;
  for (const auto& r : relations_)
    if (std::max(r.t1, r.t2) <= t_end) rel.push_back(r);
  if (rel.empty()) return std::nullopt;
  std::vector<TimedPose> odo;
  for (const auto& r : *scans_)
    if (r.has_odometry) odo.push_back({r.scan.timestamp, r.odometry});
  const eval::OdometryTrack track(std::move(odo));
  relations_cache_ = eval::evaluateRelations(s.trajectory, rel, track.empty() ? nullptr : &track);
  return relations_cache_;
}

void Session::saveSlamOutputs(const std::string& dir) {
  if (!runner_) throw std::runtime_error("no SLAM run to save");
  // An idle run's snapshot is the one that acknowledged the pause (or the end), so it counts the scans the run
  // has fed; saveOutputs refuses a running one.
  const auto s = slamSnapshot();
  // The files and formats of gridtopo-slam; options.ini is the RUN.ini that reruns the part of the log fed so far.
  slam::SlamRunSpec spec;
  spec.input = log_path_;
  spec.output = dir;
  spec.max_scans = s->scans_fed;
  spec.options = runner_->options();
  runner_->saveOutputs(dir,
                       {"gridtopo-gui " + log_path_,
                        "one pose per laser scan, best particle (" + std::to_string(s->scans_fed) + " scans)"},
                       slam::slamRunIni(spec));
}

void Session::useSlamMap() {
  const auto s = slamSnapshot();
  if (!s) throw std::runtime_error("no SLAM run");
  const auto grid = slam::toOccupancyGrid(s->resultMap());
  map_ = mapLayerFromGrid(grid, "<slam map, " + std::to_string(s->scans_fed) + " scans>",
                          MapKind::ProbabilisticGrid);
  ++map_generation_;
  topology_.reset();
  ++topo_generation_;
  canvas_ = LabelCanvas();
  ++label_generation_;
}

// ---------------------------------------------------------------- topology, labels

void Session::setTopology(TopologyData t) {
  topology_ = std::make_unique<TopologyData>(std::move(t));
  ++topo_generation_;
  selection_ = {};
}

OptionTable Session::topologyOptionTable() const {
  return OptionTable::fromSections(topology::describeTopologyOptions(topology_options_));
}

void Session::setTopologyOptions(const OptionTable& table) {
  topology::TopologyOptions o;
  table.applyTo(o, "topology");
  topology_options_ = o;
}

void Session::runTopology() { setTopology(computeTopology(map_, model_, topology_options_)); }

void Session::startLabelling() {
  if (map_.empty()) throw std::runtime_error("open a map first");
  canvas_.reset(map_.grey, topology_options_.freeThresholdFor(map_.kind));
  ++label_generation_;
}

const MapLayer& Session::labelsMap() const { return topology_ ? topology_->map : map_; }

// ---------------------------------------------------------------- selection

const Selection& Session::select(ViewMode mode, double x, double y, double radius_m) {
  Selection sel;
  std::ostringstream text;
  if (mode == ViewMode::Slam) {
    if (const auto s = slamSnapshot()) {
      int best = -1;
      double bd = radius_m;
      for (std::size_t i = 0; i < s->particles.size(); ++i) {
        const double d = std::hypot(s->particles[i].pose.x - x, s->particles[i].pose.y - y);
        if (d <= bd) bd = d, best = static_cast<int>(i);
      }
      if (best >= 0) {
        const auto& p = s->particles[static_cast<std::size_t>(best)];
        sel.kind = Selection::Kind::Particle;
        sel.particle = best;
        sel.particle_weight = p.weight;
        sel.particle_pose = p.pose;
        for (const auto* n : slam::pathOf(p.node)) sel.particle_path.emplace_back(n->pose.x, n->pose.y);
        text << "particle " << best << (static_cast<std::size_t>(best) == s->best ? " (best)" : "") << "\n"
             << "weight " << p.weight << " (log weight total " << p.log_weight_total << ")\n"
             << "pose x = " << p.pose.x << " m, y = " << p.pose.y << " m, theta = " << p.pose.theta * 180 / M_PI
             << " deg\n"
             << "trajectory: " << sel.particle_path.size() << " poses\n";
        sel.text = text.str();
        selection_ = std::move(sel);
        return selection_;
      }
    }
  }
  if (mode == ViewMode::Topology && topology_) {
    if (auto n = inspectNodeAt(*topology_, x, y, radius_m)) {
      sel.kind = Selection::Kind::Node;
      sel.text = n->text();
      sel.node = std::move(n);
      selection_ = std::move(sel);
      return selection_;
    }
    int row, col;
    if (topology_->map.worldToCell(x, y, row, col)) {
      sel.kind = Selection::Kind::Cell;
      sel.cell = inspectCell(*topology_, row, col);
      sel.text = sel.cell->text();
    }
    selection_ = std::move(sel);
    return selection_;
  }
  sel.text = hoverText(mode, x, y);
  if (mode == ViewMode::Labels && !canvas_.empty()) {
    int row, col;
    if (map_.worldToCell(x, y, row, col)) {
      const unsigned char c = canvas_.code(row, col);
      sel.text += "\npainted label: " + (places::labelFromCode(c) >= 0 ? places::labelName(places::labelFromCode(c))
                                                                        : std::string("none")) +
                  " (code " + std::to_string(c) + ")\n";
    }
  }
  if (!sel.text.empty()) sel.kind = Selection::Kind::Cell;
  selection_ = std::move(sel);
  return selection_;
}

std::string Session::hoverText(ViewMode mode, double x, double y) const {
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "x = " << x << " m, y = " << y << " m";
  const MapLayer* m = nullptr;
  if (mode == ViewMode::Slam && runner_) m = &slam_layer_;
  else if (mode == ViewMode::Topology && topology_) m = &topology_->map;
  else m = &map_;
  int row, col;
  if (m && !m->empty() && m->worldToCell(x, y, row, col)) {
    o << "  cell (" << col << ", " << row << ")  p(occupied) = " << std::setprecision(2) << m->occupancy(row, col);
    if (mode == ViewMode::Topology && topology_) {
      const cv::Mat& l = topology_->topo.labels;
      if (!l.empty() && l.at<unsigned char>(row, col) <= 2)
        o << "  " << places::labelName(l.at<unsigned char>(row, col));
    }
  }
  return o.str();
}

// ---------------------------------------------------------------- view

bool Session::bounds(ViewMode mode, double& xmin, double& ymin, double& xmax, double& ymax) const {
  const MapLayer* m = &map_;
  MapLayer tmp;
  if (mode == ViewMode::Slam && runner_) {
    if (const auto s = slamSnapshot()) {
      int x0, y0, x1, y1;
      s->best_map.cellBounds(x0, y0, x1, y1);
      if (s->optimised_map) {  // either map may be shown: both fit
        int ox0, oy0, ox1, oy1;
        s->optimised_map->cellBounds(ox0, oy0, ox1, oy1);
        if (ox1 > ox0)
          x0 = std::min(x0, ox0), y0 = std::min(y0, oy0), x1 = std::max(x1, ox1), y1 = std::max(y1, oy1);
      }
      if (x1 > x0) {
        const double r = s->best_map.resolution();
        xmin = x0 * r, ymin = y0 * r, xmax = x1 * r, ymax = y1 * r;
        return true;
      }
    }
  }
  if (mode == ViewMode::Topology && topology_) m = &topology_->map;
  if (m->empty()) {
    if (!trajectories_.empty()) {
      xmin = ymin = 1e300, xmax = ymax = -1e300;
      for (const auto& t : trajectories_)
        for (const auto& p : t.poses)
          xmin = std::min(xmin, p.pose.x), xmax = std::max(xmax, p.pose.x), ymin = std::min(ymin, p.pose.y),
          ymax = std::max(ymax, p.pose.y);
      return true;
    }
    return false;
  }
  xmin = m->origin_x, ymin = m->origin_y, xmax = m->origin_x + m->width_m(), ymax = m->origin_y + m->height_m();
  return true;
}

void Session::render(cv::Mat& screen, ViewMode mode, const ViewTransform& v, const Layers& layers) {
  screen.setTo(cv::Scalar(72, 72, 72));
  if (mode == ViewMode::Slam) {
    const auto s = slamSnapshot();
    if (s) {
      const auto now = std::chrono::steady_clock::now();
      const bool optimised = layers.optimised_map && s->optimised_map;
      // A switch between the two maps is drawn at once; a newer snapshot of the same map waits for live_map_interval.
      if ((s->version != slam_raster_version_ || optimised != slam_raster_optimised_) &&
          (s->state != RunState::Running || slam_raster_.empty() || optimised != slam_raster_optimised_ ||
           std::chrono::duration<double>(now - slam_raster_time_).count() >= live_map_interval)) {
        slam_raster_time_ = now;
        slam_layer_ = mapLayerFromSlam(optimised ? *s->optimised_map : s->best_map);
        slam_raster_.set(slam_layer_.empty() ? cv::Mat() : greyToBgr(slam_layer_.grey), slam_layer_);
        slam_raster_version_ = s->version;
        slam_raster_optimised_ = optimised;
      }
      if (layers.map) slam_raster_.draw(screen, v);
      // The live topology over the growing map: the labelled map of the scan it is of, then its graph.
      if (const auto live = liveTopologyResult()) {
        if (live->data) {
          const int key = 2 * static_cast<int>(layers.stage);
          if (layers.labels) {
            if (live->sequence != live_raster_sequence_ || key != live_raster_key_) {
              live_raster_.set(topologyImage(*live->data, layers.stage, true), live->data->map);
              live_raster_sequence_ = live->sequence;
              live_raster_key_ = key;
            }
            live_raster_.draw(screen, v);
          }
          drawTopologyGraph(screen, v, *live->data, layers.graph, layers.region_ids);
        }
        if (layers.labels || layers.graph)
          drawCaption(screen, liveTopologyCaption(*live));
      }
    } else if (layers.map && !map_.empty()) {
      if (map_raster_generation_ != map_generation_) {
        map_raster_.set(greyToBgr(map_.grey), map_);
        map_raster_generation_ = map_generation_;
      }
      map_raster_.draw(screen, v);
    }
    if (layers.trajectories) {
      const cv::Scalar colours[] = {{0, 140, 255}, {200, 0, 200}, {0, 200, 200}};
      for (std::size_t i = 0; i < trajectories_.size(); ++i) {
        std::vector<cv::Point2d> pts;
        for (const auto& p : trajectories_[i].poses) pts.emplace_back(p.pose.x, p.pose.y);
        drawPath(screen, v, pts, colours[i % 3], 1);
      }
    }
    if (s && !s->particles.empty()) {
      if (layers.odometry) drawPath(screen, v, odometryPath(*s), cv::Scalar(160, 120, 60), 1);
      if (layers.particle_paths) {
        // Each tree node once: walk every particle's path until a node already drawn.
        std::unordered_set<const slam::TrajectoryNode*> seen;
        for (const auto& p : s->particles) {
          std::vector<cv::Point2d> pts;
          for (const slam::TrajectoryNode* n = p.node.get(); n; n = n->parent.get()) {
            pts.emplace_back(n->pose.x, n->pose.y);
            if (!seen.insert(n).second) break;
          }
          drawPath(screen, v, pts, cv::Scalar(60, 170, 250), 1);
        }
      }
      if (layers.best_path) {
        std::vector<cv::Point2d> pts;
        for (const slam::TrajectoryNode* n = s->particles[s->best].node.get(); n; n = n->parent.get())
          pts.emplace_back(n->pose.x, n->pose.y);
        drawPath(screen, v, pts, cv::Scalar(0, 0, 230), 2);
      }
      if (layers.closures) {
        // Rejected ones first, so that an accepted closure between the same places stays on top.
        for (const bool rejected : {true, false})
          for (const auto& c : s->closures)
            if (c.rejected == rejected)
              drawClosure(screen, v, {c.submap.x, c.submap.y}, {c.newest.x, c.newest.y}, c.rejected, c.global);
      }
      if (layers.scan && s->scans_fed > 0 && runner_) {
        const auto& rec = runner_->scans()[s->last_scan];
        const slam::Pose2 sensor = slam::compose(s->last_scan_pose, toPose2(rec.scan.sensor_pose));
        for (std::size_t k = 0; k < rec.scan.size(); ++k) {
          if (!rec.scan.valid[k]) continue;
          const double a = sensor.theta + rec.scan.beamAngle(k), r = rec.scan.ranges[k];
          const cv::Point2d q = v.toScreen(sensor.x + r * std::cos(a), sensor.y + r * std::sin(a));
          cv::circle(screen, cv::Point(static_cast<int>(q.x), static_cast<int>(q.y)), 1, cv::Scalar(0, 200, 0),
                     cv::FILLED);
        }
      }
      if (layers.particles) {
        double wmax = 0;
        for (const auto& p : s->particles) wmax = std::max(wmax, p.weight);
        // The best particle as a red disc (radius 5), the others on top coloured by weight (blue light ..
        // magenta heavy, radius 3), so both stay visible when the cloud is tight.
        const auto& b = s->particles[s->best];
        drawPose(screen, v, b.pose.x, b.pose.y, b.pose.theta, cv::Scalar(0, 0, 255), 5);
        for (std::size_t i = 0; i < s->particles.size(); ++i) {
          if (i == s->best) continue;
          const auto& p = s->particles[i];
          const double f = wmax > 0 ? p.weight / wmax : 1;
          drawPose(screen, v, p.pose.x, p.pose.y, p.pose.theta, cv::Scalar(255 * (1 - f), 60, 255 * f), 2);
        }
      }
    }
    if (layers.inspection && selection_.kind == Selection::Kind::Particle) {
      drawPath(screen, v, selection_.particle_path, cv::Scalar(0, 230, 255), 3);
      drawPose(screen, v, selection_.particle_pose.x, selection_.particle_pose.y, selection_.particle_pose.theta,
               cv::Scalar(0, 230, 255), 6);
    }
  } else if (mode == ViewMode::Topology) {
    const MapLayer& m = labelsMap();
    if (!m.empty() && layers.map) {
      const int key = (layers.labels ? 1 : 0) + 2 * static_cast<int>(layers.stage);
      if (topo_raster_generation_ != topo_generation_ + map_generation_ || key != topo_raster_key_) {
        const cv::Mat bgr = topology_ ? topologyImage(*topology_, layers.stage, layers.labels) : greyToBgr(m.grey);
        topo_raster_.set(bgr, m);
        topo_raster_generation_ = topo_generation_ + map_generation_;
        topo_raster_key_ = key;
      }
      topo_raster_.draw(screen, v);
    }
    if (topology_) {
      drawTopologyGraph(screen, v, *topology_, layers.graph, layers.region_ids);
      if (layers.inspection && selection_.cell && selection_.cell->has_sample) {
        const auto& c = *selection_.cell;
        const cv::Point2d o = topology_->map.cellCentre(c.sample_cell.y, c.sample_cell.x);
        const cv::Point2d so = v.toScreen(o.x, o.y);
        std::vector<cv::Point> poly;
        for (const auto& e : c.scan_world) {
          const cv::Point2d q = v.toScreen(e.x, e.y);
          poly.emplace_back(static_cast<int>(q.x), static_cast<int>(q.y));
        }
        for (std::size_t k = 0; k < poly.size(); k += 10) cv::line(screen, so, poly[k], cv::Scalar(0, 200, 255), 1, cv::LINE_AA);
        cv::polylines(screen, poly, true, cv::Scalar(0, 140, 255), 2, cv::LINE_AA);
        cv::circle(screen, so, 4, cv::Scalar(0, 0, 0), cv::FILLED);
      }
      if (layers.inspection && selection_.node) {
        const cv::Point2d p = v.toScreen(selection_.node->centroid_world.x, selection_.node->centroid_world.y);
        cv::circle(screen, p, 11, cv::Scalar(0, 230, 255), 3, cv::LINE_AA);
      }
    }
  } else {  // Labels
    if (!map_.empty() && layers.map) {
      if (label_raster_generation_ != label_generation_ + map_generation_) {
        label_raster_.set(canvas_.empty() ? greyToBgr(map_.grey) : codesOverlay(map_.grey, canvas_.codes()), map_);
        label_raster_generation_ = label_generation_ + map_generation_;
      }
      label_raster_.draw(screen, v);
    }
  }
  if (layers.scale_bar) drawScaleBar(screen, v);
}

}  // namespace gridtopo::session
