// gridtopo-eval: scores an estimated trajectory against the ground-truth relations of the Freiburg SLAM
// benchmark with the relations metric of Kümmerle et al. 2009 (see doc/evaluation.md).
#include <mrpt/config/CConfigFile.h>
#include <tclap/CmdLine.h>

#include <filesystem>
#include <iostream>
#include <sstream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/eval/corrected_log.h"
#include "gridtopo/eval/relations_metric.h"
#include "gridtopo/eval/report.h"
#include "gridtopo/io/carmen_log.h"
#include "gridtopo/io/trajectory_io.h"

using namespace gridtopo;

namespace {

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd(
      "Scores an estimated trajectory against ground-truth relations (Kuemmerle et al. 2009, Freiburg SLAM "
      "benchmark): nearest estimated pose per relation timestamp, carried over gaps > --max-gap by odometry; "
      "translational / rotational error mean +- sample std, min, max, absolute and squared.\n"
      "Example: gridtopo-eval --relations datasets/slam/intel.relations.gz --log datasets/slam/intel.clf.gz "
      "--gfs datasets/slam/intel.gfs.log.gz --odometry laser --json out.json",
      ' ', "0.1");
  TCLAP::ValueArg<std::string> relations("r", "relations", "ground-truth relations file (plain or .gz)", true, "",
                                         "file", cmd);
  TCLAP::ValueArg<std::string> log("l", "log", "raw CARMEN log (plain or .gz): odometry for the gap correction",
                                   false, "", "file", cmd);
  TCLAP::ValueArg<std::string> trajectory("t", "trajectory", "estimated trajectory: 'timestamp x y theta' lines",
                                          false, "", "file", cmd);
  TCLAP::ValueArg<std::string> gfs("g", "gfs",
                                   "estimate as a CARMEN log with corrected poses (e.g. GMapping's .gfs.log.gz); "
                                   "needs --log",
                                   false, "", "file", cmd);
  TCLAP::SwitchArg baseline("", "baseline-odometry",
                            "estimate = the raw log's odometry (laser lines): the no-SLAM baseline", cmd);
  TCLAP::ValueArg<std::string> gfs_match("", "gfs-match",
                                         "how --gfs timestamps find the raw laser lines: auto (ipc if all match "
                                         "exactly, else logger), ipc, logger (nearest logger timestamp, the "
                                         "reference convention), ranges (logger + identical ranges)",
                                         false, "auto", "auto|ipc|logger|ranges", cmd);
  TCLAP::ValueArg<std::string> gfs_pose("", "gfs-pose", "which pose of the --gfs laser lines: robot or laser",
                                        false, "robot", "robot|laser", cmd);
  TCLAP::ValueArg<std::string> odometry("o", "odometry",
                                        "odometry for the gap correction: odom (ODOM lines), laser (odometry inside "
                                        "the laser lines), auto (odom if the log has ODOM lines) [default from "
                                        "--config, else auto]",
                                        false, "auto", "auto|odom|laser", cmd);
  TCLAP::SwitchArg interpolate("i", "interpolate",
                               "interpolate the odometry between readings instead of taking the nearest reading",
                               cmd);
  TCLAP::SwitchArg interpolate_estimate(
      "", "interpolate-estimate",
      "beyond --max-gap, blend the poses carried over from the estimates before and after the relation time "
      "(a variant, not the benchmark's definition)",
      cmd);
  TCLAP::ValueArg<double> max_gap("", "max-gap", "seconds: nearer estimated poses are used as they are [0.1]",
                                  false, 0.1, "s", cmd);
  TCLAP::ValueArg<std::string> config("c", "config", "INI file with a [relations_metric] section (config-ini/eval.ini)",
                                      false, "", "file", cmd);
  TCLAP::ValueArg<std::string> json("j", "json", "write the result as JSON to this file", false, "", "file", cmd);
  TCLAP::ValueArg<std::string> errors("e", "errors", "write per-relation errors to this text file", false, "",
                                      "file", cmd);
  TCLAP::SwitchArg skip_bad("", "skip-bad-lines", "skip (and count) malformed lines of CARMEN logs", cmd);
  cmd.setExceptionHandling(false);
  cmd.parse(argc, argv);

  const int sources = trajectory.isSet() + gfs.isSet() + baseline.getValue();
  if (sources != 1) {
    throw UsageError("give exactly one estimate: --trajectory, --gfs or --baseline-odometry");
  }
  if ((gfs.isSet() || baseline.getValue()) && !log.isSet()) {
    throw UsageError("--gfs and --baseline-odometry need the raw log (--log)");
  }

