#include "gridtopo/eval/corrected_log.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::eval {
namespace {

/// Half a unit of the 6th significant digit of v: the rounding error of a "%g" (6 significant digits) print.
double sixDigitTolerance(double v) {
  const double a = std::abs(v);
  if (a < 1e-300) return 1e-9;
  return 0.5 * std::pow(10.0, std::floor(std::log10(a)) - 5.0) * (1.0 + 1e-9) + 1e-12;
}

bool sameRanges(const LaserScan& a, const LaserScan& b) {
  if (a.ranges.size() != b.ranges.size()) return false;
  for (std::size_t k = 0; k < a.ranges.size(); ++k) {
    const float x = a.ranges[k], y = b.ranges[k];
    if (std::isnan(x) && std::isnan(y)) continue;
    if (!(std::abs(x - y) <= 1e-4f * std::max(1.0f, std::abs(x)))) return false;
  }
  return true;
}

struct RawStamp {
  double key;        // logger or ipc timestamp
  std::size_t scan;  // index into raw
};

}  // namespace

const char* toString(CorrectedTimeMatch m) {
  switch (m) {
    case CorrectedTimeMatch::Auto:
      return "auto";
    case CorrectedTimeMatch::Ipc:
      return "ipc";
    case CorrectedTimeMatch::Logger:
      return "logger";
    case CorrectedTimeMatch::LoggerAndRanges:
      return "ranges";
  }
  return "?";
}

CorrectedTimeMatch correctedTimeMatchFromString(const std::string& s) {
  if (s == "auto") return CorrectedTimeMatch::Auto;
  if (s == "ipc") return CorrectedTimeMatch::Ipc;
  if (s == "logger") return CorrectedTimeMatch::Logger;
  if (s == "ranges") return CorrectedTimeMatch::LoggerAndRanges;
  throw std::invalid_argument("time matching must be auto, ipc, logger or ranges (got '" + s + "')");
}

std::vector<TimedPose> correctedTrajectory(const std::vector<ScanRecord>& corrected, const std::string& corrected_name,
                                           const std::vector<ScanRecord>& raw, const std::string& raw_name,
                                           const CorrectedLogOptions& options, CorrectedTimeMatch* used) {
  if (corrected.empty()) throw InputError(corrected_name, "no laser lines with corrected poses");
  if (raw.empty()) throw InputError(raw_name, "no laser lines to match the corrected log's timestamps to");

  auto sorted = [&](bool logger) {
    std::vector<RawStamp> v(raw.size());
    for (std::size_t i = 0; i < raw.size(); ++i)
      v[i] = {logger ? raw[i].scan.logger_timestamp : raw[i].scan.timestamp, i};
    std::stable_sort(v.begin(), v.end(), [](const RawStamp& a, const RawStamp& b) { return a.key < b.key; });
    return v;
  };
  const auto by_ipc = sorted(false);
  auto exact_ipc = [&](double t) {
    const auto it = std::lower_bound(by_ipc.begin(), by_ipc.end(), t,
                                     [](const RawStamp& a, double v) { return a.key < v; });
    return it != by_ipc.end() && it->key == t;
  };

  CorrectedTimeMatch match = options.match;
  if (match == CorrectedTimeMatch::Auto) {
    match = CorrectedTimeMatch::Ipc;
    for (const auto& s : corrected)
      if (!exact_ipc(s.scan.timestamp)) {
        match = CorrectedTimeMatch::Logger;
        break;
      }
  }
  if (used) *used = match;

  const auto by_logger = sorted(true);
  std::vector<TimedPose> out;
  out.reserve(corrected.size());
  for (const auto& rec : corrected) {
    if (!rec.has_odometry)
      throw InputError(corrected_name, rec.source_index, "pose", "laser line without a pose");
    const mrpt::math::TPose2D pose =
        options.pose == CorrectedPose::Robot ? rec.odometry : rec.odometry + rec.scan.sensor_pose;
    double t = rec.scan.timestamp;
    if (match == CorrectedTimeMatch::Ipc) {
      if (!exact_ipc(t))
        throw InputError(corrected_name, rec.source_index, "ipc_timestamp",
                         "no laser line of " + raw_name + " has this ipc timestamp");
    } else {
      const double L = rec.scan.logger_timestamp;
      const double tol = sixDigitTolerance(L);
      const auto lo = std::lower_bound(by_logger.begin(), by_logger.end(), L - tol,
                                       [](const RawStamp& a, double v) { return a.key < v; });
      const auto hi = std::upper_bound(by_logger.begin(), by_logger.end(), L + tol,
                                       [](double v, const RawStamp& a) { return v < a.key; });
      if (lo == hi)
        throw InputError(corrected_name, rec.source_index, "logger_timestamp",
                         "no laser line of " + raw_name + " has a logger timestamp within " + std::to_string(tol) +
                             " s of " + io::formatDouble(L));
      // Nearest logger timestamp (ties: the earlier one in time, then in file order).
      auto best = lo;
      for (auto it = lo; it != hi; ++it)
        if (std::abs(it->key - L) < std::abs(best->key - L)) best = it;
      if (match == CorrectedTimeMatch::LoggerAndRanges) {
        auto by_ranges = hi;
        for (auto it = lo; it != hi; ++it) {
          if (!sameRanges(raw[it->scan].scan, rec.scan)) continue;
          if (by_ranges == hi || std::abs(it->key - L) < std::abs(by_ranges->key - L)) by_ranges = it;
        }
        if (by_ranges != hi) best = by_ranges;
      }
      t = raw[best->scan].scan.timestamp;
    }
    out.push_back({t, pose});
  }
  return out;
}

}  // namespace gridtopo::eval
