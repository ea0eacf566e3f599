#pragma once
// Scores: per-cell label accuracy against labelled maps, and room-segmentation precision / recall against the
// ground truth of the room-segmentation benchmark (Bormann et al., ICRA 2016).
#include <array>
#include <opencv2/core.hpp>
#include <string>

#include "gridtopo/places/place_label.h"

namespace gridtopo::eval {

struct ConfusionMatrix {
  std::array<std::array<long long, places::kNumLabels>, places::kNumLabels> count{};  ///< [truth][predicted]
  /// Adds every cell with a place code in `truth_codes` and a label 0..2 in `predicted`; labelled cells that
  /// were not predicted (not free in the map) count as `unpredicted`.
  void add(const cv::Mat& truth_codes, const cv::Mat& predicted);
  void add(const ConfusionMatrix& other);
  long long unpredicted = 0;
  long long total() const;
  double accuracy() const;
  double precision(int label) const;
  double recall(int label) const;
  std::string toJson(int indent = 0) const;
};

/// Ground-truth rooms: each 8-connected region of grey > 250 with more than 100 pixels (CV_32S ids, 0 none).
cv::Mat groundTruthRooms(const cv::Mat& gt_image);

struct SegmentationScore {
  int segments = 0, rooms = 0;
  double precision = 0, recall = 0;                    ///< mean over segments / rooms
  double precision_weighted = 0, recall_weighted = 0;  ///< pixel-weighted means
  std::string toJson() const;
};

/// Per segment: largest overlap with a ground-truth room / segment size; per room: largest overlap with a
/// segment / room size. Both images CV_32S with 0 = nothing, same size.
SegmentationScore scoreSegmentation(const cv::Mat& segments, const cv::Mat& gt_rooms);

}  // namespace gridtopo::eval
