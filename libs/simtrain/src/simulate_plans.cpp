#include "gridtopo/simtrain/simulate_plans.h"

#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/io/trajectory_io.h"
#include "gridtopo/places/training.h"
#include "gridtopo/slam/slam_options.h"
#include "gridtopo/slam/slam_run_ini.h"

namespace gridtopo::simtrain {

void loadSlamMapOptions(const std::string& slam_ini, TrainingMapOptions& o) {
  if (slam_ini.empty()) return;
  if (!std::filesystem::is_regular_file(slam_ini)) throw InputError(slam_ini, "SLAM INI file not found");
  // As strictly as gridtopo-slam -c (unknown sections and keys refused with the line and a "did you mean").
  const slam::SlamOptions s = slam::loadSlamOptionsIni(slam_ini, "slam");
  o.slam = s;
  o.map = s.map;
  o.beams = s.beams;
}

MapVariant mapVariantFromString(const std::string& s, const std::string& field) {
  if (s == "exact") return MapVariant::Exact;
  if (s == "slam") return MapVariant::Slam;
  throw InputError(field, "must be 'exact' or 'slam', got '" + s + "'");
}

std::string summaryLine(const SimulatedPlan& p, MapVariant variant) {
  std::ostringstream s;
  s << p.name << ": " << p.scans << " scans, " << p.path_length << " m, rooms entered " << p.rooms_entered << " of "
    << p.rooms << " (" << p.rooms_unreachable << " unreachable), known " << 100 * p.known_fraction
    << " % of the plan's free cells, free " << 100 * p.free_fraction << " %";
  if (variant == MapVariant::Slam)
    s << ", SLAM final error " << p.drift.final_position_error << " m, label agreement "
      << 100 * p.drift.label_agreement << " %";
  return s.str();
}

const char* toString(MapVariant v) { return v == MapVariant::Slam ? "slam" : "exact"; }

std::vector<SimulatedPlan> simulatePlans(
    const std::string& places_dir, const std::string& out_dir, const TrainingMapOptions& o,
    const std::vector<std::string>& only, const std::string& command_line,
    const std::function<void(std::size_t, std::size_t, const std::string&)>& progress,
    const std::function<void(const std::string&, std::size_t, std::size_t)>& slam_progress) {
  std::vector<places::LabelledMapFiles> files;
  for (const auto& f : places::standardLabelledMaps(places_dir))
    if (only.empty() || std::find(only.begin(), only.end(), f.name) != only.end()) files.push_back(f);
  for (const auto& n : only)
    if (std::none_of(files.begin(), files.end(), [&](const auto& f) { return f.name == n; }))
      throw InputError("--maps", 0, n, "not a standard labelled map of " + places_dir);
  const double res = 0.05;  // every plan of datasets/places (datasets/README.md)
  std::vector<SimulatedPlan> out;
  const bool slam = o.variant == MapVariant::Slam;
  checkOutputFolder(out_dir);
  OutputSet outputs(out_dir);
  for (const auto& f : files) {
    const cv::Mat grey = cv::imread(f.map, cv::IMREAD_UNCHANGED);
    if (grey.empty()) throw InputError(f.map, "cannot read map image");
    const cv::Mat codes = cv::imread(f.labels, cv::IMREAD_GRAYSCALE);
    if (codes.empty()) throw InputError(f.labels, "cannot read labelled map image");
    if (codes.size() != grey.size()) throw InputError(f.labels, "labels and map differ in size");
    const TrainingMap tm = simulateTrainingMap(grey, codes, res, o, f.map, [&](std::size_t fed, std::size_t total) {
      if (slam_progress) slam_progress(f.name, fed, total);
    });
    SimulatedPlan p;
    p.name = f.name;
    p.scans = static_cast<int>(tm.log.records.size());
    p.path_length = tm.tour.length;
    p.rooms = tm.tour.rooms, p.rooms_entered = tm.tour.rooms_entered;
    p.rooms_unreachable = tm.tour.rooms_unreachable, p.corridor_goals = tm.tour.corridor_goals;
    const places::OccupancyImage plan = places::occupancyFromGrey(grey, res, f.map);
    std::size_t plan_free = 0, known = 0, free = 0;
    const int unknown = 128;  // grey of a never observed cell (io::gridToImage of p = 0.5)
    for (int r = 0; r < plan.rows(); ++r)
      for (int c = 0; c < plan.cols(); ++c) {
        if (!plan.isFree(r, c)) continue;
        ++plan_free;
        const int g = tm.grey.at<unsigned char>(r, c);
        known += g != unknown;
        free += g >= 204;
      }
    p.known_fraction = plan_free ? static_cast<double>(known) / plan_free : 0;
    p.free_fraction = plan_free ? static_cast<double>(free) / plan_free : 0;
    p.slam_processed_scans = tm.slam_processed_scans;
    p.drift = tm.drift;
    const cv::Mat img = tm.grey;
    outputs.write(places::simulatedMapPath(out_dir, f.name), [&img](const std::string& tmp) {
      if (!cv::imwrite(tmp, img)) throw std::runtime_error("cannot write " + tmp);
    });
    // The run's poses, so that the topology can be scored along the path as on a real SLAM map (gridtopo-topology
    // -t, gridtopo-topology-compare -t; scripts/bench_topology_runs.sh).
    const std::vector<TimedPose> poses = slam ? tm.slam_trajectory : tm.log.timedTruth();
    const std::vector<std::string> header = {
        f.name + ": " + (slam ? "the SLAM's pose of every scan" : "the true pose of every scan") +
            " of the simulated run, in the plan's frame (lower-left corner at 0 0, 0.05 m cells); command: "
            "manifest.txt"};
    outputs.write(places::simulatedTrajectoryPath(out_dir, f.name),
                  [&](const std::string& tmp) { io::writeTrajectory(tmp, poses, header); });
    out.push_back(p);
    if (progress) progress(out.size(), files.size(), f.name);
  }
  std::ostringstream m;
  if (slam)
    m << "# Simulated SLAM-like maps of the labelled plans (issue 15), SLAM variant: NAME_sim_map.png is the map the\n"
      << "# SLAM built from the simulated run, started at the true start pose and placed in the plan's pixel lattice\n"
      << "# (labels: labelled/training_*.png of the same plan, which land where the SLAM put the cells);\n"
      << "# NAME_sim_trajectory.txt holds the SLAM's pose of every scan. Made by:\n# "
      << command_line << "\n"
      << "# name scans path_m rooms rooms_entered rooms_unreachable corridor_goals known_fraction free_fraction"
      << " processed_scans final_error_m final_heading_error_deg max_error_m occupied_cells occupied_within_1"
      << " occupied_within_2 labelled_free_cells label_agreement\n";
  else
    m << "# Simulated SLAM-like maps of the labelled plans (issue 15): NAME_sim_map.png is pixel-aligned with the plan\n"
      << "# (labels: labelled/training_*.png of the same plan); NAME_sim_trajectory.txt holds the true pose of every\n"
      << "# scan. Made by:\n# " << command_line << "\n"
      << "# name scans path_m rooms rooms_entered rooms_unreachable corridor_goals known_fraction free_fraction\n";
  m << std::fixed;
  for (const auto& p : out) {
    m << p.name << " " << p.scans << " " << std::setprecision(1) << p.path_length << " " << p.rooms << " "
      << p.rooms_entered << " " << p.rooms_unreachable << " " << p.corridor_goals << " " << std::setprecision(4)
      << p.known_fraction << " " << p.free_fraction;
    if (slam)
      m << " " << p.slam_processed_scans << " " << std::setprecision(3) << p.drift.final_position_error << " "
        << std::setprecision(2) << p.drift.final_heading_error * 180.0 / M_PI << " " << std::setprecision(3)
        << p.drift.max_position_error << " " << p.drift.occupied_cells << " " << std::setprecision(4)
        << p.drift.occupied_within_1 << " " << p.drift.occupied_within_2 << " " << p.drift.labelled_free_cells << " "
        << p.drift.label_agreement;
    m << "\n";
  }
  const std::string text = m.str();
  outputs.write(out_dir + "/manifest.txt", [&text](const std::string& tmp) { writeTextFileAtomically(tmp, text); });
  outputs.commit();
  return out;
}

SimulateMapsRun simulateMapsRunOf(const SimulateMapsArgs& a) {
  SimulateMapsRun r;
  TrainingMapOptions& o = r.options;
  o.variant = mapVariantFromString(a.variant);
  loadSlamMapOptions(a.slam_ini, o);
  const bool slam = o.variant == MapVariant::Slam;
  r.places_dir = a.places_dir;
  r.output = !a.output.empty() ? a.output : slam ? "datasets/places/derived/slam" : "datasets/places/derived";
  if (a.threads >= 0) o.slam.threads = a.threads;
  if (a.seed < 0) throw InputError("--seed", "must be >= 0");
  if (!(a.room_visit_probability >= 0 && a.room_visit_probability <= 1))
    throw InputError("--room-visit-probability", "must be in [0, 1]");
  if (!(a.clearance >= 0 && a.clearance <= 1)) throw InputError("--clearance", "must be in [0, 1] m");
  if (!(a.no_return_probability >= 0 && a.no_return_probability < 1))
    throw InputError("--no-return-probability", "must be in [0, 1)");
  o.laser.dropout_probability = a.no_return_probability;
  o.laser.seed = static_cast<std::uint64_t>(a.seed);
  o.tour.seed = static_cast<std::uint64_t>(a.seed);
  o.tour.room_visit_probability = a.room_visit_probability;
  o.tour.clearance = a.clearance;
  std::stringstream names(a.maps);
  for (std::string n; std::getline(names, n, ',');)
    if (!n.empty()) r.only.push_back(n);
  std::ostringstream command;
  command << "gridtopo-simulate-maps" << (slam ? " --variant slam" : "") << " -d " << a.places_dir << " -o "
          << r.output << " -c " << (a.slam_ini.empty() ? "''" : a.slam_ini) << " -s " << a.seed
          << " --room-visit-probability " << a.room_visit_probability << " --clearance " << a.clearance
          << (a.maps.empty() ? "" : " --maps " + a.maps);
  if (a.no_return_probability != SimulateMapsArgs{}.no_return_probability)
    command << " --no-return-probability " << a.no_return_probability;
  r.command = command.str();
  return r;
}

}  // namespace gridtopo::simtrain
