#pragma once
// The exact Euclidean distance transform of every library (the topology's clearances, robot fit and corridor
// half-widths; the SLAM render's wall agreement; the training tours' clearance; the graph evaluation's holes),
// cache-friendly on large maps. Use it instead of cv::distanceTransform(..., DIST_MASK_PRECISE), which is wrong on
// maps wider than 4 096 cells.
#include <opencv2/core.hpp>

namespace gridtopo {

/// Distance of every cell of `mask` (CV_8U) to the nearest zero cell, in cells (CV_32F): the float of the root of the
/// exact integer squared distance. The same two passes as cv::distanceTransform(mask, out, DIST_L2,
/// DIST_MASK_PRECISE) of OpenCV 4.6 (a column pass of integer distances, then a row pass over the lower envelope of
/// parabolas, Felzenszwalb & Huttenlocher), bit for bit its result on maps up to a few thousand cells a side; but
/// the row pass in integers and doubles (OpenCV squares the column index in a float: beyond 4 096 columns its
/// result goes wrong, zero cells at 1 and errors up to 2.8 cells on the hospital's map), and the column pass walks
/// the image row by row over blocks of columns instead of down one column at a time (on a large map each step of a
/// column is a cache and TLB miss). Both passes run on OpenCV's threads; the result does not depend on their
/// number. No zero cell in a column or row gives large values, as OpenCV's (1e15 squared cells before the root).
cv::Mat preciseDistance(const cv::Mat& mask);

/// The cells whose preciseDistance is at most `max_distance` (cells): CV_8U, 255 there and 0 elsewhere, the very
/// cells of `preciseDistance(mask) <= max_distance` (cv::compare's: the same float of the root of the same integer
/// squared distance against max_distance rounded to a float) without a float image: a column pass of distances capped just beyond the reach (one byte
/// a cell) and, per row, each cell's reach marked as an interval. For small reaches (up to 254 cells); larger ones
/// fall back to preciseDistance.
cv::Mat withinDistance(const cv::Mat& mask, double max_distance);

/// preciseDistance(mask) at one cell, without the image: square rings around `p` are searched for zero cells until
/// a ring lies further than the nearest found (the exact squared distance, the same float); work grows with the
/// square of the distance. For the few cells a step reads (a skeleton's points, a path's cells).
/// With `max_ring` >= 0 the search stops after the ring at that Chebyshev distance: the same value when it is at
/// most `max_ring`, else some value above `max_ring` (+infinity when no zero cell lies within the ring): for a test
/// against a threshold below `max_ring`, at a cost bounded by the threshold.
float preciseDistanceAt(const cv::Mat& mask, cv::Point p, int max_ring = -1);

/// The nearest zero cell of every cell of `mask` (CV_8U) by exact Euclidean distance: CV_32S, its row-major index
/// (y * cols + x; a zero cell's own), -1 when the mask has no zero cell. The same two passes as preciseDistance (a
/// column pass of the nearest zero row, a row pass over the lower envelope of parabolas) keeping where the minimum
/// lies; among cells at the same distance, the one of the leftmost envelope parabola, and within a column the upper
/// one. The distance is the norm of the offset: one 4-byte image instead of a distance and a label image.
cv::Mat nearestZero(const cv::Mat& mask);

}  // namespace gridtopo
