#include <gtest/gtest.h>

#include "common/scratch.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "gridtopo/core/data_dir.h"

namespace fs = std::filesystem;
using namespace gridtopo;

namespace {
// Sets GRIDTOPO_DATA_DIR for one scope (unset when `value` is null), restoring the previous value after.
struct DataDirEnv {
  std::string old;
  bool had;
  explicit DataDirEnv(const char* value) : had(std::getenv("GRIDTOPO_DATA_DIR") != nullptr) {
    if (had) old = std::getenv("GRIDTOPO_DATA_DIR");
    if (value) setenv("GRIDTOPO_DATA_DIR", value, 1);
    else unsetenv("GRIDTOPO_DATA_DIR");
  }
  ~DataDirEnv() {
    if (had) setenv("GRIDTOPO_DATA_DIR", old.c_str(), 1);
    else unsetenv("GRIDTOPO_DATA_DIR");
  }
};
}  // namespace

TEST(DataDirs, EnvironmentThenBesideTheExecutableThenTheBuildTimeDir) {
  {
    DataDirEnv env("/data/override");
    EXPECT_EQ(dataDirs("/src/datasets", "/opt/gt/bin/gridtopo-gui"),
              (std::vector<std::string>{"/data/override", "/opt/gt/share/gridtopo/datasets", "/opt/gt/datasets",
                                        "/src/datasets"}));
  }
  DataDirEnv env(nullptr);
  EXPECT_EQ(dataDirs("", "/opt/gt/bin/gridtopo-gui"),
            (std::vector<std::string>{"/opt/gt/share/gridtopo/datasets", "/opt/gt/datasets"}));
  EXPECT_EQ(dataDirs("/src/datasets", ""), (std::vector<std::string>{"/src/datasets"}));
  // This test binary is found through /proc/self/exe.
  const std::string exe = executablePath();
  ASSERT_FALSE(exe.empty());
  EXPECT_TRUE(fs::equivalent(exe, "/proc/self/exe"));
}

TEST(DataDirs, FindsAFileInTheFirstDirThatHasIt) {
  const fs::path root = gridtopo::test::scratchPath("data_dir_test");
  fs::remove_all(root);
  const fs::path installed = root / "share/gridtopo/datasets/models", env_dir = root / "env/models";
  fs::create_directories(installed);
  fs::create_directories(env_dir);
  fs::create_directories(root / "bin");
  std::ofstream(installed / "m.yml") << "installed";
  const std::string exe = (root / "bin/app").string();
  {
    DataDirEnv env(nullptr);
    EXPECT_EQ(findDataFile("models/m.yml", "/nonexistent", exe), (installed / "m.yml").string());
    EXPECT_EQ(findDataFile("models/none.yml", "/nonexistent", exe), "");
  }
  {
    // The override comes first when it has the file, and does not hide the others when it does not.
    DataDirEnv env((root / "env").c_str());
    EXPECT_EQ(findDataFile("models/m.yml", "", exe), (installed / "m.yml").string());
    std::ofstream(env_dir / "m.yml") << "env";
    EXPECT_EQ(findDataFile("models/m.yml", "", exe), (root / "env/models/m.yml").string());
  }
  fs::remove_all(root);
}
