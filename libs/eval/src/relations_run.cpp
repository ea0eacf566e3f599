#include "gridtopo/eval/relations_run.h"

#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"
#include "gridtopo/eval/odometry_track.h"
#include "gridtopo/eval/report.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::eval {

RelationsMetricOptions loadRelationsMetricIni(const std::string& path) {
  RelationsMetricOptions opt;
  if (!std::filesystem::exists(path)) throw InputError(path, "cannot open INI file");
  const IniFile ini = IniFile::read(path);
  ini.requireOptionsFile({"relations_metric"}, "relations_metric");
  ini.requireKnownKeys("relations_metric", relationsMetricOptionSchema().keys(), "see config-ini/eval.ini");
  try {
    opt.loadFromConfigFile(mrpt::config::CConfigFile(path), "relations_metric");
  } catch (const InputError& e) {
    throw ini.withLine(e);  // the table names "[relations_metric] key" without the line
  }
  return opt;
}

std::string relationsMetricOptionsHelp() {
  return optionsHelp("relations_metric", relationsMetricOptionSchema().describe({}));
}

void applyRelationsFlags(RelationsRunSpec& spec, const RelationsFlags& f) {
  const auto parsed = [](const char* flag, auto parse, const std::string& v) {
    try {
      return parse(v);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string(flag) + ": " + e.what());
    }
  };
  RelationsMetricOptions& opt = spec.metric;
  if (!f.odometry.empty()) opt.odometry = parsed("--odometry", odometrySourceFromString, f.odometry);
  if (f.interpolate) opt.interpolate_odometry = true;
  if (f.interpolate_estimate) opt.interpolate_estimate = true;
  if (f.max_gap) {
    if (!(*f.max_gap >= 0.0)) throw UsageError("--max-gap must be >= 0");
    opt.max_time_gap = *f.max_gap;
  }
  if (f.revisit_span) {
    if (!(*f.revisit_span > 0.0)) throw UsageError("--revisit-span must be > 0");
    opt.revisit_span = *f.revisit_span;
  }
  spec.corrected.match = parsed("--gfs-match", correctedTimeMatchFromString, f.gfs_match);
  if (f.gfs_pose == "laser") spec.corrected.pose = CorrectedPose::Laser;
  else if (f.gfs_pose != "robot") throw UsageError("--gfs-pose must be robot or laser");
}

void configureRelationsRun(RelationsRunSpec& spec, const std::optional<std::string>& config,
                           const RelationsFlags& flags) {
  checkRelationsRunSpec(spec);
  if (config) spec.metric = loadRelationsMetricIni(*config);
  applyRelationsFlags(spec, flags);
}

void checkRelationsRunSpec(const RelationsRunSpec& s) {
  const int sources = !s.trajectory.empty() + !s.corrected_log.empty() + s.baseline_odometry;
  if (sources != 1) throw UsageError("give exactly one estimate: --trajectory, --gfs or --baseline-odometry");
  if ((!s.corrected_log.empty() || s.baseline_odometry) && s.log.empty())
    throw UsageError("--gfs and --baseline-odometry need the raw log (--log)");
}

namespace {
void reportSkips(const io::CarmenLog& l, std::ostream& log) {
  if (l.skipped_lines == 0) return;
  log << l.path << ": skipped " << l.skipped_lines << " malformed line(s)\n";
  for (const auto& s : l.skipped) log << "  " << s << "\n";
}
}  // namespace

