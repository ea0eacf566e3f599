#pragma once
// A per-process scratch folder for tests: ctest runs the tests of one binary as parallel processes, and several
// checkouts may run the suite at once, so fixed names under the temporary directory collide.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace gridtopo::test {

/// temp/gridtopo_<binary>_<pid>: this process's own folder, created on first use.
inline std::filesystem::path processScratch() {
  const auto d = std::filesystem::temp_directory_path() /
                 ("gridtopo_" + std::string(program_invocation_short_name) + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

/// temp/gridtopo_<binary>_<pid>/<name>, created empty.
inline std::filesystem::path scratch(const std::string& name) {
  const auto d = processScratch() / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

/// temp/gridtopo_<binary>_<pid>/<name>, neither created nor removed: a file or folder name no other test process
/// can use at the same time.
inline std::filesystem::path scratchPath(const std::string& name) { return processScratch() / name; }

struct RemoveScratch : ::testing::Environment {
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(std::filesystem::temp_directory_path() /
                                    ("gridtopo_" + std::string(program_invocation_short_name) + "_" +
                                     std::to_string(::getpid())),
                                ec);
  }
};
inline const auto* const kRemoveScratch = ::testing::AddGlobalTestEnvironment(new RemoveScratch);

}  // namespace gridtopo::test
