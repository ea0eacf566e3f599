#pragma once
// A room the robot travels through is a corridor (issue 35, item 2: labels per space from how the robot used it).
// The classifier sees only the map: a wide hall that the building's plan calls a corridor (Freiburg 101's 10 m hall,
// the halls of real buildings with offices off them) reads as room from every simulated scan inside it. The path
// says more: a room is where the robot enters and leaves through the same door; a thoroughfare is where it comes in
// at one place and goes out at another, again and again. Per room region (after the correction rules and the open
// spaces), the path's visits (maximal runs of consecutive path cells in the region, resampled every cell) are read:
//  - a crossing is a visit that came from outside the region and went on outside it (not where the trajectory
//    starts, ends or has a gap) with its entry and exit at least `min_span` apart;
//  - its openings are the places where visits entered or left it, those within `opening_radius` of each other one.
// A room region of at least `min_area` with at least `min_crossings` crossings through at least `min_openings`
// openings, at least `min_coverage` of whose cells lie within `cover_radius` of the path inside it (a space the
// crossings sweep, not rooms joined to a corridor in one region, whose far parts the path never comes near),
// becomes corridor. Measured on simulated runs through eight labelled plans and on the SLAM maps of the real logs
// (doc/topology-trajectory.md, "Thoroughfares").
#include <opencv2/core.hpp>

#include <vector>

namespace gridtopo::topology {

struct ThoroughfareOptions {
  bool enabled = true;        ///< [topology] thoroughfares (needs the robot's path)
  int min_crossings = 3;      ///< [topology] thoroughfare_min_crossings
  double min_span = 3.0;      ///< [topology] thoroughfare_min_span (m): a crossing's entry and exit this far apart
  int min_openings = 3;       ///< [topology] thoroughfare_min_openings
  double opening_radius = 2.0;  ///< [topology] thoroughfare_opening_radius (m): entries / exits this close are one
  double min_area = 4.0;      ///< [topology] thoroughfare_min_area (m^2): smaller room regions are left alone
  double min_coverage = 0.85;  ///< [topology] thoroughfare_min_coverage: share of its cells near the path at least
  double cover_radius = 2.0;   ///< [topology] thoroughfare_cover_radius (m): "near" (4-neighbour steps in the region)
};

/// One room region relabelled corridor.
struct Thoroughfare {
  int crossings = 0;   ///< visits that went through it
  int openings = 0;    ///< distinct places where the path entered or left it
  double area_m2 = 0;
  double coverage = 0; ///< share of its cells within cover_radius of the path inside it
  cv::Point at;        ///< a cell of the region (its centroid's cell when that is in the region)
};

/// `labels` (CV_8U, 0..2 or places::kNoLabel) with every room region the path (cells, pathInCells) travelled through
/// set to corridor; `found` gets them. A copy of `labels` when disabled or without a path.
cv::Mat relabelThoroughfares(const cv::Mat& labels, const std::vector<cv::Point2d>& path, double resolution,
                             const ThoroughfareOptions& o, std::vector<Thoroughfare>* found = nullptr);

}  // namespace gridtopo::topology
