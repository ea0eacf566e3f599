#pragma once
// Test support shared by the io test binaries: a per-process temporary directory, removed when the binary's tests
// are done, and a whole-file reader.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace gridtopo::test {

/// temp/gridtopo_<binary>_<pid>, created on first use.
inline std::filesystem::path tmpDir() {
  const std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  ("gridtopo_" + std::string(program_invocation_short_name) + "_" +
                                   std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

struct RemoveTmpDir : ::testing::Environment {
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(tmpDir(), ec);
  }
};
inline const auto* const kRemoveTmpDir = ::testing::AddGlobalTestEnvironment(new RemoveTmpDir);

inline std::string readText(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace gridtopo::test
