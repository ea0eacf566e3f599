#pragma once
// Region-level label votes (round 5, doc/topology.md): the relaxed room / corridor probabilities summed over
// an area of the map, and every room / corridor cell of that area given the larger of the two sums.
//  - Blob vote (pipeline step 7b, `[topology] blob_vote`): the areas are geometric blobs of free space, an
//    over-segmentation that follows the walls (the cores left once the band within neck_width / 2 of every
//    obstacle is removed, grown back over the free space), computed without looking at the labels.
//  - Oracle region vote (evaluation diagnostic only): the areas are the ground-truth regions; the accuracy it
//    gives is the ceiling of any vote over a perfect segmentation.
#include <opencv2/core.hpp>

#include "gridtopo/places/scan_simulation.h"

namespace gridtopo::topology {

struct BlobVoteOptions {
  bool enabled = false;  ///< [topology] blob_vote
  /// m; [topology] blob_vote_neck_width: free cells closer than half of this to an obstacle are removed to find
  /// the blob cores, so blobs are separated by passages narrower than this (doors).
  double neck_width = 2.6;
  double min_core_area = 0.5;  ///< m^2; [topology] blob_vote_min_core_area: smaller cores seed no blob
  /// m; [topology] blob_vote_grow_limit: a core grows back over at most this many metres of breadth-first steps
  /// (8-connected, one cell per step); free cells no core reaches form blobs of their own (8-connected
  /// components), so a corridor narrower than the neck width is not swallowed by the rooms along it. 0 = no limit.
  double grow_limit = 1.5;
  /// m^2; [topology] blob_vote_fill_obstacle_area: obstacles (4-connected blobs of non-free cells not touching the
  /// image border) up to this area count as free space for the distance transform (furniture is not a wall).
  double fill_obstacle_area = 0.25;
  /// [topology] blob_vote_min_share: a blob is voted only when the winner's share of the blob's room + corridor
  /// probability mass is at least this (0.5 = always).
  double min_share = 0.75;
};

/// Per-cell probabilities (CV_32FC3): every cell with a label 0..2 in `labels` takes its lattice block's
/// distribution from `lattice_probs` (CV_32FC3 lattice grid, e.g. LabellingResult::probs); other cells 0.
cv::Mat cellProbabilities(const cv::Mat& labels, const places::Lattice& lattice, const cv::Mat& lattice_probs);

/// Geometric blobs of the free cells `free_mask` (CV_8U, non-zero = free): cores = 8-connected components of
/// the cells farther than neck_width / 2 from every non-free cell (and from the image border), enclosed
/// obstacles up to fill_obstacle_area counted as free, of at least min_core_area; each core grows back
/// breadth-first (8-connected) over the free cells, at most grow_limit metres when grow_limit > 0; the free
/// cells left over are blobs of their own (8-connected components). CV_32S, ids 1..K; 0 = not free (or, without
/// a grow limit, reached by no core).
cv::Mat geometricBlobs(const cv::Mat& free_mask, double resolution, const BlobVoteOptions& options);

/// Vote: in every area of `areas` (CV_32S, > 0), the cells labelled room or corridor in `labels` (CV_8U) all take
/// the one of the two whose summed probability (`cell_probs`, CV_32FC3) over those cells is larger, provided its
/// share is at least `min_share`; doorway cells (unless `vote_doorway_cells`: then they count and are voted too)
/// and cells outside areas keep their labels. Ties go to room.
cv::Mat voteLabelsInAreas(const cv::Mat& labels, const cv::Mat& areas, const cv::Mat& cell_probs,
                          double min_share = 0.5, bool vote_doorway_cells = false);

/// Step 7b, the blob vote: geometricBlobs of the labelled cells of `labels` (CV_8U, kNoLabel = not free), then
/// voteLabelsInAreas with the per-cell relaxed probabilities (cellProbabilities of lattice / lattice_probs).
cv::Mat voteInGeometricBlobs(const cv::Mat& labels, double resolution, const BlobVoteOptions& options,
                             const places::Lattice& lattice, const cv::Mat& lattice_probs);

}  // namespace gridtopo::topology
