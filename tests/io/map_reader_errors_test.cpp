// issue 36 items 6 and 9: the map readers (YAML, PGM, PNG) and the log and trajectory readers say
// "file: what is wrong" on bad input, never a library's banner or call stack; an image larger than the cell budget
// is refused from its header, before its pixels are allocated.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "gridtopo/core/error.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/io/map_io.h"
#include "gridtopo/io/trajectory_io.h"
#include "test_tmp_dir.h"

namespace fs = std::filesystem;
using namespace gridtopo;

namespace {
fs::path dir() {
  const fs::path d = gridtopo::test::tmpDir() / "map_reader_errors";
  fs::create_directories(d);
  return d;
}
void put(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

// The error of reading `path` as a map: an InputError (anything else fails the test), as its what().
std::string mapError(const fs::path& path, const io::MapReadOptions& o = {}) {
  try {
    io::readGridMap(path.string(), o);
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error for " << path;
  return "";
}

// One line naming the file, with nothing of a library's banner, source location or call stack.
void expectClean(const std::string& message, const fs::path& file) {
  EXPECT_EQ(message.rfind(file.string(), 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  for (const char* noise : {"====", "Call stack", "MRPT", ".cpp:", ".h:", "OpenCV(", "in function"})
    EXPECT_EQ(message.find(noise), std::string::npos) << noise << " in: " << message;
  EXPECT_LT(message.size(), 400u) << message;
}
}  // namespace

TEST(MapReaderErrors, MalformedYamlSaysFileAndWhatIsWrong) {
  const fs::path d = dir();
  cv::imwrite((d / "m.pgm").string(), cv::Mat(4, 4, CV_8UC1, cv::Scalar(254)));
  const std::vector<std::string> texts = {
      "image: [m.pgm, x]\nresolution: 0.05\norigin: [0, 0, 0]\n",
      "image: {a: 1}\nresolution: 0.05\norigin: [0, 0, 0]\n",
      "image: m.pgm\nresolution: {a: 1}\norigin: [0, 0, 0]\n",
      "image: m.pgm\nresolution: 0.05\norigin: {x: 1}\n",
      "image: m.pgm\nresolution: 0.05\norigin: [a, b, c]\n",
      "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nmode: [trinary]\n",
      "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: [1]\n",
      "- just\n- a list\n",
      "image: m.pgm\n  resolution: 0.05\n bad: : :\n",
      "{{{{",
      "\x01\x02\x03\xff\xfe",
      "",
  };
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const fs::path y = d / ("bad" + std::to_string(i) + ".yaml");
    put(y, texts[i]);
    SCOPED_TRACE(texts[i]);
    expectClean(mapError(y), y);
  }
  EXPECT_EQ(mapError(d / "bad0.yaml"), (d / "bad0.yaml").string() + ": image: expected a file name");
  EXPECT_EQ(mapError(d / "bad5.yaml"), (d / "bad5.yaml").string() + ": mode: expected trinary, scale or raw");
  // Ten bytes on which the YAML parser looped forever (found by map_fuzzer): refused as not text.
  put(d / "hang.yaml", std::string("%\xc6-P2\0\x99r~\x06", 10));
  EXPECT_EQ(mapError(d / "hang.yaml"), (d / "hang.yaml").string() + ": not a UTF-8 text YAML file (byte 1)");
  // And on broken UTF-8 (the second input map_fuzzer found): refused too; valid UTF-8 passes the check.
  put(d / "hang2.yaml", "P2\n# c\n%%%%\xd4\xda\xda%%\n");
  EXPECT_EQ(mapError(d / "hang2.yaml"), (d / "hang2.yaml").string() + ": not a UTF-8 text YAML file (byte 11)");
  put(d / "utf8.yaml", "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n# caf\xc3\xa9\n");
  EXPECT_EQ(io::readGridMap((d / "utf8.yaml").string())->getSizeX(), 4u);
  // Found by map_fuzzer (libFuzzer, ASan + UBSan): numbers MRPT's as<double>() could not read went on to its integer
  // conversion, which casts DBL_MAX to long long (undefined behaviour); numbers are now parsed here.
  put(d / "hexnum.yaml", "image: m.pgm\nresolution: 0x1G\norigin: [0, 0, 0]\n");
  EXPECT_EQ(mapError(d / "hexnum.yaml"), (d / "hexnum.yaml").string() + ": resolution: expected a number");
  put(d / "hugenum.yaml", "image: m.pgm\nresolution: 0.05\norigin: [1e999, 0, 0]\n");
  EXPECT_EQ(mapError(d / "hugenum.yaml"), (d / "hugenum.yaml").string() + ": origin: expected finite numbers");
  put(d / "numbers.yaml", "image: m.pgm\nresolution: 5e-2\norigin: [ -1.5 , 2, 0x0]\nnegate: 1\nfree_thresh: .1\n");
  const auto g = io::readGridMap((d / "numbers.yaml").string());
  EXPECT_FLOAT_EQ(g->getResolution(), 0.05f);
  EXPECT_NEAR(g->getXMin(), -1.5, 1e-6);
  EXPECT_NEAR(g->getYMin(), 2.0, 1e-6);
  // A resolution or origin that MRPT's float limits cannot hold (found by map_fuzzer: 3.3e126 m became inf, the
  // grid had no cells and the image was written through a null pointer): refused with the field.
  put(d / "hugeres.yaml", "image: m.pgm\nresolution: 3.3e126\norigin: [0, 0, 0]\n");
  EXPECT_EQ(mapError(d / "hugeres.yaml"),
            (d / "hugeres.yaml").string() +
                ": resolution: 4 x 4 cells of 3.3e+126 m at (0, 0): the resolution is out of the range a grid can hold");
  put(d / "tinyres.yaml", "image: m.pgm\nresolution: 1e-300\norigin: [0, 0, 0]\n");
  EXPECT_NE(mapError(d / "tinyres.yaml").find(": resolution: 4 x 4 cells of 1e-300 m at (0, 0): the resolution is out"),
            std::string::npos);
  put(d / "hugeorigin.yaml", "image: m.pgm\nresolution: 0.05\norigin: [1e39, 0, 0]\n");
  EXPECT_EQ(mapError(d / "hugeorigin.yaml"),
            (d / "hugeorigin.yaml").string() +
                ": origin: 4 x 4 cells of 0.05 m at (1e+39, 0): the map's limits are out of the range a grid can hold");
  io::MapReadOptions huge_resolution;
  huge_resolution.resolution = 1e200;
  EXPECT_NE(mapError(d / "m.pgm", huge_resolution).find("m.pgm: resolution: 4 x 4 cells of 1e+200 m"), std::string::npos);
  // An image named by an absolute path that does not exist: the YAML's error (it named only the image before).
  put(d / "absimg.yaml", "image: /no/such/dir/m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  EXPECT_EQ(mapError(d / "absimg.yaml"),
            (d / "absimg.yaml").string() + ": image: no such image file: /no/such/dir/m.pgm");
  // A quoted value holding a line break is quoted on one line, escaped (the message stays one line).
  put(d / "mode.yaml", "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nmode: \"tri\\nary\"\n");
  EXPECT_EQ(mapError(d / "mode.yaml"),
            (d / "mode.yaml").string() + ": mode: expected trinary, scale or raw, not 'tri\\x0Aary'");
  // An image name longer than the system allows (found by map_fuzzer: std::filesystem threw "File name too long"):
  // the YAML's error with the system's reason; the same for a map file named so.
  put(d / "longname.yaml", "image: " + std::string(300, 'b') + ".pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
  EXPECT_EQ(mapError(d / "longname.yaml")
                .rfind((d / "longname.yaml").string() + ": image: cannot open the image file (File name too long): " +
                           (d / "bbbb").string(),
                       0),
            0u)
      << mapError(d / "longname.yaml");
  EXPECT_EQ(mapError(d / "longname.yaml").find('\n'), std::string::npos);
  const fs::path long_png = d / (std::string(300, 'c') + ".png");
  EXPECT_EQ(mapError(long_png), long_png.string() + ": cannot open the image file: File name too long");
  const fs::path long_yaml = d / (std::string(300, 'c') + ".yaml");
  EXPECT_EQ(mapError(long_yaml), long_yaml.string() + ": cannot open the YAML file: File name too long");
  // A YAML of more than 1 MiB is no map's YAML: refused before parsing; 1 MiB of comment lines is read.
  std::string big = "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  while (big.size() < (1u << 20)) big += "# " + std::string(std::min<std::size_t>(1000, (1u << 20) - big.size()), 'x') + "\n";
  big.resize(1u << 20);
  big.back() = '\n';
  put(d / "mib.yaml", big);
  EXPECT_EQ(io::readGridMap((d / "mib.yaml").string())->getSizeX(), 4u);
  put(d / "over.yaml", big + "#");
  EXPECT_EQ(mapError(d / "over.yaml"), (d / "over.yaml").string() + ": not a ROS map_server YAML file (larger than 1 MiB)");
  // A syntax error: the parser's own diagnosis and line (it printed them to stderr and failed a bare assertion).
  put(d / "syntax.yaml", "image: m.pgm\nresolution: 0.05\n  origin: [0,0,0\n bad");
  EXPECT_EQ(mapError(d / "syntax.yaml"), (d / "syntax.yaml").string() + ":2: cannot parse YAML: invalid multiline plain key");
}

// A header claiming 2 000 000 000² pixels: refused from the header with the file, not an allocator's or OpenCV's
// failure. A small budget shows the check is the header's size against MapReadOptions::max_cells.
TEST(MapReaderErrors, ImageLargerThanTheCellBudgetIsRefusedFromItsHeader) {
  const fs::path d = dir();
  put(d / "huge.pgm", "P5\n# a comment\n2000000000 2000000000\n255\n" + std::string(64, '\xfe'));
  EXPECT_EQ(mapError(d / "huge.pgm"),
            (d / "huge.pgm").string() +
                ": size: the image header says 2000000000 x 2000000000 pixels, more than the budget of 100000000 "
                "cells (MapReadOptions::max_cells)");
  // A PNG whose IHDR says 70000 x 70000 (4.9e9 cells); the rest of the file does not matter.
  std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\x01\x11\x70\0\x01\x11\x70\x08\0\0\0\0", 29);
  put(d / "huge.png", png + std::string(16, '\0'));
  EXPECT_EQ(mapError(d / "huge.png"),
            (d / "huge.png").string() +
                ": size: the image header says 70000 x 70000 pixels, more than the budget of 100000000 cells "
                "(MapReadOptions::max_cells)");
  cv::imwrite((d / "ten.png").string(), cv::Mat(10, 10, CV_8UC1, cv::Scalar(200)));
  cv::imwrite((d / "ten.pgm").string(), cv::Mat(10, 11, CV_8UC1, cv::Scalar(200)));
  io::MapReadOptions small;
  small.max_cells = 100;
  EXPECT_EQ(io::readGridMap((d / "ten.png").string(), small)->getSizeX(), 10u);  // 100 cells: within
  EXPECT_NE(mapError(d / "ten.pgm", small).find("11 x 10 pixels, more than the budget of 100 cells"),
            std::string::npos);  // 110 cells: refused
  put(d / "empty.pgm", "P5\n0 5\n255\n");
  EXPECT_NE(mapError(d / "empty.pgm").find("no cells"), std::string::npos);
}

// Truncated and corrupted images: an InputError with the file, whatever the decoder says.
TEST(MapReaderErrors, TruncatedOrCorruptImagesAreInputErrors) {
  const fs::path d = dir();
  cv::Mat img(64, 64, CV_8UC1);
  cv::randu(img, 0, 255);
  cv::imwrite((d / "ok.png").string(), img);
  cv::imwrite((d / "ok.pgm").string(), img);
  for (const char* name : {"ok.png", "ok.pgm"}) {
    std::ifstream f(d / name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(f)), {});
    const fs::path cut = d / (std::string("cut_") + name), bad = d / (std::string("bad_") + name);
    put(cut, bytes.substr(0, bytes.size() / 3));
    std::string flipped = bytes;
    for (std::size_t i = 40; i < flipped.size(); i += 7) flipped[i] = static_cast<char>(~flipped[i]);
    put(bad, flipped);
    for (const fs::path& p : {cut, bad}) {
      try {
        io::readGridMap(p.string());  // a decoder may accept a damaged PGM body: then a map, never a crash
      } catch (const InputError& e) {
        expectClean(e.what(), p);
      }
    }
  }
  put(d / "words.png", "not an image at all");
  expectClean(mapError(d / "words.png"), d / "words.png");
}

// Item 9: a log that cannot be read says why (a file that exists but cannot be opened gets the system's reason,
// "cannot open the log file: Permission denied": not testable as root); a trajectory line without theta names
// the field.
TEST(MapReaderErrors, LogAndTrajectoryReadersSayTheReason) {
  const fs::path d = dir();
  try {
    io::readScanLog((d / "nothing.clf").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (d / "nothing.clf").string() + ": no such log file");
  }
  try {
    io::readScanLog(d.string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), d.string() + ": is a folder, not a log file");
  }
  put(d / "traj.txt", "# t x y theta\n1.0 0 0 0\n2.0 1.5 2.5\n");
  try {
    io::readTrajectory((d / "traj.txt").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (d / "traj.txt").string() + ":3: theta: missing (each line is 'timestamp x y theta')");
  }
  try {
    io::readTrajectory((d / "none.txt").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (d / "none.txt").string() + ": cannot open the trajectory file: No such file or directory");
  }
}
