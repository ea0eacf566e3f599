#pragma once
// Pictures of a labelled or segmented map for looking at evaluation results (gridtopo-topology-eval --dump-dir).
#include <opencv2/core.hpp>

#include "gridtopo/places/occupancy.h"

namespace gridtopo::eval {

/// A segmentation for viewing: segments in colours (topology::colourSegmentation), segment borders black,
/// non-free cells grey, and the ground-truth room borders (free cells next to another ground-truth room or to a
/// cell outside every room, `gt_rooms` <= 0) red. `segments` and `gt_rooms` are CV_32S of the map's size.
cv::Mat segmentationView(const places::OccupancyImage& occ, const cv::Mat& segments, const cv::Mat& gt_rooms);

/// Labels for viewing: room blue, corridor green, doorway red (topology::kLabelColoursBgr), non-free grey, free
/// unlabelled white. `labels` is CV_8U (0..2, anything else = unlabelled).
cv::Mat labelsView(const places::OccupancyImage& occ, const cv::Mat& labels);

/// Label errors for viewing: non-free cells dark grey, free cells white, labelled free cells pale in their true
/// label's colour when `predicted` (CV_8U labels 0..2, else none) agrees with `truth_codes` (77 / 115 / 179), in the
/// saturated colour of the *predicted* label when it does not (room blue, corridor green, doorway red), black when
/// there is no prediction.
cv::Mat labelErrorOverlay(const places::OccupancyImage& occ, const cv::Mat& truth_codes, const cv::Mat& predicted);

}  // namespace gridtopo::eval
