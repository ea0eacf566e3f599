#pragma once
// Scoring a map of one building against a labelled reference map of the same building drawn in another frame
// (other origin, orientation, scale, possibly mirrored): e.g. the Intel map that gridtopo-slam builds against the
// labelled `lab_intel` floor plan and its room-segmentation ground truth.
//
// The alignment maximises the enhanced correlation coefficient of the two free-space masks (Evangelidis and
// Psarakis, IEEE PAMI 2008; OpenCV's findTransformECC) over an affine warp, started from each of the 8 axis-aligned
// orientations (4 rotations, with and without mirroring) with the scale of the free areas and the centroids
// matched; the start with the highest correlation wins.
#include <opencv2/core.hpp>

#include <string>

#include "gridtopo/eval/evaluation.h"

namespace gridtopo::eval {

struct ReferenceAlignment {
  cv::Matx23d map_to_reference;  ///< affine warp: map pixel (x, y) -> reference pixel
  double correlation = 0;        ///< ECC of the free-space masks at the optimum, in [-1, 1]
  int start = 0;                 ///< which of the 8 orientations it started from (bit 2: mirrored, bits 0-1: k * 90°)
};

/// Aligns `reference_free` to `map_free` (CV_8U masks, non-zero = free). Throws InputError (naming `source`) if a
/// mask is empty or no start converges.
ReferenceAlignment alignReference(const cv::Mat& map_free, const cv::Mat& reference_free,
                                  const std::string& source = "<reference>");

/// The identity (a reference pixel-aligned with the map, of the same size), with the ECC of the two masks as they
/// lie as its correlation.
ReferenceAlignment identityAlignment(const cv::Mat& map_free, const cv::Mat& reference_free);
/// Resamples a reference image (CV_8U or CV_32S ids) into the map's frame (nearest neighbour; 0 outside).
cv::Mat warpReferenceToMap(const cv::Mat& reference, const ReferenceAlignment& a, cv::Size map_size);

struct ReferenceScore {
  ReferenceAlignment alignment;
  ConfusionMatrix labels;        ///< reference codes vs our labels, over cells free in the map
  SegmentationScore segmentation;  ///< our segments vs the reference rooms, both cut to the map's free cells
};

/// Scores `labels` (CV_8U, place labels 0..2 or places::kNoLabel) and `segments` (CV_32S, 0 = none) of a map whose
/// free cells are `map_free` against the reference: `reference_codes` (room 77 / corridor 115 / doorway 179) and
/// `reference_rooms` (groundTruthRooms of the reference's ground truth), both in the frame of `reference_free`.
/// Ground-truth rooms with fewer than `min_room_cells` free map cells are left out. Alignment errors name `source`.
ReferenceScore scoreAgainstReference(const cv::Mat& map_free, const cv::Mat& labels, const cv::Mat& segments,
                                     const cv::Mat& reference_free, const cv::Mat& reference_codes,
                                     const cv::Mat& reference_rooms, int min_room_cells = 100,
                                     const std::string& source = "<reference>");

/// The same scores with a known alignment (e.g. the labels and segmentation the plan's own labels give on the map,
/// scored with the alignment scoreAgainstReference found for the map).
ReferenceScore scoreAligned(const cv::Mat& map_free, const cv::Mat& labels, const cv::Mat& segments,
                            const cv::Mat& reference_codes, const cv::Mat& reference_rooms,
                            const ReferenceAlignment& alignment, int min_room_cells = 100);

}  // namespace gridtopo::eval
