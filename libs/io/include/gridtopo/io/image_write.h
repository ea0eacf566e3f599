#pragma once
// The SLAM outputs' images written with libpng and by hand (binary PGM) rather than cv::imwrite: OpenCV's first
// imwrite builds its whole codec registry (about 10 MB resident, GDAL's drivers among them), which gridtopo-slam's
// output phase, its peak memory, would otherwise pay for three small images. Atomic: a temporary file beside
// `path`, renamed over it once complete.
#include <opencv2/core.hpp>

#include <functional>
#include <string>

namespace gridtopo::io {

/// A PNG of an 8-bit grey (CV_8UC1) or BGR (CV_8UC3) image: the same pixels cv::imwrite writes (zlib level 1 and
/// run-length strategy, OpenCV's defaults). std::invalid_argument for another type or an empty image;
/// std::runtime_error naming the file when it cannot be written.
void writePng(const cv::Mat& image, const std::string& path);

/// A PNG of `size` pixels whose rows come from `row(y, buffer)` one at a time (top to bottom; `buffer` holds
/// size.width pixels of `type`: CV_8UC1, CV_8UC3 as BGR, or CV_16UC1), so that no image of the whole picture is
/// made: for pictures of a map computed on a part of it (TopologyResult::frame). Same encoding and errors as
/// writePng.
void writePngRows(const std::string& path, cv::Size size, int type,
                  const std::function<void(int y, unsigned char* buffer)>& row);

/// A binary PGM (P5, maxval 255) of an 8-bit grey image, byte for byte what cv::imwrite(path, image,
/// {IMWRITE_PXM_BINARY, 1}) writes. Errors as writePng.
void writePgm(const cv::Mat& image, const std::string& path);

}  // namespace gridtopo::io
