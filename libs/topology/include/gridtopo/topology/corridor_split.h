#pragma once
// Corridor pieces for the topological graph: a corridor region that branches (a T, a cross, a grid of corridors as
// in ACES) becomes one node per junction and one per branch between junctions, so the graph shows the corridor
// network instead of a single corridor node with every room wired to it. Found on the skeleton of the region
// (Zhang-Suen thinning, thinZhangSuen below): skeleton points where three or more branches meet are junctions,
// branches shorter than `min_branch` (wall bumps, door recesses) are pruned first; every corridor cell joins the nearest
// junction or branch (geodesic, inside the region). Only the graph's regions change: labels and the room
// segmentation do not.
#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

struct CorridorSplitOptions {
  bool enabled = true;
  double min_branch = 4.0;      ///< m beyond the corridor's wall: shorter side branches (recesses, open doors) are pruned
  double min_piece_area = 2.0;  ///< m^2; smaller pieces join the neighbouring piece they share most border with
  double max_hole_area = 4.0;   ///< m^2; holes in the region up to this size are filled before the skeleton
};

/// Returns a region map in which every corridor region with at least one junction is replaced by its pieces
/// (same label; new ids, all regions renumbered 1..N in the order rooms, corridors, doorways of the input). Other
/// regions are kept as they are (with new ids).
RegionMap splitCorridors(const RegionMap& regions, double resolution, const CorridorSplitOptions& options = {});
/// The same result, written over `regions`' id image (no second full-map id image: on the hospital's map each is
/// 200 MB, and this step held the run's peak).
RegionMap splitCorridors(RegionMap&& regions, double resolution, const CorridorSplitOptions& options = {});

/// Zhang-Suen thinning of `mask` (CV_8U; cells >= 128 are set): the same skeleton (0 / 255) as
/// cv::ximgproc::thinning(mask, out, THINNING_ZHANGSUEN), cell for cell, but each sub-iteration looks only at the
/// cells next to the ones the previous sub-iterations removed, so the cost grows with the mask's area rather than
/// with the image's area times the number of iterations (the mask's half-width). Border cells are never removed.
cv::Mat thinZhangSuen(const cv::Mat& mask);

}  // namespace gridtopo::topology
