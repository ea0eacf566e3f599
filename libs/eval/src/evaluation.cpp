#include "gridtopo/eval/evaluation.h"

#include <map>
#include <opencv2/imgproc.hpp>
#include <sstream>

namespace gridtopo::eval {

void ConfusionMatrix::add(const cv::Mat& truth, const cv::Mat& pred) {
  CV_Assert(truth.size() == pred.size() && truth.type() == CV_8U && pred.type() == CV_8U);
  for (int y = 0; y < truth.rows; ++y)
    for (int x = 0; x < truth.cols; ++x) {
      const int t = places::labelFromCode(truth.at<unsigned char>(y, x));
      if (t < 0) continue;
      const int p = pred.at<unsigned char>(y, x);
      if (p >= places::kNumLabels) { ++unpredicted; continue; }
      ++count[static_cast<std::size_t>(t)][static_cast<std::size_t>(p)];
    }
}

void ConfusionMatrix::add(const ConfusionMatrix& o) {
  for (int a = 0; a < places::kNumLabels; ++a)
    for (int b = 0; b < places::kNumLabels; ++b) count[a][b] += o.count[a][b];
  unpredicted += o.unpredicted;
}

long long ConfusionMatrix::total() const {
  long long s = 0;
  for (const auto& r : count)
    for (long long v : r) s += v;
  return s;
}

double ConfusionMatrix::accuracy() const {
  long long c = 0;
  for (int a = 0; a < places::kNumLabels; ++a) c += count[a][a];
  return total() ? static_cast<double>(c) / static_cast<double>(total()) : 0.0;
}

double ConfusionMatrix::precision(int l) const {
  long long s = 0;
  for (int a = 0; a < places::kNumLabels; ++a) s += count[a][l];
  return s ? static_cast<double>(count[l][l]) / static_cast<double>(s) : 0.0;
}

double ConfusionMatrix::recall(int l) const {
  long long s = 0;
  for (int b = 0; b < places::kNumLabels; ++b) s += count[l][b];
  return s ? static_cast<double>(count[l][l]) / static_cast<double>(s) : 0.0;
}

std::string ConfusionMatrix::toJson(int indent) const {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::ostringstream o;
  o << "{\n" << pad << "  \"labels\": [\"room\", \"corridor\", \"doorway\"],\n" << pad
    << "  \"confusion_truth_by_predicted\": [";
  for (int a = 0; a < places::kNumLabels; ++a)
    o << (a ? ", " : "") << "[" << count[a][0] << ", " << count[a][1] << ", " << count[a][2] << "]";
  o << "],\n" << pad << "  \"accuracy\": " << accuracy() << ",\n" << pad << "  \"precision\": [" << precision(0) << ", "
    << precision(1) << ", " << precision(2) << "],\n" << pad << "  \"recall\": [" << recall(0) << ", " << recall(1) << ", "
    << recall(2) << "],\n" << pad << "  \"cells\": " << total() << ",\n" << pad << "  \"unpredicted_cells\": " << unpredicted
    << "\n" << pad << "}";
  return o.str();
}

cv::Mat groundTruthRooms(const cv::Mat& gt_image) {
  cv::Mat grey = gt_image;
  if (gt_image.channels() == 3) cv::cvtColor(gt_image, grey, cv::COLOR_BGR2GRAY);
  else if (gt_image.channels() == 4) cv::cvtColor(gt_image, grey, cv::COLOR_BGRA2GRAY);
  cv::Mat cc, stats, cents;
  const int n = cv::connectedComponentsWithStats(grey > 250, cc, stats, cents, 8, CV_32S);
  std::vector<int> remap(static_cast<std::size_t>(n), 0);
  int next = 0;
  for (int k = 1; k < n; ++k)
    if (stats.at<int>(k, cv::CC_STAT_AREA) > 100) remap[static_cast<std::size_t>(k)] = ++next;
  for (int y = 0; y < cc.rows; ++y)
    for (int x = 0; x < cc.cols; ++x) cc.at<int>(y, x) = remap[static_cast<std::size_t>(cc.at<int>(y, x))];
  return cc;
}

SegmentationScore scoreSegmentation(const cv::Mat& seg, const cv::Mat& gt) {
  CV_Assert(seg.size() == gt.size() && seg.type() == CV_32S && gt.type() == CV_32S);
  std::map<std::pair<int, int>, long long> overlap;
  std::map<int, long long> seg_size, gt_size;
  for (int y = 0; y < seg.rows; ++y)
    for (int x = 0; x < seg.cols; ++x) {
      const int s = seg.at<int>(y, x), g = gt.at<int>(y, x);
      if (s) ++seg_size[s];
      if (g) ++gt_size[g];
      if (s && g) ++overlap[{s, g}];
    }
  std::map<int, long long> best_s, best_g;
  for (const auto& [k, v] : overlap) {
    best_s[k.first] = std::max(best_s[k.first], v);
    best_g[k.second] = std::max(best_g[k.second], v);
  }
  SegmentationScore sc;
  sc.segments = static_cast<int>(seg_size.size());
  sc.rooms = static_cast<int>(gt_size.size());
  long long sum_s = 0, sum_g = 0, ov_s = 0, ov_g = 0;
  for (const auto& [s, n] : seg_size) {
    sc.precision += static_cast<double>(best_s[s]) / static_cast<double>(n);
    sum_s += n, ov_s += best_s[s];
  }
  for (const auto& [g, n] : gt_size) {
    sc.recall += static_cast<double>(best_g[g]) / static_cast<double>(n);
    sum_g += n, ov_g += best_g[g];
  }
  if (sc.segments) sc.precision /= sc.segments;
  if (sc.rooms) sc.recall /= sc.rooms;
  sc.precision_weighted = sum_s ? static_cast<double>(ov_s) / static_cast<double>(sum_s) : 0.0;
  sc.recall_weighted = sum_g ? static_cast<double>(ov_g) / static_cast<double>(sum_g) : 0.0;
  return sc;
}

std::string SegmentationScore::toJson() const {
  std::ostringstream o;
  o << "{\"segments\": " << segments << ", \"rooms\": " << rooms << ", \"precision\": " << precision
    << ", \"recall\": " << recall << ", \"precision_weighted\": " << precision_weighted
    << ", \"recall_weighted\": " << recall_weighted << "}";
  return o.str();
}

}  // namespace gridtopo::eval
