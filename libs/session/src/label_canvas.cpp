#include "gridtopo/session/label_canvas.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"

namespace gridtopo::session {

void LabelCanvas::reset(const cv::Mat& grey, int free_threshold) {
  CV_Assert(grey.type() == CV_8UC1);
  codes_ = cv::Mat(grey.size(), CV_8U, cv::Scalar(0));
  cv::compare(grey, cv::Scalar(free_threshold), free_, cv::CMP_GE);
  free_ /= 255;
  undo_.clear();
  in_stroke_ = false;
}

void LabelCanvas::load(const std::string& path) {
  if (free_.empty()) throw InputError(path, "open a map before its label image");
  cv::Mat img = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (img.empty()) throw InputError(path, "cannot read the image");
  if (img.depth() != CV_8U) throw InputError(path, "not an 8-bit image");
  if (img.channels() == 3) cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
  else if (img.channels() == 4) cv::cvtColor(img, img, cv::COLOR_BGRA2GRAY);
  if (img.size() != free_.size())
    throw InputError(path, "label image is " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                               " but the map is " + std::to_string(free_.cols) + "x" + std::to_string(free_.rows));
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c)
      if (!isTrainingCode(img.at<unsigned char>(r, c)))
        throw InputError(path, 0, "pixel (" + std::to_string(c) + ", " + std::to_string(r) + ")",
                         "value " + std::to_string(img.at<unsigned char>(r, c)) +
                             " is not a training code (room 77, corridor 115, doorway 179, other 0)");
  codes_ = img;
  undo_.clear();
  in_stroke_ = false;
}

void LabelCanvas::save(const std::string& path) const {
  if (codes_.empty()) throw std::runtime_error("no label canvas to save");
  writeFileAtomically(path, [&](const std::string& tmp) {
    if (!cv::imwrite(tmp, codes_)) throw std::runtime_error("cannot write " + tmp);
  });
}

void LabelCanvas::pushPatch(const cv::Rect& r) {
  if (!in_stroke_) undo_.emplace_back();
  if (undo_.empty()) undo_.emplace_back();
  undo_.back().push_back({r, codes_(r).clone()});
  if (undo_.size() > max_undo_) undo_.erase(undo_.begin());
}

void LabelCanvas::beginStroke() {
  if (in_stroke_) return;
  undo_.emplace_back();
  in_stroke_ = true;
  if (undo_.size() > max_undo_) undo_.erase(undo_.begin());
}

void LabelCanvas::endStroke() {
  if (!in_stroke_) return;
  in_stroke_ = false;
  if (!undo_.empty() && undo_.back().empty()) undo_.pop_back();
}

int LabelCanvas::brush(int row, int col, int radius, unsigned char code, bool free_only) {
  if (codes_.empty() || radius < 0) return 0;
  const cv::Rect r = cv::Rect(col - radius, row - radius, 2 * radius + 1, 2 * radius + 1) &
                     cv::Rect(0, 0, codes_.cols, codes_.rows);
  if (r.empty()) return 0;
  int changed = 0;
  bool pushed = false;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) {
      if ((x - col) * (x - col) + (y - row) * (y - row) > radius * radius) continue;
      if (free_only && !free_.at<unsigned char>(y, x)) continue;
      unsigned char& v = codes_.at<unsigned char>(y, x);
      if (v == code) continue;
      if (!pushed) pushPatch(r), pushed = true;
      v = code;
      ++changed;
    }
  return changed;
}

int LabelCanvas::floodFill(int row, int col, unsigned char code) {
  if (codes_.empty() || row < 0 || col < 0 || row >= codes_.rows || col >= codes_.cols) return 0;
  if (!free_.at<unsigned char>(row, col)) return 0;
  const unsigned char seed = codes_.at<unsigned char>(row, col);
  if (seed == code) return 0;
  // Region: 4-connected free cells with the seed's code. Mask (1 px border) blocks everything else.
  cv::Mat same;
  cv::compare(codes_, cv::Scalar(seed), same, cv::CMP_EQ);
  cv::Mat blocked = (same & (free_ * 255)) == 0;  // 255 where the fill must not go
  cv::Mat mask(codes_.rows + 2, codes_.cols + 2, CV_8U, cv::Scalar(1));
  blocked.convertTo(mask(cv::Rect(1, 1, codes_.cols, codes_.rows)), CV_8U, 1.0 / 255);
  cv::Mat before = codes_.clone();
  cv::Rect box;
  const int n = cv::floodFill(codes_, mask, cv::Point(col, row), cv::Scalar(code), &box, cv::Scalar(0),
                              cv::Scalar(0), 4 | cv::FLOODFILL_FIXED_RANGE);
  if (n > 0) {
    const bool was = in_stroke_;
    if (!was) undo_.emplace_back();
    undo_.back().push_back({box, before(box).clone()});
    if (undo_.size() > max_undo_) undo_.erase(undo_.begin());
  }
  return n;
}

bool LabelCanvas::undo() {
  if (in_stroke_) endStroke();
  while (!undo_.empty() && undo_.back().empty()) undo_.pop_back();
  if (undo_.empty()) return false;
  const Step& s = undo_.back();
  for (auto it = s.rbegin(); it != s.rend(); ++it) it->before.copyTo(codes_(it->rect));
  undo_.pop_back();
  return true;
}

std::vector<long> LabelCanvas::histogram() const {
  std::vector<long> h(4, 0);
  for (int r = 0; r < codes_.rows; ++r)
    for (int c = 0; c < codes_.cols; ++c) {
      if (!free_.at<unsigned char>(r, c)) continue;
      const unsigned char v = codes_.at<unsigned char>(r, c);
      h[v == 77 ? 1 : v == 115 ? 2 : v == 179 ? 3 : 0]++;
    }
  return h;
}

}  // namespace gridtopo::session
