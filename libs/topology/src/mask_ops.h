#pragma once
// Mask operations shared by the segmentation rule S1, the blob vote and the corridor pieces (library-internal).
#include <opencv2/core.hpp>

namespace gridtopo::topology {

/// Copy of `mask` (CV_8U, 0 / 255) with its small holes set to 255: the 4-connected components of zero cells that
/// touch no image border, have at most `max_cells` cells and, when `veto` (CV_8U, same size) is given, hold no
/// cell where veto != 0.
cv::Mat fillSmallHoles(const cv::Mat& mask, double max_cells, const cv::Mat& veto = cv::Mat());

/// Multi-source breadth-first growth, 8-connected: the cells of `ids` (CV_32S) > 0 are the seeds (queued in
/// row-major order); each cell reached takes the id of the cell it was reached from. Only cells with
/// allowed != 0 (CV_8U, same size) and ids == 0 are entered; with `max_steps` >= 0, no cell farther than that many
/// steps from its seed.
void growSeeds(cv::Mat& ids, const cv::Mat& allowed, int max_steps = -1);

}  // namespace gridtopo::topology
