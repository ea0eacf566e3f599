#include "gridtopo/eval/relations_metric.h"
#include "gridtopo/core/ini_value.h"

#include <mrpt/math/wrap2pi.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include "gridtopo/core/error.h"

namespace gridtopo::eval {

const OptionSchema<RelationsMetricOptions>& relationsMetricOptionSchema() {
  using O = RelationsMetricOptions;
  static const OptionSchema<O> schema =
      OptionSchema<O>("gridtopo::eval::RelationsMetricOptions")
          .add("max_time_gap", &O::max_time_gap, OptionRange::atLeast(0), "s",
               "nearer estimated poses are used as they are; further ones are carried by odometry")
          .add("interpolate_odometry", &O::interpolate_odometry, OptionRange::any(), "",
               "odometry at a time: the nearest reading (false, the reference tool) or interpolated (true)")
          .add("interpolate_estimate", &O::interpolate_estimate, OptionRange::any(), "",
               "blend the estimates before and after a gap (not the benchmark's definition)")
          .addWords<OdometrySource>("odometry", field(&O::odometry),
                                    {{"auto", OdometrySource::Auto}, {"odom", OdometrySource::OdomLines},
                                     {"laser", OdometrySource::LaserLines}},
                                    "the odometry that fills the gaps: ODOM lines, laser lines, auto (odom if any)")
          .add("revisit_span", &O::revisit_span, OptionRange::above(0), "s",
               "relations with |t2 - t1| up to this are local, longer ones revisits (the errors split in two)");
  return schema;
}


ErrorStats ErrorStats::of(const std::vector<double>& v) {
  ErrorStats s;
  s.count = v.size();
  if (v.empty()) return s;
  double sum = 0.0;
  s.min = s.max = v.front();
  for (double x : v) {
    sum += x;
    s.min = std::min(s.min, x);
    s.max = std::max(s.max, x);
  }
  s.mean = sum / static_cast<double>(v.size());
  if (v.size() > 1) {
    double ss = 0.0;
    for (double x : v) ss += (x - s.mean) * (x - s.mean);
    s.std = std::sqrt(ss / static_cast<double>(v.size() - 1));
  }
  return s;
}

TrajectoryLookup::TrajectoryLookup(std::vector<TimedPose> estimate, const OdometryTrack* odometry,
                                   const RelationsMetricOptions& options)
    : estimate_(std::move(estimate)), odometry_(odometry), options_(options) {
  if (estimate_.empty()) throw std::invalid_argument("the estimated trajectory is empty");
  sortByTime(estimate_);
}

TrajectoryLookup::Result TrajectoryLookup::poseAt(double t) const {
  const TimedPose* e = &nearestInTime(estimate_, t);
  Result r;
  r.pose = e->pose;
  r.gap = std::abs(e->timestamp - t);
  if (r.gap <= options_.max_time_gap) return r;
  const bool have_odometry = odometry_ && !odometry_->empty();
  if (options_.interpolate_estimate) {
    // Estimates on both sides of t: the last one at or before t and the first one after it.
    const auto next = std::upper_bound(estimate_.begin(), estimate_.end(), t,
                                       [](double v, const TimedPose& p) { return v < p.timestamp; });
    if (next != estimate_.begin() && next != estimate_.end()) {
      auto prev = std::prev(next);
      while (prev != estimate_.begin() && std::prev(prev)->timestamp == prev->timestamp) --prev;
      const auto& before = *prev;
      const auto& after = *next;
      const double w = (t - before.timestamp) / (after.timestamp - before.timestamp);
      const auto a = have_odometry ? carry(before, t) : before.pose;
      const auto b = have_odometry ? carry(after, t) : after.pose;
      r.pose = {a.x + w * (b.x - a.x), a.y + w * (b.y - a.y),
                mrpt::math::wrapToPi(a.phi + w * mrpt::math::wrapToPi(b.phi - a.phi))};
      r.interpolated = true;
      return r;
    }
  }
  if (!have_odometry) {
    r.uncorrectable = true;
    return r;
  }
  r.pose = carry(*e, t);
  r.corrected = true;
  return r;
}

mrpt::math::TPose2D TrajectoryLookup::carry(const TimedPose& from, double t) const {
  // p(t) = p(t_e) ⊕ (o(t_e)⁻¹ ⊕ o(t)): the odometry motion between the two times, applied in the estimate's frame.
  const auto o_e = odometry_->at(from.timestamp, options_.interpolate_odometry);
  const auto o_t = odometry_->at(t, options_.interpolate_odometry);
  auto p = from.pose + (o_t - o_e);
  p.phi = mrpt::math::wrapToPi(p.phi);
  return p;
}

RelationsResult evaluateRelations(const std::vector<TimedPose>& estimate, const std::vector<Relation>& relations,
                                  const OdometryTrack* odometry, const RelationsMetricOptions& options) {
  if (relations.empty()) throw std::invalid_argument("no relations to evaluate");
  const TrajectoryLookup lookup(estimate, odometry, options);
  RelationsResult res;
  std::vector<double> te, te2, re, re2;
  std::vector<double> local_te, local_re, revisit_te, revisit_re;
  te.reserve(relations.size());
  res.errors.reserve(relations.size());
  constexpr double kRadToDeg = 180.0 / M_PI;
  for (const Relation& rel : relations) {
    const auto a = lookup.poseAt(rel.t1);
    const auto b = lookup.poseAt(rel.t2);
    for (const auto* x : {&a, &b}) {
      res.endpoints_direct += !x->corrected && !x->interpolated && !x->uncorrectable;
      res.endpoints_corrected += x->corrected;
      res.endpoints_interpolated += x->interpolated;
      res.endpoints_uncorrected += x->uncorrectable;
      res.max_gap = std::max(res.max_gap, x->gap);
    }
    RelationError err;
    err.relation = rel;
    err.estimated_delta = b.pose - a.pose;  // a⁻¹ ⊕ b
    err.translational = std::hypot(err.estimated_delta.x - rel.delta.x, err.estimated_delta.y - rel.delta.y);
    err.rotational = std::abs(mrpt::math::wrapToPi(err.estimated_delta.phi - rel.delta.phi));
    err.gap1 = a.gap;
    err.gap2 = b.gap;
    err.corrected = a.corrected || b.corrected;
    te.push_back(err.translational);
    te2.push_back(err.translational * err.translational);
    const double deg = err.rotational * kRadToDeg;
    re.push_back(deg);
    re2.push_back(deg * deg);
    const bool revisit = std::abs(rel.t2 - rel.t1) > options.revisit_span;
    (revisit ? revisit_te : local_te).push_back(err.translational);
    (revisit ? revisit_re : local_re).push_back(deg);
    res.errors.push_back(err);
  }
  res.translational = ErrorStats::of(te);
  res.translational_squared = ErrorStats::of(te2);
  res.rotational = ErrorStats::of(re);
  res.rotational_squared = ErrorStats::of(re2);
  res.revisit_span = options.revisit_span;
  res.local = {ErrorStats::of(local_te), ErrorStats::of(local_re)};
  res.revisit = {ErrorStats::of(revisit_te), ErrorStats::of(revisit_re)};
  return res;
}

}  // namespace gridtopo::eval