  eval::RelationsMetricOptions opt;
  if (config.isSet()) {
    if (!std::filesystem::exists(config.getValue())) throw InputError(config.getValue(), "cannot open INI file");
    mrpt::config::CConfigFile ini(config.getValue());
    try {
      opt.loadFromConfigFile(ini, "relations_metric");
    } catch (const InputError& e) {
      throw InputError(config.getValue(), 0, "relations_metric." + e.field(), e.message());
    }
  }
  try {
    if (odometry.isSet()) opt.odometry = eval::odometrySourceFromString(odometry.getValue());
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--odometry: ") + e.what());
  }
  if (interpolate.getValue()) opt.interpolate_odometry = true;
  if (interpolate_estimate.getValue()) opt.interpolate_estimate = true;
  if (max_gap.isSet()) {
    if (!(max_gap.getValue() >= 0.0)) {
      throw UsageError("--max-gap must be >= 0");
    }
    opt.max_time_gap = max_gap.getValue();
  }
  eval::CorrectedLogOptions copt;
  try {
    copt.match = eval::correctedTimeMatchFromString(gfs_match.getValue());
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--gfs-match: ") + e.what());
  }
  if (gfs_pose.getValue() == "laser") {
    copt.pose = eval::CorrectedPose::Laser;
  } else if (gfs_pose.getValue() != "robot") {
    throw UsageError("--gfs-pose must be robot or laser");
  }

  io::CarmenReadOptions ropt;
  ropt.skip_bad_lines = skip_bad.getValue();
  std::vector<std::pair<std::string, std::string>> info;
  info.emplace_back("relations", relations.getValue());
  const auto rels = eval::readRelations(relations.getValue());
  if (rels.empty()) throw InputError(relations.getValue(), "no relations in the file");

  io::CarmenLog raw;
  eval::OdometryTrack odom;
  auto report_skips = [](const io::CarmenLog& l) {
    if (l.skipped_lines == 0) return;
    std::cerr << l.path << ": skipped " << l.skipped_lines << " malformed line(s)\n";
    for (const auto& s : l.skipped) std::cerr << "  " << s << "\n";
  };
  if (log.isSet()) {
    raw = io::readCarmenLog(log.getValue(), ropt);
    report_skips(raw);
    eval::OdometrySource used = opt.odometry;
    odom = eval::OdometryTrack::fromLog(raw, opt.odometry, &used);
    if (used == eval::OdometrySource::OdomLines && raw.odometry.empty())
      throw InputError(log.getValue(), 0, "ODOM", "--odometry odom asked for, but the log has no ODOM lines");
    info.emplace_back("log", log.getValue());
    info.emplace_back("odometry", eval::toString(used));
  } else {
    info.emplace_back("odometry", "none");
  }
  info.emplace_back("odometry_interpolated", opt.interpolate_odometry ? "true" : "false");
  info.emplace_back("estimate_interpolated", opt.interpolate_estimate ? "true" : "false");
  info.emplace_back("max_time_gap_s", io::formatDouble(opt.max_time_gap));

  std::vector<io::TimedPose> estimate;
  if (trajectory.isSet()) {
    estimate = io::readTrajectory(trajectory.getValue());
    if (estimate.empty()) throw InputError(trajectory.getValue(), "the trajectory has no poses");
    info.emplace_back("trajectory", trajectory.getValue());
  } else if (gfs.isSet()) {
    const io::CarmenLog corrected = io::readCarmenLog(gfs.getValue(), ropt);
    report_skips(corrected);
    eval::CorrectedTimeMatch used = copt.match;
    estimate = eval::correctedTrajectory(corrected, raw, copt, &used);
    info.emplace_back("gfs", gfs.getValue());
    info.emplace_back("gfs_time_match", eval::toString(used));
    info.emplace_back("gfs_pose", gfs_pose.getValue());
  } else {
    for (const auto& s : raw.scans)
      if (s.has_odometry) estimate.push_back({s.scan.timestamp, s.odometry});
    if (estimate.empty()) throw InputError(log.getValue(), "the log has no odometry in its laser lines");
    info.emplace_back("trajectory", "baseline: odometry of the laser lines of " + log.getValue());
  }
  info.emplace_back("estimated_poses", std::to_string(estimate.size()));

  const auto result = eval::evaluateRelations(estimate, rels, odom.empty() ? nullptr : &odom, opt);
  std::cout << "relations:  " << relations.getValue() << " (" << rels.size() << ")\n";
  for (const auto& [k, v] : info)
    if (k != "relations") std::cout << k << ": " << v << "\n";
  std::cout << eval::formatSummary(result);
  if (result.endpoints_uncorrected)
    std::cerr << "warning: " << result.endpoints_uncorrected
              << " relation endpoints are further than --max-gap from every estimated pose and there is no "
                 "odometry (--log) to correct them\n";

  if (result.max_gap > 60.0)
    std::cerr << "warning: a relation timestamp is " << result.max_gap
              << " s from the nearest estimated pose: are the trajectory's timestamps the log's ipc timestamps?\n";

  OutputSet out;
  if (json.isSet()) {
    const std::string text = eval::formatJson(result, info);
    out.write(json.getValue(), [&](const std::string& tmp) { writeTextFileAtomically(tmp, text); });
  }
  if (errors.isSet()) {
    const std::string text = eval::formatErrors(result);
    out.write(errors.getValue(), [&](const std::string& tmp) { writeTextFileAtomically(tmp, text); });
  }
  out.commit();
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return gridtopo::runApp("gridtopo-eval", [&] { return run(argc, argv); }); }
