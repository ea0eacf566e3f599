#pragma once
// A per-process scratch folder for tests: ctest runs the tests of one binary as parallel processes, and several
// checkouts may run the suite at once, so fixed names under the temporary directory collide.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace gridtopo::test {

/// temp/gridtopo_<binary>_<pid>/<name>, created empty.
inline std::filesystem::path scratch(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() /
                 ("gridtopo_" + std::string(program_invocation_short_name) + "_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

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
