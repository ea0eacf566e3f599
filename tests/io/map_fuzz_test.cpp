// Deterministic random-mutation fuzzing of the map readers (issue 36): 1 500 mutated, truncated and spliced
// variants of a real ROS YAML, PGM and PNG, each read as all three formats (tests/io/map_fuzz_common.h): a map or
// an InputError naming the file on one line, never another exception, a crash or a library's call stack. The
// libFuzzer target map_fuzzer.cpp runs the same check on 10^6 inputs outside the suite (doc/guarantees.md).
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

#include "map_fuzz_common.h"
#include "test_tmp_dir.h"

namespace {
const char* kTokens[] = {"image:", "resolution:", "origin:", "negate:", "mode:", "occupied_thresh:", "free_thresh:",
                         "[", "]", "{", "}", ":", "- ", "nan", "inf", "-1", "1e999", "0", "\n", "  ", "\t", "'", "\"",
                         "&a", "*a", "!!binary", "P5", "P2", "IHDR", "4294967295", "99999999", "\xff"};

std::string mutate(std::string s, std::mt19937& rng) {
  const int edits = 1 + static_cast<int>(rng() % 6);
  for (int k = 0; k < edits && !s.empty(); ++k) {
    const std::size_t at = rng() % s.size();
    switch (rng() % 5) {
      case 0: s[at] = static_cast<char>(rng() & 0xff); break;
      case 1: s.erase(at, 1 + rng() % 8); break;
      case 2: s.insert(at, kTokens[rng() % (sizeof kTokens / sizeof *kTokens)]); break;
      case 3: s.resize(at); break;
      default: s.insert(at, s.substr(rng() % s.size(), 1 + rng() % 16)); break;
    }
  }
  return s;
}

std::string bytesOf(const std::vector<uchar>& v) { return std::string(v.begin(), v.end()); }
}  // namespace

TEST(MapFuzz, MutatedYamlPgmAndPngGiveAMapOrAnInputError) {
  const auto dir = gridtopo::test::tmpDir() / "map_fuzz";
  std::filesystem::create_directories(dir);
  cv::Mat img(24, 32, CV_8UC1);
  cv::randu(img, 0, 255);
  std::vector<uchar> png, pgm;
  cv::imencode(".png", img, png);
  cv::imencode(".pgm", img, pgm, {cv::IMWRITE_PXM_BINARY, 1});
  const std::vector<std::string> seeds = {
      "image: base.pgm\nresolution: 0.05\norigin: [-1.5, 2.25, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
      "free_thresh: 0.196\nmode: trinary\n",
      bytesOf(pgm), bytesOf(png)};
  std::mt19937 rng(36);
  // The seeds: the YAML reads as a ROS map (and as no image), the PGM and the PNG as images under either name (the
  // decoder goes by the content).
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    int maps = 0;
    ASSERT_EQ(gridtopo::test::mapFuzzOne(dir, seeds[i], &maps), "");
    EXPECT_EQ(maps, i == 0 ? 1 : 2) << "seed " << i;
  }
  int maps = 0;
  for (int i = 0; i < 1500; ++i) {
    const std::string failure = gridtopo::test::mapFuzzOne(dir, mutate(seeds[static_cast<std::size_t>(i) % 3], rng), &maps);
    ASSERT_EQ(failure, "") << "input " << i;
  }
  EXPECT_GT(maps, 50);  // mutations that still read: the readers' success paths are fuzzed too
}
