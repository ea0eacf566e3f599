#pragma once
// Comparing the outputs of two runs in tests: files as text, with the lines or columns that may differ left out, and
// trajectories pose by pose.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gridtopo/io/trajectory_io.h"

namespace gridtopo::testing_outputs {

inline std::string slurp(const std::filesystem::path& p) {
  std::ostringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}

/// The text without its lines "key = ..." (e.g. the output directory of an options.ini).
inline std::string withoutLine(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::string out;
  for (std::string l; std::getline(in, l);)
    if (l.rfind(key + " = ", 0) != 0) out += l + "\n";
  return out;
}

/// A stats.txt's text without its wall-time (4th) and RSS (13th) columns, which differ from run to run.
inline std::string statsWithoutTimeAndRss(const std::string& text) {
  std::istringstream in(text);
  std::string out;
  for (std::string l; std::getline(in, l);) {
    if (l.rfind("# loop_closure_cpu_seconds:", 0) == 0) continue;  // processor seconds: not deterministic
    std::istringstream w(l);
    std::vector<std::string> words;
    for (std::string word; w >> word;) words.push_back(word);
    // A step row: drop its wall time (column 3) and the process RSS (the last column).
    for (std::size_t i = 0; i < words.size(); ++i)
      if (l[0] == '#' || (i != 3 && i + 1 != words.size())) out += words[i] + ' ';
    out += '\n';
  }
  return out;
}

/// The same poses at the same timestamps, bit for bit.
inline void expectSameTrajectory(const std::vector<gridtopo::TimedPose>& a, const std::vector<gridtopo::TimedPose>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].timestamp, b[i].timestamp) << i;
    ASSERT_EQ(a[i].pose.x, b[i].pose.x) << i;
    ASSERT_EQ(a[i].pose.y, b[i].pose.y) << i;
    ASSERT_EQ(a[i].pose.phi, b[i].pose.phi) << i;
  }
}

}  // namespace gridtopo::testing_outputs