RelationsRun runRelations(const RelationsRunSpec& spec, std::ostream& log) {
  RelationsRun run;
  auto& info = run.info;
  const RelationsMetricOptions& opt = spec.metric;
  info.emplace_back("relations", spec.relations);
  const auto rels = readRelations(spec.relations);
  if (rels.empty()) throw InputError(spec.relations, "no relations in the file");
  run.relation_count = rels.size();

  io::CarmenLog raw;
  OdometryTrack odom;
  if (!spec.log.empty()) {
    raw = io::readCarmenLog(spec.log, spec.read);
    reportSkips(raw, log);
    OdometrySource used = opt.odometry;
    odom = OdometryTrack::fromScans(raw.scans, raw.odometry, opt.odometry, &used);
    if (used == OdometrySource::OdomLines && raw.odometry.empty())
      throw InputError(spec.log, 0, "ODOM", "--odometry odom asked for, but the log has no ODOM lines");
    info.emplace_back("log", spec.log);
    info.emplace_back("odometry", toString(used));
  } else {
    info.emplace_back("odometry", "none");
  }
  run.flags.emplace_back("odometry_interpolated", opt.interpolate_odometry);
  run.flags.emplace_back("estimate_interpolated", opt.interpolate_estimate);
  run.numbers.emplace_back("max_time_gap_s", opt.max_time_gap);

  std::vector<TimedPose> estimate;
  if (!spec.trajectory.empty()) {
    estimate = io::readTrajectory(spec.trajectory);
    if (estimate.empty()) throw InputError(spec.trajectory, "the trajectory has no poses");
    info.emplace_back("trajectory", spec.trajectory);
  } else if (!spec.corrected_log.empty()) {
    const io::CarmenLog corrected = io::readCarmenLog(spec.corrected_log, spec.read);
    reportSkips(corrected, log);
    CorrectedTimeMatch used = spec.corrected.match;
    estimate = correctedTrajectory(corrected.scans, corrected.path, raw.scans, raw.path, spec.corrected, &used);
    info.emplace_back("gfs", spec.corrected_log);
    info.emplace_back("gfs_time_match", toString(used));
    info.emplace_back("gfs_pose", spec.corrected.pose == CorrectedPose::Laser ? "laser" : "robot");
  } else {
    for (const auto& s : raw.scans)
      if (s.has_odometry) estimate.push_back({s.scan.timestamp, s.odometry});
    if (estimate.empty()) throw InputError(spec.log, "the log has no odometry in its laser lines");
    info.emplace_back("trajectory", "baseline: odometry of the laser lines of " + spec.log);
  }
  run.numbers.emplace_back("estimated_poses", static_cast<double>(estimate.size()));
  if (!spec.trajectory.empty()) {
    run.loop_closure = readLoopClosureSummary(statsBesideTrajectory(spec.trajectory));
    if (run.loop_closure)
      for (const auto& [k, v] : run.loop_closure->values) run.numbers.emplace_back("loop_closure_" + k, v);
  }

  // Inputs that do not belong together are refused, not scored: the estimate's time span against the raw log's
  // and the relations'.
  double first = estimate.front().timestamp, last = first;
  for (const auto& p : estimate) first = std::min(first, p.timestamp), last = std::max(last, p.timestamp);
  run.estimate_first = first, run.estimate_last = last;
  const std::string estimate_name = !spec.trajectory.empty() ? spec.trajectory
                                    : !spec.corrected_log.empty() ? spec.corrected_log
                                                                  : spec.log;
  const auto span = [](double a, double b) { return "[" + io::formatDouble(a) + ", " + io::formatDouble(b) + "] s"; };
  if (!spec.log.empty() && !raw.scans.empty() && spec.trajectory == estimate_name) {
    double log_first = raw.scans.front().scan.timestamp, log_last = log_first;
    for (const auto& s : raw.scans)
      log_first = std::min(log_first, s.scan.timestamp), log_last = std::max(log_last, s.scan.timestamp);
    std::size_t inside = 0;
    for (const auto& p : estimate) inside += p.timestamp >= log_first - 1.0 && p.timestamp <= log_last + 1.0;
    if (2 * inside < estimate.size())
      throw InputError(spec.log, "its times " + span(log_first, log_last) + " do not match the trajectory's " +
                                     span(first, last) + " (" + std::to_string(inside) + " of " +
                                     std::to_string(estimate.size()) +
                                     " poses in the log's span): the trajectory was made from another log");
  }
  const double tol = opt.max_time_gap;
  std::vector<Relation> within;
  double rel_first = rels.front().t1, rel_last = rel_first;
  for (const auto& r : rels) {
    rel_first = std::min({rel_first, r.t1, r.t2}), rel_last = std::max({rel_last, r.t1, r.t2});
    if (std::min(r.t1, r.t2) >= first - tol && std::max(r.t1, r.t2) <= last + tol) within.push_back(r);
  }
  run.relations_scored = within.size();
  run.relations_skipped = rels.size() - within.size();
  if (within.empty())
    throw InputError(spec.relations, "no relation lies in the time span " + span(first, last) + " of " +
                                         estimate_name + " (the relations span " + span(rel_first, rel_last) +
                                         "): the relations and the estimate do not belong together");
  if (2 * run.relations_skipped > rels.size() && !spec.partial)
    throw InputError(spec.relations, std::to_string(run.relations_skipped) + " of " + std::to_string(rels.size()) +
                                         " relations lie outside the time span " + span(first, last) + " of " +
                                         estimate_name +
                                         ": most cannot be scored (an estimate of another log, or of part of "
                                         "it: --partial scores the part)");
  run.result = evaluateRelations(estimate, within, odom.empty() ? nullptr : &odom, opt);
  for (const auto& e : run.result.errors) run.relations_corrected += e.corrected;
  run.numbers.emplace_back("relations_total", static_cast<double>(rels.size()));
  run.numbers.emplace_back("relations_scored", static_cast<double>(run.relations_scored));
  run.numbers.emplace_back("relations_corrected", static_cast<double>(run.relations_corrected));
  run.numbers.emplace_back("relations_skipped", static_cast<double>(run.relations_skipped));
  return run;
}

