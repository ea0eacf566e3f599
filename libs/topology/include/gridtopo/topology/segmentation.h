#pragma once
// Room segmentation from place regions: every room and corridor region is one segment (so rooms are split
// wherever a doorway region separates them), and every doorway cell joins the nearest segment across the
// doorway (multi-source breadth-first growth inside the doorway regions, 8-connected).
#include <opencv2/core.hpp>

#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

/// CV_32S image, same size as the labels: segment id 1..K for every labelled cell, 0 elsewhere. Ids follow
/// region order. A doorway region touching no room / corridor becomes its own segment.
cv::Mat roomSegmentation(const RegionMap& regions);
/// The same with rule S0: room and corridor regions touching along more than `merge_contact_m` are one segment.
/// `sixteen_bits`: CV_16U instead when every id fits (half the memory of a large map's segmentation).
cv::Mat roomSegmentation(const RegionMap& regions, double merge_contact_m, double resolution,
                         bool sixteen_bits = false);

/// Room segmentation where only doorways separate places: every 8-connected component of non-doorway cells
/// (room and corridor cells together) is one segment, doorway cells join the nearest segment as above.
/// Room / corridor confusions inside a place then cannot split it; a missed doorway merges two places.
cv::Mat doorwaySegmentation(const RegionMap& regions, bool sixteen_bits = false);

/// Rule S1 (neck split): a segment whose free area falls apart into two or more large parts when every cell
/// closer than neck_width / 2 to the segment's border is removed (i.e. the parts are joined only through
/// passages narrower than neck_width, such as a door the classifier missed) is split: every part of at least
/// `min_part_area` m^2 seeds a new segment and the seeds grow back over the segment's cells (breadth-first,
/// 8-connected, so the split runs through the middle of the neck). Cells of a segment reached by no seed keep
/// the segment's id.
struct SegmentationRules {
  /// m; rule S0 (regions mode): a room and a corridor region that touch along more than this (border length
  /// = 8-neighbour cell pairs / 3 x resolution) without a doorway between them are one place (an open area
  /// cut by a room / corridor confusion; a room reached through a missed door touches the corridor only along
  /// the door's width). 0 = off.
  double merge_contact = 5.0;
  double neck_width = 1.3;     ///< m; rule S1; 0 = off
  double min_part_area = 0.5;  ///< m^2, minimum area of each part (after removing the border band)
  /// m^2; rule S1: obstacles enclosed by a segment (4-connected blobs of non-free cells surrounded by the
  /// segment's cells, touching no other segment) up to this area count as part of the segment when the necks are
  /// measured: furniture standing in a room (chairs, tables, pillars) is not a wall, and the band around every
  /// chair would otherwise cut a furnished room into pieces too small to split at its door. Kept small: wall
  /// stubs between two doors of one wall are enclosed obstacles too (lab_ipa), and filling them joins rooms.
  /// 0 = off.
  double fill_obstacle_area = 0.25;
  /// Segment vote (a label correction after the segmentation, not part of relaxation): inside every segment, the
  /// room and corridor cells all take the one of the two labels that has more cells in the segment (doorway
  /// cells keep theirs). A room is one place, so one label; used by buildTopology when true.
  bool segment_vote = false;
};
/// Returns the split segmentation (new segments get ids after the current maximum).
cv::Mat splitAtNecks(const cv::Mat& segmentation, double resolution, const SegmentationRules& options);
/// The same split written into `segmentation` itself (no second full-map image); CV_32S or CV_16U (turned CV_32S
/// when the new ids no longer fit 16 bits).
void splitAtNecksInPlace(cv::Mat& segmentation, double resolution, const SegmentationRules& options);

/// Segment vote (see SegmentationRules::segment_vote): copy of `labels` (CV_8U place labels) where, in every
/// segment of `segmentation` (CV_32S), the room and corridor cells take the majority label of the two.
cv::Mat voteLabelsInSegments(const cv::Mat& labels, const cv::Mat& segmentation);

/// Number of segments (max id). `segmentation` CV_32S or CV_16U.
int segmentCount(const cv::Mat& segmentation);

}  // namespace gridtopo::topology
