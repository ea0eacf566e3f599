#pragma once
// SLAM-like labelled training maps, the SLAM variant (issue 15, item 1): the SLAM (slam::SlamRun, the scan loop of
// gridtopo-slam) runs on a plan's simulated log, starting at the tour's true start pose, so the SLAM's frame is the
// plan's frame up to the drift the SLAM makes. Its map (the best particle's) is placed cell by cell in the plan's
// pixel lattice and takes the plan's labels there: where the SLAM drifted, labels land on the wrong cells. The
// drift is measured against the truth the simulation knows (SlamDrift).
#include <mrpt/math/TPose2D.h>

#include <cstddef>
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "gridtopo/core/scan_record.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/slam/slam_options.h"

namespace gridtopo::simtrain {

/// How far the SLAM map is from the plan it was simulated in.
struct SlamDrift {
  double final_position_error = 0;  ///< m, the SLAM's pose of the last scan against the true pose
  double final_heading_error = 0;   ///< rad, absolute
  double max_position_error = 0;    ///< m, over every scan of the run
  std::size_t occupied_cells = 0;   ///< occupied cells of the SLAM map (grey <= 50) inside the plan's lattice
  double occupied_within_1 = 0;     ///< fraction of them within 1 cell (3 x 3) of a plan wall (non-free plan cell)
  double occupied_within_2 = 0;     ///< ... within 2 cells (5 x 5)
  std::size_t labelled_free_cells = 0;  ///< free map cells (grey >= 204) where the transferred or true label is set
  /// Fraction of those whose transferred label (the plan's label at the cell) is the label of the place the cell
  /// shows (labelTransferAgreement).
  double label_agreement = 0;
};

struct SlamTrainingMap {
  cv::Mat grey;                      ///< CV_8U, the plan's size: the SLAM map as gridtopo-slam writes map.png
  std::vector<TimedPose> trajectory; ///< the SLAM's pose of every scan of the log (RbpfSlam::trajectory)
  std::size_t processed_scans = 0;
};

/// Runs the SLAM with `options` on `log` (its first scan placed at `start`, normally log.truth[0]) and returns the
/// best particle's map in the plan's lattice of rows x cols cells of options.resolution (mapInPlanFrame).
/// `progress(fed, total)` as SlamRun::runToEnd. InputError on bad options.
SlamTrainingMap runSlamInPlanFrame(const sim::SimLog& log, const mrpt::math::TPose2D& start, int rows, int cols,
                                   const slam::SlamOptions& options,
                                   const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The label-transfer check: for every free cell of `map_grey` (grey >= 204), the label of the place it shows is the
/// plan's label at the cell moved by the local drift: the SLAM pose nearest to the cell (in the map) and the true
/// pose of the same scan give the rigid correction truth ⊕ (slam ⊖ cell). Returns the fraction of the free cells,
/// among those with a transferred or a true label, whose transferred label (`codes` at the cell) equals it.
/// `labelled` (optional) gets the number of those cells.
double labelTransferAgreement(const cv::Mat& map_grey, const cv::Mat& codes, double resolution,
                              const std::vector<TimedPose>& slam_poses,
                              const std::vector<mrpt::math::TPose2D>& true_poses, std::size_t* labelled = nullptr);

/// Every SlamDrift figure of a SLAM map in the plan's frame. `plan_free`: CV_8U, non-zero = free plan cell.
SlamDrift measureSlamDrift(const cv::Mat& map_grey, const cv::Mat& plan_free, const cv::Mat& codes, double resolution,
                           const std::vector<TimedPose>& slam_poses,
                           const std::vector<mrpt::math::TPose2D>& true_poses);

}  // namespace gridtopo::simtrain
