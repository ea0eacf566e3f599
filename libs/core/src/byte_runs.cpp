#include "gridtopo/core/byte_runs.h"

namespace gridtopo {

ByteRuns ByteRuns::of(const cv::Mat& image, unsigned char background, cv::Point offset, cv::Size size) {
  CV_Assert(image.type() == CV_8U);
  ByteRuns r;
  r.size = size.empty() ? image.size() : size;
  r.background = background;
  CV_Assert(offset.x >= 0 && offset.y >= 0 && offset.x + image.cols <= r.size.width &&
            offset.y + image.rows <= r.size.height);
  r.row_begin.assign(static_cast<std::size_t>(r.size.height) + 1, 0);
  for (int y = 0; y < image.rows; ++y) {
    const unsigned char* v = image.ptr<unsigned char>(y);
    for (int x = 0; x < image.cols;) {
      if (v[x] == background) {
        ++x;
        continue;
      }
      int e = x;
      while (e + 1 < image.cols && v[e + 1] == v[x]) ++e;
      r.runs.push_back({offset.x + x, offset.x + e, v[x]});
      x = e + 1;
    }
    r.row_begin[static_cast<std::size_t>(offset.y + y) + 1] = r.runs.size();
  }
  for (std::size_t y = 1; y < r.row_begin.size(); ++y) r.row_begin[y] = std::max(r.row_begin[y], r.row_begin[y - 1]);
  r.runs.shrink_to_fit();
  return r;
}

cv::Mat ByteRuns::image() const {
  cv::Mat out(size, CV_8U);
  for (int y = 0; y < size.height; ++y) row(y, out.ptr<unsigned char>(y), [](unsigned char v) { return v; });
  return out;
}

}  // namespace gridtopo
