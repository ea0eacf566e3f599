#include "gridtopo/simtrain/slam_training_map.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/simtrain/training_map.h"
#include "gridtopo/slam/pose2.h"
#include "gridtopo/slam/slam_run.h"

namespace gridtopo::simtrain {

namespace {

constexpr int kFreeGrey = 204;     // the topology's grid_free_threshold for SLAM maps
constexpr int kOccupiedGrey = 50;  // places::occupancyFromGrey's occupied threshold

slam::Pose2 toPose2(const mrpt::math::TPose2D& p) { return {p.x, p.y, p.phi}; }

}  // namespace

SlamTrainingMap runSlamInPlanFrame(const sim::SimLog& log, const mrpt::math::TPose2D& start, int rows, int cols,
                                   const slam::SlamOptions& options,
                                   const std::function<void(std::size_t, std::size_t)>& progress) {
  auto scans = std::make_shared<const std::vector<ScanRecord>>(log.records);
  slam::SlamRun run(scans, options);
  run.filter().setInitialPose(toPose2(start));
  run.runToEnd(progress);
  SlamTrainingMap out;
  out.trajectory = run.filter().trajectory();
  out.processed_scans = run.filter().stepsProcessed();
  out.grey = mapInPlanFrame(run.filter().bestParticle().map, rows, cols);
  return out;
}

double labelTransferAgreement(const cv::Mat& map_grey, const cv::Mat& codes, double res,
                              const std::vector<TimedPose>& slam_poses,
                              const std::vector<mrpt::math::TPose2D>& true_poses, std::size_t* labelled) {
  if (slam_poses.size() != true_poses.size())
    throw std::invalid_argument("labelTransferAgreement: SLAM and true poses differ in number");
  const int rows = map_grey.rows, cols = map_grey.cols;
  const auto pixelOf = [&](double x, double y) { return cv::Point(static_cast<int>(std::floor(x / res)),
                                                                  rows - 1 - static_cast<int>(std::floor(y / res))); };
  const cv::Rect inside(0, 0, cols, rows);
  // The SLAM pose nearest to every cell: a distance transform from the cells of the poses, one label per cell.
  cv::Mat seeds(rows, cols, CV_8U, cv::Scalar(255));
  std::vector<cv::Point> at;
  std::vector<std::size_t> pose_at;
  for (std::size_t i = 0; i < slam_poses.size(); ++i) {
    const cv::Point p = pixelOf(slam_poses[i].pose.x, slam_poses[i].pose.y);
    if (!inside.contains(p) || seeds.at<unsigned char>(p) == 0) continue;  // the first pose of a cell stands for it
    seeds.at<unsigned char>(p) = 0;
    at.push_back(p);
    pose_at.push_back(i);
  }
  if (labelled) *labelled = 0;
  if (at.empty()) return 0.0;
  cv::Mat dist, nearest;
  cv::distanceTransform(seeds, dist, nearest, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  std::vector<std::size_t> pose_of_label(at.size() + 1, 0);
  for (std::size_t k = 0; k < at.size(); ++k) {
    const int l = nearest.at<int>(at[k]);
    if (l >= static_cast<int>(pose_of_label.size())) pose_of_label.resize(l + 1, 0);
    pose_of_label[l] = pose_at[k];
  }
  std::size_t count = 0, agree = 0;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      if (map_grey.at<unsigned char>(r, c) < kFreeGrey) continue;
      const std::size_t i = pose_of_label[nearest.at<int>(r, c)];
      const slam::Pose2 cell{(c + 0.5) * res, (rows - r - 0.5) * res, 0.0};
      const slam::Pose2 shown =
          slam::compose(toPose2(true_poses[i]), slam::relative(toPose2(slam_poses[i].pose), cell));
      const cv::Point q = pixelOf(shown.x, shown.y);
      const int truth = inside.contains(q) ? codes.at<unsigned char>(q) : 0;
      const int transferred = codes.at<unsigned char>(r, c);
      if (truth == 0 && transferred == 0) continue;
      ++count;
      agree += truth == transferred;
    }
  if (labelled) *labelled = count;
  return count ? static_cast<double>(agree) / count : 0.0;
}

SlamDrift measureSlamDrift(const cv::Mat& map_grey, const cv::Mat& plan_free, const cv::Mat& codes, double res,
                           const std::vector<TimedPose>& slam_poses,
                           const std::vector<mrpt::math::TPose2D>& true_poses) {
  SlamDrift d;
  if (slam_poses.size() != true_poses.size() || slam_poses.empty())
    throw std::invalid_argument("measureSlamDrift: SLAM and true poses differ in number or are empty");
  for (std::size_t i = 0; i < slam_poses.size(); ++i)
    d.max_position_error = std::max(d.max_position_error, std::hypot(slam_poses[i].pose.x - true_poses[i].x,
                                                                     slam_poses[i].pose.y - true_poses[i].y));
  const auto& s = slam_poses.back().pose;
  const auto& t = true_poses.back();
  d.final_position_error = std::hypot(s.x - t.x, s.y - t.y);
  d.final_heading_error = std::abs(slam::wrapAngle(s.phi - t.phi));
  // Occupied map cells near a plan wall: the plan's non-free cells grown by 1 and 2 cells.
  const cv::Mat wall = plan_free == 0;
  cv::Mat near1, near2;
  cv::dilate(wall, near1, cv::Mat::ones(3, 3, CV_8U));
  cv::dilate(wall, near2, cv::Mat::ones(5, 5, CV_8U));
  std::size_t n1 = 0, n2 = 0;
  for (int r = 0; r < map_grey.rows; ++r)
    for (int c = 0; c < map_grey.cols; ++c) {
      if (map_grey.at<unsigned char>(r, c) > kOccupiedGrey) continue;
      ++d.occupied_cells;
      n1 += near1.at<unsigned char>(r, c) != 0;
      n2 += near2.at<unsigned char>(r, c) != 0;
    }
  d.occupied_within_1 = d.occupied_cells ? static_cast<double>(n1) / d.occupied_cells : 0.0;
  d.occupied_within_2 = d.occupied_cells ? static_cast<double>(n2) / d.occupied_cells : 0.0;
  d.label_agreement = labelTransferAgreement(map_grey, codes, res, slam_poses, true_poses, &d.labelled_free_cells);
  return d;
}

}  // namespace gridtopo::simtrain
