#pragma once
// Diagnostics of the label votes (gridtopo-topology-eval): what a vote could reach with the ground truth's regions
// or majorities, to tell a weak vote from weak labels.
#include <opencv2/core.hpp>

#include <vector>

namespace gridtopo::eval {

/// Ground-truth regions: 8-connected components of equal place code in `truth_codes` (CV_8U, codes 77/115/179)
/// restricted to cells with a label 0..2 in `labels`. CV_32S ids 1..K; `region_label` receives each id's label.
cv::Mat groundTruthRegions(const cv::Mat& truth_codes, const cv::Mat& labels, std::vector<int>* region_label = nullptr);

/// Oracle region vote (evaluation diagnostic): every labelled cell of a room or corridor ground-truth region
/// takes the room / corridor majority (summed `cell_probs`) of the region; with `keep_predicted_doorways`, cells
/// predicted doorway keep that label (the ceiling of a vote that, like the blob vote, leaves doorways alone).
/// Cells of doorway ground-truth regions keep their predicted label.
cv::Mat oracleRegionVote(const cv::Mat& truth_codes, const cv::Mat& labels, const cv::Mat& cell_probs,
                         bool keep_predicted_doorways = false);

/// The blob oracle: the room / corridor labels of `labels` voted in every geometric blob of `blobs` (CV_32S) with
/// the blob's true majority (the ground-truth codes `truth_codes` as one-hot probabilities): the ceiling of the blob
/// vote (topology::voteInGeometricBlobs) for these blobs.
cv::Mat blobOracleVote(const cv::Mat& truth_codes, const cv::Mat& labels, const cv::Mat& blobs);

}  // namespace gridtopo::eval
