#pragma once
// The relations metric of Kümmerle, Steder, Dornhege, Ruhnke, Grisetti, Stachniss, Kleiner, "On measuring the
// accuracy of SLAM algorithms", Autonomous Robots 27(4), 2009, as defined by the Freiburg benchmark:
// for each relation timestamp take the estimated pose nearest in time; if it is more than 0.1 s away, carry it
// to the relation's time with the odometry motion between the two times. d_est = p1⁻¹ ⊕ p2; translational
// error |t(d_est) − t(ref)|, rotational error |wrap(θ(d_est) − θ(ref))|; mean ± sample std, min, max, count,
// absolute and squared; the same split into "local" relations (|t2 − t1| ≤ revisit_span) and "revisit" relations
// (|t2 − t1| > revisit_span: the robot came back). See doc/evaluation.md for the conventions that reproduce the
// published figures.
#include <mrpt/config/CConfigFileBase.h>

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "gridtopo/core/option_schema.h"
#include "gridtopo/eval/odometry_track.h"
#include "gridtopo/eval/relations.h"
#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::eval {

struct RelationsMetricOptions;
/// The key table of RelationsMetricOptions ([relations_metric] of config-ini/eval.ini).
const OptionSchema<RelationsMetricOptions>& relationsMetricOptionSchema();

/// Loaded, saved, dumped and validated through relationsMetricOptionSchema: max_time_gap, interpolate_odometry,
/// interpolate_estimate, odometry = auto|odom|laser, revisit_span; missing keys keep their value; wrong values throw
/// gridtopo::InputError(file, 0, "[section] key", ...).
struct RelationsMetricOptions : TableOptions<RelationsMetricOptions, relationsMetricOptionSchema> {
  static constexpr const char* kSection = "relations_metric";
  /// An estimated pose further than this (seconds) from a relation timestamp is corrected by odometry.
  double max_time_gap = 0.1;
  /// Odometry at a time: the reading nearest in time (false, the reference tool's choice) or linearly
  /// interpolated between the two readings around it (true, "interpolation variant").
  bool interpolate_odometry = false;
  /// Not part of the benchmark's definition (off by default): beyond max_time_gap, when estimated poses exist on
  /// both sides of t, blend the pose carried forward from the previous estimate with the pose carried back from
  /// the next one (weights by time; plain linear interpolation between the two when there is no odometry).
  bool interpolate_estimate = false;
  /// Which odometry of the raw log corrects the gaps.
  OdometrySource odometry = OdometrySource::Auto;
  /// Seconds (> 0): a relation with |t2 − t1| at most this is "local", a longer one a "revisit" (RelationsResult's
  /// split; it does not change which relations are scored or how).
  double revisit_span = 50.0;
};

/// Mean ± sample standard deviation (n − 1), min, max and count of a set of values.
struct ErrorStats {
  std::size_t count = 0;
  double mean = 0.0, std = 0.0, min = 0.0, max = 0.0;  ///< std = 0 when count < 2
  static ErrorStats of(const std::vector<double>& values);
};

/// Per-relation errors.
struct RelationError {
  Relation relation;
  mrpt::math::TPose2D estimated_delta{0, 0, 0};
  double translational = 0.0;  ///< m
  double rotational = 0.0;     ///< rad, in [0, π]
  double gap1 = 0.0, gap2 = 0.0;  ///< |time of the estimated pose used − relation timestamp| for t1 and t2
  bool corrected = false;  ///< an endpoint was carried over a gap by odometry
};

/// The errors of a subset of the relations (its count: translational.count == rotational.count).
struct RelationsSplit {
  ErrorStats translational;  ///< m
  ErrorStats rotational;     ///< deg
};

struct RelationsResult {
  ErrorStats translational;          ///< m
  ErrorStats translational_squared;  ///< m²
  ErrorStats rotational;             ///< deg
  ErrorStats rotational_squared;     ///< deg²
  std::vector<RelationError> errors;  ///< in the order of the relations file
  std::size_t endpoints_direct = 0;      ///< relation endpoints whose nearest pose was within max_time_gap
  std::size_t endpoints_corrected = 0;   ///< endpoints carried over a gap by odometry
  std::size_t endpoints_interpolated = 0; ///< endpoints interpolated between two estimates (interpolate_estimate)
  std::size_t endpoints_uncorrected = 0; ///< endpoints beyond max_time_gap with no odometry to correct them
  double max_gap = 0.0;                  ///< largest |t_estimate − t_relation| met (s)
  double revisit_span = 50.0;  ///< s: the options' revisit_span that split `local` and `revisit`
  RelationsSplit local;        ///< the relations with |t2 − t1| <= revisit_span
  RelationsSplit revisit;      ///< the relations with |t2 − t1| > revisit_span (the robot came back)
};

/// The estimated pose at time t: the nearest estimate, carried over the gap by odometry when further than
/// options.max_time_gap (odometry may be null or empty: then the nearest pose is used as is).
class TrajectoryLookup {
 public:
  TrajectoryLookup(std::vector<TimedPose> estimate, const OdometryTrack* odometry,
                   const RelationsMetricOptions& options);
  struct Result {
    mrpt::math::TPose2D pose{0, 0, 0};
    double gap = 0.0;  ///< |t_nearest − t|
    bool corrected = false, interpolated = false, uncorrectable = false;
  };
  Result poseAt(double t) const;

 private:
  mrpt::math::TPose2D carry(const TimedPose& from, double t) const;  // from ⊕ (o(t_from)⁻¹ ⊕ o(t))

  std::vector<TimedPose> estimate_;  // sorted by time (stable)
  const OdometryTrack* odometry_;
  RelationsMetricOptions options_;
};

/// Scores `estimate` (any order, any timestamps) against `relations`. Throws std::invalid_argument if the
/// estimate or the relations are empty.
RelationsResult evaluateRelations(const std::vector<TimedPose>& estimate, const std::vector<Relation>& relations,
                                  const OdometryTrack* odometry, const RelationsMetricOptions& options = {});

}  // namespace gridtopo::eval
