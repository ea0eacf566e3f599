// writePng / writePgm (libpng and a hand-written P5 header instead of cv::imwrite, for the SLAM outputs): the pixels
// OpenCV reads back are the ones written, the PGM is OpenCV's byte for byte, bad input and unwritable files are
// errors that name the file.
#include "gridtopo/io/image_write.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "common/scratch.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
std::string fileBytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
cv::Mat randomImage(int rows, int cols, int type, int seed) {
  cv::Mat m(rows, cols, type);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  // Runs of one value, as in a map (free, unknown, walls), beside the noise.
  m(cv::Rect(0, 0, cols / 2, rows / 3)).setTo(cv::Scalar::all(205));
  return m;
}
int differingValues(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return -1;
  cv::Mat d;
  cv::absdiff(a, b, d);
  return cv::countNonZero(d.reshape(1));
}
}  // namespace

TEST(ImageWrite, PngHoldsThePixelsWrittenGreyAndBgr) {
  const fs::path dir = test::scratch("image_write_png");
  int k = 0;
  for (const auto& [rows, cols] : {std::pair{1, 1}, std::pair{7, 13}, std::pair{300, 517}}) {
    for (const int type : {CV_8UC1, CV_8UC3}) {
      const cv::Mat img = randomImage(rows, cols, type, ++k);
      const fs::path p = dir / ("i" + std::to_string(k) + ".png");
      io::writePng(img, p.string());
      EXPECT_EQ(differingValues(cv::imread(p.string(), cv::IMREAD_UNCHANGED), img), 0) << p;
    }
  }
  // A region of a larger image (rows not contiguous) is written as itself.
  const cv::Mat big = randomImage(60, 80, CV_8UC3, 99);
  const cv::Mat roi = big(cv::Rect(5, 7, 31, 20));
  io::writePng(roi, (dir / "roi.png").string());
  EXPECT_EQ(differingValues(cv::imread((dir / "roi.png").string(), cv::IMREAD_UNCHANGED), roi), 0);
}

TEST(ImageWrite, PgmIsOpenCvsBinaryPgmByteForByte) {
  const fs::path dir = test::scratch("image_write_pgm");
  for (int k = 0; k < 3; ++k) {
    const cv::Mat img = randomImage(1 + 37 * k, 2 + 91 * k, CV_8UC1, k);
    io::writePgm(img, (dir / "ours.pgm").string());
    ASSERT_TRUE(cv::imwrite((dir / "opencv.pgm").string(), img, {cv::IMWRITE_PXM_BINARY, 1}));
    EXPECT_EQ(fileBytes(dir / "ours.pgm"), fileBytes(dir / "opencv.pgm")) << k;
  }
}

TEST(ImageWrite, BadImagesAndUnwritableFilesAreNamedErrors) {
  const fs::path dir = test::scratch("image_write_errors");
  EXPECT_THROW(io::writePng(cv::Mat(), (dir / "a.png").string()), std::invalid_argument);
  EXPECT_THROW(io::writePng(cv::Mat(4, 4, CV_16UC1, cv::Scalar(3)), (dir / "a.png").string()), std::invalid_argument);
  EXPECT_THROW(io::writePgm(cv::Mat(4, 4, CV_8UC3, cv::Scalar(3)), (dir / "a.pgm").string()), std::invalid_argument);
  const std::string inside_a_file = (dir / "file" / "a.png").string();
  std::ofstream(dir / "file") << "x";
  try {
    io::writePng(cv::Mat(4, 4, CV_8UC1, cv::Scalar(3)), inside_a_file);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    // OutputSet names the folder it cannot create, a file here.
    EXPECT_NE(std::string(e.what()).find((dir / "file").string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "a.png"));
  // A folder where the image must go: the error names the image, nothing is left beside it.
  fs::create_directories(dir / "taken.png" / "x");
  try {
    io::writePng(cv::Mat(4, 4, CV_8UC1, cv::Scalar(3)), (dir / "taken.png").string());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "taken.png").string()), std::string::npos) << e.what();
  }
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 2u);  // file, taken.png
}

TEST(ImageWrite, PngRowsHoldThePixelsOfEachRowGreyBgrAnd16Bit) {
  // writePngRows: the picture made row by row from a callback (the topology's label and segmentation pictures of
  // a whole map from the box of its places); 16-bit values above 255 keep their byte order.
  const fs::path dir = test::scratch("image_write_png_rows");
  int k = 0;
  for (const int type : {CV_8UC1, CV_8UC3, CV_16UC1}) {
    cv::Mat img(37, 53, type);
    cv::RNG(static_cast<std::uint64_t>(++k)).fill(img, cv::RNG::UNIFORM, 0, type == CV_16UC1 ? 65536 : 256);
    const fs::path p = dir / ("rows" + std::to_string(k) + ".png");
    io::writePngRows(p.string(), img.size(), type, [&](int y, unsigned char* out) {
      std::copy(img.ptr<unsigned char>(y), img.ptr<unsigned char>(y) + img.cols * img.elemSize(), out);
    });
    EXPECT_EQ(differingValues(cv::imread(p.string(), cv::IMREAD_UNCHANGED), img), 0) << p;
  }
  EXPECT_THROW(io::writePngRows((dir / "f.png").string(), {4, 4}, CV_32FC1, [](int, unsigned char*) {}),
               std::invalid_argument);
  EXPECT_THROW(io::writePngRows((dir / "e.png").string(), {0, 4}, CV_8UC1, [](int, unsigned char*) {}),
               std::invalid_argument);
  // A folder where the picture must go: the error names the picture.
  fs::create_directories(dir / "taken.png" / "x");
  try {
    io::writePngRows((dir / "taken.png").string(), {4, 4}, CV_8UC1, [](int, unsigned char*) {});
    ADD_FAILURE() << "an unwritable file must throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "taken.png").string()), std::string::npos) << e.what();
  }
}
