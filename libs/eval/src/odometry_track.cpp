#include "gridtopo/eval/odometry_track.h"

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <stdexcept>

namespace gridtopo::eval {

const char* toString(OdometrySource s) {
  switch (s) {
    case OdometrySource::Auto:
      return "auto";
    case OdometrySource::OdomLines:
      return "odom";
    case OdometrySource::LaserLines:
      return "laser";
  }
  return "?";
}

OdometrySource odometrySourceFromString(const std::string& s) {
  if (s == "auto") return OdometrySource::Auto;
  if (s == "odom") return OdometrySource::OdomLines;
  if (s == "laser") return OdometrySource::LaserLines;
  throw std::invalid_argument("odometry source must be auto, odom or laser (got '" + s + "')");
}

OdometryTrack::OdometryTrack(std::vector<TimedPose> readings) : poses_(std::move(readings)) {
  sortByTime(poses_);
}

OdometryTrack OdometryTrack::fromScans(const std::vector<ScanRecord>& scans,
                                       const std::vector<OdometryReading>& odometry, OdometrySource source,
                                       OdometrySource* used) {
  if (source == OdometrySource::Auto)
    source = odometry.empty() ? OdometrySource::LaserLines : OdometrySource::OdomLines;
  if (used) *used = source;
  std::vector<TimedPose> r;
  if (source == OdometrySource::OdomLines) {
    r.reserve(odometry.size());
    for (const auto& o : odometry) r.push_back({o.timestamp, o.pose});
  } else {
    r.reserve(scans.size());
    for (const auto& s : scans)
      if (s.has_odometry) r.push_back({s.scan.timestamp, s.odometry});
  }
  return OdometryTrack(std::move(r));
}

const TimedPose& nearestInTime(const std::vector<TimedPose>& sorted, double t) {
  if (sorted.empty()) throw std::logic_error("nearestInTime on an empty sequence");
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), t,
                                   [](const TimedPose& p, double v) { return p.timestamp < v; });
  if (it == sorted.begin()) return *it;
  // The first element at or after t versus the last one before it; a tie goes to the earlier one, and among
  // equal timestamps to the first of them.
  auto prev = std::prev(it);
  if (it == sorted.end() || t - prev->timestamp <= it->timestamp - t) {
    while (prev != sorted.begin() && std::prev(prev)->timestamp == prev->timestamp) --prev;
    return *prev;
  }
  return *it;
}

void sortByTime(std::vector<TimedPose>& poses) {
  std::stable_sort(poses.begin(), poses.end(),
                   [](const TimedPose& a, const TimedPose& b) { return a.timestamp < b.timestamp; });
}

const TimedPose& OdometryTrack::nearest(double t) const { return nearestInTime(poses_, t); }

mrpt::math::TPose2D OdometryTrack::interpolate(double t) const {
  if (poses_.empty()) throw std::logic_error("OdometryTrack::interpolate on an empty track");
  const auto it = std::lower_bound(poses_.begin(), poses_.end(), t,
                                   [](const TimedPose& p, double v) { return p.timestamp < v; });
  if (it == poses_.begin()) return it->pose;
  if (it == poses_.end()) return poses_.back().pose;
  const auto& b = *it;
  const auto& a = *std::prev(it);
  const double span = b.timestamp - a.timestamp;
  if (!(span > 0)) return b.pose;
  const double f = (t - a.timestamp) / span;
  return {a.pose.x + f * (b.pose.x - a.pose.x), a.pose.y + f * (b.pose.y - a.pose.y),
          mrpt::math::wrapToPi(a.pose.phi + f * mrpt::math::wrapToPi(b.pose.phi - a.pose.phi))};
}

mrpt::math::TPose2D OdometryTrack::at(double t, bool interpolated) const {
  return interpolated ? interpolate(t) : nearest(t).pose;
}

}  // namespace gridtopo::eval
