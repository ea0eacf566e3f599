#pragma once
// Test support for the experiment tests: small file helpers (and the per-process scratch folder of
// common/scratch.h).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/scratch.h"

namespace gridtopo::test {

inline void writeText(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p);
  f << text;
}

inline std::string readText(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline std::size_t countLines(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

}  // namespace gridtopo::test
