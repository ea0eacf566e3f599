#include "gridtopo/topology/label_runs.h"

#include "gridtopo/places/place_label.h"

namespace gridtopo::topology {

LabelRuns LabelRuns::of(const cv::Mat& labels, cv::Point offset, cv::Size size) {
  CV_Assert(labels.type() == CV_8U);
  LabelRuns r;
  r.size = size.empty() ? labels.size() : size;
  CV_Assert(cv::Rect(cv::Point(), r.size).contains(offset) || labels.empty());
  CV_Assert(offset.x + labels.cols <= r.size.width && offset.y + labels.rows <= r.size.height);
  r.row_begin.assign(static_cast<std::size_t>(r.size.height) + 1, 0);
  for (int y = 0; y < labels.rows; ++y) {
    const unsigned char* l = labels.ptr<unsigned char>(y);
    for (int x = 0; x < labels.cols;) {
      if (l[x] >= places::kNumLabels) {
        ++x;
        continue;
      }
      int e = x;
      while (e + 1 < labels.cols && l[e + 1] == l[x]) ++e;
      r.runs.push_back({offset.x + x, offset.x + e, l[x]});
      x = e + 1;
    }
    r.row_begin[static_cast<std::size_t>(offset.y + y) + 1] = r.runs.size();
  }
  for (std::size_t y = 1; y < r.row_begin.size(); ++y) r.row_begin[y] = std::max(r.row_begin[y], r.row_begin[y - 1]);
  r.runs.shrink_to_fit();
  return r;
}

cv::Mat LabelRuns::image(unsigned char fill) const {
  cv::Mat out(size, CV_8U);
  for (int y = 0; y < size.height; ++y) row(y, out.ptr<unsigned char>(y), fill, [](unsigned char l) { return l; });
  return out;
}

}  // namespace gridtopo::topology
