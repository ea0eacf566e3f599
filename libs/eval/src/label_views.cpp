#include "gridtopo/eval/label_views.h"

#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/export.h"

namespace gridtopo::eval {

namespace {
const cv::Vec3b kNotFree(110, 110, 110);
}

cv::Mat segmentationView(const places::OccupancyImage& occ, const cv::Mat& segments, const cv::Mat& gt_rooms) {
  cv::Mat out = topology::colourSegmentation(segments);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      cv::Vec3b& o = out.at<cv::Vec3b>(r, c);
      if (!occ.isFree(r, c)) {
        o = kNotFree;
        continue;
      }
      const int s = segments.at<int>(r, c), g = gt_rooms.at<int>(r, c);
      bool seg_border = false, gt_border = g <= 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int rr = r + dy, cc = c + dx;
          if (rr < 0 || cc < 0 || rr >= out.rows || cc >= out.cols || !occ.isFree(rr, cc)) continue;
          if (segments.at<int>(rr, cc) != s) seg_border = true;
          if (g > 0 && gt_rooms.at<int>(rr, cc) != g) gt_border = true;
        }
      if (gt_border) o = cv::Vec3b(0, 0, 255);
      else if (seg_border) o = cv::Vec3b(0, 0, 0);
    }
  return out;
}

cv::Mat labelsView(const places::OccupancyImage& occ, const cv::Mat& labels) {
  cv::Mat out(labels.size(), CV_8UC3);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      const int l = labels.at<unsigned char>(r, c);
      out.at<cv::Vec3b>(r, c) = !occ.isFree(r, c)       ? kNotFree
                                : l < places::kNumLabels ? topology::kLabelColoursBgr[l]
                                                         : cv::Vec3b(255, 255, 255);
    }
  return out;
}

cv::Mat labelErrorOverlay(const places::OccupancyImage& occ, const cv::Mat& truth_codes, const cv::Mat& predicted) {
  static const cv::Vec3b pale[3] = {{250, 215, 190}, {200, 240, 200}, {200, 200, 250}};
  cv::Mat out(occ.cells.size(), CV_8UC3);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) {
      cv::Vec3b& o = out.at<cv::Vec3b>(r, c);
      o = occ.isFree(r, c) ? cv::Vec3b(255, 255, 255) : cv::Vec3b(90, 90, 90);
      const int t = places::labelFromCode(truth_codes.at<unsigned char>(r, c));
      if (t < 0 || !occ.isFree(r, c)) continue;
      const int p = predicted.at<unsigned char>(r, c);
      if (p >= places::kNumLabels) o = cv::Vec3b(0, 0, 0);
      else o = p == t ? pale[t] : topology::kLabelColoursBgr[p];
    }
  return out;
}

}  // namespace gridtopo::eval
