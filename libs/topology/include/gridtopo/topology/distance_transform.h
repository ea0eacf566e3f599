#pragma once
// The exact Euclidean distance transform the topology uses everywhere (clearances, robot fit, corridor half-widths),
// cache-friendly on large maps.
#include <opencv2/core.hpp>

namespace gridtopo::topology {

/// Distance of every cell of `mask` (CV_8U) to the nearest zero cell, in cells (CV_32F): bit for bit
/// cv::distanceTransform(mask, out, DIST_L2, DIST_MASK_PRECISE) of OpenCV 4.6 (the same two passes and the same
/// float arithmetic: a column pass of integer distances, then a row pass over the lower envelope of parabolas), but
/// the column pass walks the image row by row over blocks of columns instead of down one column at a time (on a
/// large map each step of a column is a cache and TLB miss: that pass was a tenth of the hospital map's run). Both
/// passes run on OpenCV's threads; the result does not depend on their number. No zero cell in a column or row
/// gives large values, as OpenCV's (1e15 squared cells before the root).
cv::Mat preciseDistance(const cv::Mat& mask);

}  // namespace gridtopo::topology
