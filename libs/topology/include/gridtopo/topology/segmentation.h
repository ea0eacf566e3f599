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

/// Room segmentation where only doorways separate places: every 8-connected component of non-doorway cells
/// (room and corridor cells together) is one segment, doorway cells join the nearest segment as above.
/// Room / corridor confusions inside a place then cannot split it; a missed doorway merges two places.
cv::Mat doorwaySegmentation(const RegionMap& regions);

/// Number of segments (max id).
int segmentCount(const cv::Mat& segmentation);

}  // namespace gridtopo::topology