std::string relationsRunText(const RelationsRun& run) {
  std::ostringstream o;
  o << "relations:  " << run.info.front().second << " (" << run.relation_count << ")\n";
  for (const auto& [k, v] : run.info) {
    if (k != "relations") o << k << ": " << v << "\n";
    if (k == "odometry")  // the flags after the odometry source, as before they were booleans
      for (const auto& [f, on] : run.flags) o << f << ": " << (on ? "true" : "false") << "\n";
  }
  for (const auto& [k, v] : run.numbers)
    if (k == "max_time_gap_s" || k == "estimated_poses") o << k << ": " << io::formatDouble(v) << "\n";
  o << "relations scored: " << run.relations_scored << " of " << run.relation_count << " ("
    << run.relations_corrected << " corrected by odometry, " << run.relations_skipped
    << " skipped: outside the estimate's time span [" << io::formatDouble(run.estimate_first) << ", "
    << io::formatDouble(run.estimate_last) << "] s)\n";
  o << formatSummary(run.result);
  if (run.loop_closure) o << loopClosureSummaryText(*run.loop_closure);
  return o.str();
}

void stageRelationsOutputs(OutputSet& outputs, const RelationsRun& run, const std::string& json_path,
                           const std::string& errors_path) {
  if (!json_path.empty()) {
    const std::string text = formatJson(run.result, run.info, run.numbers, run.flags);
    outputs.write(json_path, [&](const std::string& tmp) { writeTextFileAtomically(tmp, text); });
  }
  if (!errors_path.empty()) {
    const std::string text = formatErrors(run.result);
    outputs.write(errors_path, [&](const std::string& tmp) { writeTextFileAtomically(tmp, text); });
  }
}

std::string relationsRunWarnings(const RelationsRun& run) {
  std::ostringstream o;
  if (run.result.endpoints_uncorrected)
    o << "warning: " << run.result.endpoints_uncorrected
      << " relation endpoints are further than --max-gap from every estimated pose and there is no "
         "odometry (--log) to correct them\n";
  if (run.result.max_gap > 60.0)
    o << "warning: a relation timestamp is " << run.result.max_gap
      << " s from the nearest estimated pose: are the trajectory's timestamps the log's ipc timestamps?\n";
  return o.str();
}

void writeRelationsOutputs(const RelationsRun& run, const std::string& json_path, const std::string& errors_path) {
  OutputSet out;
  stageRelationsOutputs(out, run, json_path, errors_path);
  out.commit();
}

}  // namespace gridtopo::eval
