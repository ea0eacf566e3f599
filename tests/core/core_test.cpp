#include <gtest/gtest.h>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/core/progress.h"

namespace fs = std::filesystem;
using namespace gridtopo;

namespace {
fs::path freshDir(const std::string& name) {
  const fs::path d = gridtopo::test::scratchPath("core_test_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
}  // namespace

TEST(InputError, NamesFileLineAndField) {
  const InputError e("log.clf", 12, "FLASER range 3", "not a number");
  EXPECT_STREQ(e.what(), "log.clf:12: FLASER range 3: not a number");
  EXPECT_EQ(e.line(), 12u);
  EXPECT_EQ(e.field(), "FLASER range 3");
  EXPECT_STREQ(InputError("x.ini", "missing").what(), "x.ini: missing");
}

TEST(OutputSet, CommitsAllOrNothing) {
  const auto dir = freshDir("commit");
  {
    OutputSet set;
    set.write((dir / "a.txt").string(), [](const std::string& tmp) { std::ofstream(tmp) << "A"; });
    const std::string tmp_b = set.add((dir / "sub/b.gridmap.gz").string());
    EXPECT_NE(tmp_b.find(".gridmap.gz"), std::string::npos);  // writers choosing by extension still work
    std::ofstream(tmp_b) << "B";
    EXPECT_FALSE(fs::exists(dir / "a.txt"));
    set.commit();
  }
  EXPECT_EQ(slurp(dir / "a.txt"), "A");
  EXPECT_EQ(slurp(dir / "sub/b.gridmap.gz"), "B");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2);  // no temporaries left
}

TEST(OutputSet, FailedRunLeavesNothing) {
  const auto dir = freshDir("fail");
  try {
    OutputSet set;
    set.write((dir / "a.txt").string(), [](const std::string& tmp) { std::ofstream(tmp) << "A"; });
    set.write((dir / "b.txt").string(), [](const std::string&) { throw std::runtime_error("boom"); });
    set.commit();
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "b.txt").string() + ": cannot write: boom");  // the final name
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

// The directories made for a set that is not committed go with it (gridtopo-map: OUT/slam of a failed run).
TEST(OutputSet, FailedRunLeavesNoNewDirectory) {
  const auto dir = freshDir("dirs");
  fs::create_directories(dir / "kept");
  {
    OutputSet set;
    set.write((dir / "new/deeper/a.txt").string(), [](const std::string& tmp) { std::ofstream(tmp) << "A"; });
    set.write((dir / "kept/b.txt").string(), [](const std::string& tmp) { std::ofstream(tmp) << "B"; });
    EXPECT_TRUE(fs::is_directory(dir / "new/deeper"));
  }
  EXPECT_FALSE(fs::exists(dir / "new"));
  EXPECT_TRUE(fs::is_directory(dir / "kept"));
  EXPECT_TRUE(fs::is_empty(dir / "kept"));
}

// An output folder that cannot be made (a file stands where a folder must go) is an InputError naming the folder,
// and the folders made before the failure are taken away again.
TEST(OutputSet, UncreatableFolderNamesItAndLeavesNothing) {
  const auto dir = freshDir("uncreatable");
  std::ofstream(dir / "file") << "x";
  {
    OutputSet set;
    set.write((dir / "a/b.txt").string(), [](const std::string& tmp) { std::ofstream(tmp) << "B"; });
    try {
      set.add((dir / "file/sub/c.txt").string());
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), (dir / "file/sub").string());
      EXPECT_NE(std::string(e.what()).find("cannot create the output folder"), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(dir / "a"));
  EXPECT_TRUE(fs::is_regular_file(dir / "file"));
}

// A commit that cannot complete (here: a directory where a file must go) leaves the outputs of an earlier run as
// they were, and no new or temporary file: before, the files renamed ahead of the failing one stayed.
TEST(OutputSet, FailedCommitKeepsThePreviousOutputs) {
  const auto dir = freshDir("commit");
  std::ofstream(dir / "a.txt") << "old A";
  fs::create_directories(dir / "b.txt");
  {
    OutputSet set;
    set.write((dir / "a.txt").string(), [](const std::string& tmp) { std::ofstream(tmp) << "new A"; });
    set.write((dir / "b.txt").string(), [](const std::string& tmp) { std::ofstream(tmp) << "B"; });
    set.write((dir / "c.txt").string(), [](const std::string& tmp) { std::ofstream(tmp) << "C"; });
    EXPECT_THROW(set.commit(), std::runtime_error);
  }
  std::ifstream a(dir / "a.txt");
  std::string text((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "old A");
  EXPECT_FALSE(fs::exists(dir / "c.txt"));
  std::size_t entries = 0;
  for (auto it = fs::directory_iterator(dir); it != fs::directory_iterator(); ++it) ++entries;
  EXPECT_EQ(entries, 2u);  // a.txt and the directory b.txt
}

TEST(OutputSet, ReplacesThePreviousOutputs) {
  const auto dir = freshDir("replace");
  std::ofstream(dir / "a.txt") << "old";
  OutputSet set;
  set.write((dir / "a.txt").string(), [](const std::string& tmp) { std::ofstream(tmp) << "new"; });
  set.commit();
  std::ifstream a(dir / "a.txt");
  std::string text((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "new");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);  // no backup left
}

TEST(OutputSet, MissingTemporaryIsAnError) {
  const auto dir = freshDir("missing");
  OutputSet set;
  set.add((dir / "never.txt").string());
  EXPECT_THROW(set.commit(), std::runtime_error);
}

TEST(ProgressBar, RendersRateAndEta) {
  ProgressBar bar(200, "slam", "scans", 0);
  EXPECT_FALSE(bar.enabled());
  const std::string line = bar.render(50, 10.0, "Neff 12.5");
  EXPECT_NE(line.find(" 25%"), std::string::npos) << line;
  EXPECT_NE(line.find("50/200"), std::string::npos) << line;
  EXPECT_NE(line.find("5.0 scans/s"), std::string::npos) << line;
  EXPECT_NE(line.find("ETA 00:30"), std::string::npos) << line;
  EXPECT_NE(line.find("Neff 12.5"), std::string::npos) << line;
  EXPECT_EQ(formatDuration(3725), "1:02:05");
}
