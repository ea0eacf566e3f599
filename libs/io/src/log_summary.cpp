#include "gridtopo/io/log_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::io {

LogSummary summarizeScans(const std::vector<ScanRecord>& scans) {
  LogSummary s;
  s.scans = scans.size();
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const LaserScan& l = scans[i].scan;
    s.with_odometry += scans[i].has_odometry;
    ++s.beams_per_scan[l.size()];
    s.beams += l.size();
    for (std::size_t k = 0; k < l.size(); ++k) {
      if (l.valid[k]) continue;
      if (l.isNoReturn(k))
        ++s.no_return;
      else
        ++s.no_information;
    }
    const double t = l.timestamp;
    if (i == 0) {
      s.t_first = s.t_min = s.t_max = t;
    } else {
      const double prev = scans[i - 1].scan.timestamp;
      if (t < prev) {
        ++s.backward_steps;
        s.max_backward_step = std::max(s.max_backward_step, prev - t);
      }
      s.t_min = std::min(s.t_min, t);
      s.t_max = std::max(s.t_max, t);
    }
    s.t_last = t;
  }
  return s;
}

void printLogSummary(std::ostream& os, const std::string& input, const ScanLogInfo& info, const LogSummary& s,
                  const LaserScan& first) {
  os << "input:              " << input;
  if (info.format != LogFormat::Simulated)
    os << " (" << logFormatName(info.format)
       << (info.format == LogFormat::Rawlog
               ? (info.rawlog_has_actions ? ", action/sensory-frame layout" : ", observation-only layout")
               : "")
       << ")";
  os << "\n";
  os << "scans:              " << s.scans << "\n";
  os << "with odometry:      " << s.with_odometry << "\n";
  if (info.format != LogFormat::Simulated)
    os << "odometry messages:  " << info.odometry_messages
       << (info.format == LogFormat::Carmen ? " (ODOM lines)" : " (CObservationOdometry)") << "\n";
  if (info.odometry_fallbacks)
    os << "odometry fallbacks: " << info.odometry_fallbacks << " scans outside the ODOM time range kept the "
       << "laser-line odometry\n";
  if (s.scans) {
    const LaserScan& f = first;
    const double deg = 180.0 / M_PI;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "first scan:         %zu beams, %.4g .. %.4g deg (step %.4g deg), max range %.4g m, laser at "
                  "(%.4g m, %.4g m, %.4g deg)\n",
                  f.size(), f.start_angle * deg, f.beamAngle(f.size() ? f.size() - 1 : 0) * deg,
                  f.angle_increment * deg, f.max_range, f.sensor_pose.x, f.sensor_pose.y, f.sensor_pose.phi * deg);
    os << buf;
  }
  os << "beams per scan:    ";
  for (const auto& [n, count] : s.beams_per_scan) os << ' ' << n << " x " << count;
  os << "\n";
  if (s.scans) {
    os << "time span:          " << formatDouble(s.t_first) << " .. " << formatDouble(s.t_last) << " (min "
       << formatDouble(s.t_min) << ", max " << formatDouble(s.t_max) << ", "
       << formatDouble(std::round((s.t_max - s.t_min) * 1e6) / 1e6) << " s)\n";
  }
  os << "backward steps:     " << s.backward_steps;
  if (s.backward_steps) os << " (largest " << formatDouble(std::round(s.max_backward_step * 1e6) / 1e6) << " s)";
  os << "\n";
  char pct[32];
  std::snprintf(pct, sizeof pct, "%.2f", s.beams ? 100.0 * static_cast<double>(s.no_return) / s.beams : 0.0);
  os << "no-return readings: " << s.no_return << " (" << pct << " % of " << s.beams << " beams)\n";
  os << "no-info readings:   " << s.no_information << " (zero, negative or NaN)\n";
  if (info.format == LogFormat::Carmen) {
    os << "lines:              " << info.lines_or_entries << "\n";
    os << "skipped bad lines:  " << info.skipped_lines << "\n";
    for (const auto& m : info.skipped) os << "  skipped: " << m << "\n";
    os << "skipped messages: ";
    if (info.skipped_messages.empty()) os << "  none";
    for (const auto& [type, lines] : info.skipped_messages) os << "  " << type << " x " << lines;
    os << "\n";
    for (const auto& n : info.notes) os << "note:               " << n << "\n";
    for (const auto& w : info.warnings) os << "warning:            " << w << "\n";
  }
}


}  // namespace gridtopo::io
