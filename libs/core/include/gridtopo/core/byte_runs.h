#pragma once
// An 8-bit image held as runs of equal values, row by row, without the cells of one background value: what a run
// keeps of a whole-map image it needs again only at the end (the hospital map's labels before the correction: 56 MB
// as an image, about 2 MB as runs; its occupancy while the topology is built).
#include <opencv2/core.hpp>

#include <algorithm>
#include <vector>

namespace gridtopo {

struct ByteRuns {
  struct Run {
    int x0, x1;           ///< cells x0..x1 of the row (inclusive)
    unsigned char value;  ///< their value (never the background)
  };
  cv::Size size;                       ///< the image's size (cells)
  unsigned char background = 0;        ///< the value of every cell outside the runs
  std::vector<std::size_t> row_begin;  ///< the runs of row y are runs[row_begin[y] .. row_begin[y + 1])
  std::vector<Run> runs;

  /// The runs of the cells of `image` (CV_8U) whose value is not `background`, placed at `offset` in an image of
  /// `size` (the whole of `image` when `size` is empty).
  static ByteRuns of(const cv::Mat& image, unsigned char background, cv::Point offset = {}, cv::Size size = {});
  bool empty() const { return size.empty(); }
  /// Row `y` into `out` (size.width bytes), each cell's value through `map` (the background's too).
  template <class Map>
  void row(int y, unsigned char* out, Map map) const {
    std::fill(out, out + size.width, map(background));
    for (std::size_t i = row_begin[static_cast<std::size_t>(y)]; i < row_begin[static_cast<std::size_t>(y) + 1]; ++i)
      std::fill(out + runs[i].x0, out + runs[i].x1 + 1, map(runs[i].value));
  }
  /// The image again.
  cv::Mat image() const;
};

}  // namespace gridtopo
