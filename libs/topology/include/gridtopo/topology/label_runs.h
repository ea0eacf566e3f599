#pragma once
// A place-label image held as runs of equal labels, row by row: what an output written at the end of a run needs of
// a whole-map label image while the pipeline's large images are alive (the hospital map's labels before the
// correction: 56 MB as an image, about 2 MB as runs).
#include <opencv2/core.hpp>
#include <vector>

namespace gridtopo::topology {

struct LabelRuns {
  struct Run {
    int x0, x1;           ///< cells x0..x1 of the row (inclusive)
    unsigned char label;  ///< places::PlaceLabel
  };
  cv::Size size;                ///< the image's size (cells)
  std::vector<std::size_t> row_begin;  ///< the runs of row y are runs[row_begin[y] .. row_begin[y + 1])
  std::vector<Run> runs;

  /// The runs of the cells of `labels` (CV_8U) with a place label (< places::kNumLabels), placed at `offset` in an
  /// image of `size` (the whole of `labels` when `size` is empty).
  static LabelRuns of(const cv::Mat& labels, cv::Point offset = {}, cv::Size size = {});
  bool empty() const { return size.empty(); }
  /// Row `y` into `out` (size.width bytes): each labelled cell `code(label)`, the others `fill`.
  template <class Code>
  void row(int y, unsigned char* out, unsigned char fill, Code code) const {
    std::fill(out, out + size.width, fill);
    for (std::size_t i = row_begin[static_cast<std::size_t>(y)]; i < row_begin[static_cast<std::size_t>(y) + 1]; ++i)
      std::fill(out + runs[i].x0, out + runs[i].x1 + 1, code(runs[i].label));
  }
  /// The image again: place labels where the runs are, `fill` elsewhere.
  cv::Mat image(unsigned char fill) const;
};

}  // namespace gridtopo::topology
