#include "gridtopo/eval/oracle_diagnostics.h"

#include <opencv2/imgproc.hpp>

#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/blob_vote.h"

namespace gridtopo::eval {

cv::Mat groundTruthRegions(const cv::Mat& truth_codes, const cv::Mat& labels, std::vector<int>* region_label) {
  CV_Assert(truth_codes.type() == CV_8U && labels.type() == CV_8U && truth_codes.size() == labels.size());
  cv::Mat out(labels.size(), CV_32S, cv::Scalar(0));
  if (region_label) region_label->assign(1, -1);
  int offset = 0;
  for (int l = 0; l < places::kNumLabels; ++l) {
    cv::Mat mask = (truth_codes == places::labelCode(l)) & (labels < places::kNumLabels), cc;
    const int n = cv::connectedComponents(mask, cc, 8, CV_32S);
    for (int y = 0; y < cc.rows; ++y)
      for (int x = 0; x < cc.cols; ++x)
        if (const int c = cc.at<int>(y, x)) out.at<int>(y, x) = offset + c;
    if (region_label) region_label->insert(region_label->end(), static_cast<std::size_t>(n - 1), l);
    offset += n - 1;
  }
  return out;
}

cv::Mat oracleRegionVote(const cv::Mat& truth_codes, const cv::Mat& labels, const cv::Mat& cell_probs,
                         bool keep_predicted_doorways) {
  std::vector<int> region_label;
  cv::Mat regions = groundTruthRegions(truth_codes, labels, &region_label);
  for (int y = 0; y < regions.rows; ++y)
    for (int x = 0; x < regions.cols; ++x) {
      int& r = regions.at<int>(y, x);
      if (r > 0 && region_label[static_cast<std::size_t>(r)] == static_cast<int>(places::PlaceLabel::Doorway)) r = 0;  // doorway regions: not voted
    }
  return topology::voteLabelsInAreas(labels, regions, cell_probs, 0.5, !keep_predicted_doorways);
}

cv::Mat blobOracleVote(const cv::Mat& truth_codes, const cv::Mat& labels, const cv::Mat& blobs) {
  cv::Mat truth_onehot(labels.size(), CV_32FC3, cv::Scalar::all(0));
  for (int r = 0; r < truth_onehot.rows; ++r)
    for (int c = 0; c < truth_onehot.cols; ++c) {
      const int t = places::labelFromCode(truth_codes.at<unsigned char>(r, c));
      if (t >= 0) truth_onehot.at<cv::Vec3f>(r, c)[t] = 1.0f;
    }
  return topology::voteLabelsInAreas(labels, blobs, truth_onehot);
}

}  // namespace gridtopo::eval
