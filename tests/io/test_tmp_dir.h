#pragma once
// Test support shared by the io test binaries: this process's temporary directory (common/scratch.h, removed when
// the binary's tests are done) and a whole-file reader.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/scratch.h"

namespace gridtopo::test {

/// temp/gridtopo_<binary>_<pid>, created on first use.
inline std::filesystem::path tmpDir() { return processScratch(); }

inline std::string readText(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace gridtopo::test
