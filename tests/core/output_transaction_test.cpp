// The output folder transaction (core OutputSet over a folder): staged beside the target, swapped in whole,
// nothing left on an error, a full disk or a signal; the checks before a run (issue 36 items 1, 2 and 5).
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>

#include "common/scratch.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"

namespace fs = std::filesystem;
using namespace gridtopo;

namespace {
fs::path freshDir(const std::string& name) {
  const fs::path d = gridtopo::test::scratchPath("txn_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir)) names.insert(fs::relative(e.path(), dir).string());
  return names;
}
void put(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
ino_t inode(const fs::path& p) {
  struct stat st {};
  ::stat(p.c_str(), &st);
  return st.st_ino;
}
}  // namespace

TEST(OutputTransaction, NewFolderAppearsWholeAtCommit) {
  const auto dir = freshDir("new");
  const fs::path out = dir / "out";
  {
    OutputSet set(out.string());
    set.write((out / "a.txt").string(), [](const std::string& t) { put(t, "A"); });
    set.write((out / "sub/b.txt").string(), [](const std::string& t) { put(t, "B"); });
    EXPECT_FALSE(fs::exists(out));  // nothing at the final name before the commit
    EXPECT_EQ(fs::path(set.stageFolder()).parent_path(), dir);  // staged beside it: same file system
    EXPECT_EQ(fs::path(set.stageFolder()).filename().string().rfind(".out.tmp-", 0), 0u);
    set.commit();
  }
  EXPECT_EQ(entries(dir), (std::set<std::string>{"out", "out/a.txt", "out/sub", "out/sub/b.txt"}));
  EXPECT_EQ(slurp(out / "sub/b.txt"), "B");
}

// An earlier run's folder (its outputs and the debris of a killed run) is replaced by one exchange: a new folder
// (another inode), no stale temporary carried over.
TEST(OutputTransaction, EarlierRunsFolderIsSwappedOutWhole) {
  const auto dir = freshDir("swap");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  put((out / "a.txt").string(), "old A");
  put((out / "b.txt").string(), "old B");
  put((out / ".a.txt.tmp-999999999-0.txt").string(), "debris");  // pid beyond pid_max: a dead process
  const ino_t before = inode(out);
  {
    OutputSet set(out.string());
    set.write((out / "a.txt").string(), [](const std::string& t) { put(t, "new A"); });
    set.write((out / "b.txt").string(), [](const std::string& t) { put(t, "new B"); });
    set.commit();
  }
  EXPECT_NE(inode(out), before);
  EXPECT_EQ(entries(dir), (std::set<std::string>{"out", "out/a.txt", "out/b.txt"}));
  EXPECT_EQ(slurp(out / "a.txt"), "new A");
}

// A folder with files the run does not write is never replaced: the run's files move in, the others stay (also
// inside a folder the run writes into).
TEST(OutputTransaction, FolderWithOtherFilesKeepsThem) {
  const auto dir = freshDir("foreign");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  put((out / "notes.txt").string(), "mine");
  put((out / "a.txt").string(), "old A");
  put((out / ".a.txt.tmp-999999999-7.txt").string(), "debris");
  fs::create_directories(out / "s");
  put((out / "s/mine.txt").string(), "also mine");  // beside a file of the run, inside a folder of the run
  const ino_t before = inode(out);
  {
    OutputSet set(out.string());
    set.write((out / "a.txt").string(), [](const std::string& t) { put(t, "new A"); });
    set.write((out / "s/c.txt").string(), [](const std::string& t) { put(t, "C"); });
    set.commit();
  }
  EXPECT_EQ(inode(out), before);
  EXPECT_EQ(entries(dir), (std::set<std::string>{"out", "out/a.txt", "out/notes.txt", "out/s", "out/s/c.txt",
                                                 "out/s/mine.txt"}));
  EXPECT_EQ(slurp(out / "notes.txt"), "mine");
  EXPECT_EQ(slurp(out / "a.txt"), "new A");
}

// A writer that fails: the error names the final file (never the temporary one), the old folder is as it was and
// no stage is left beside it.
TEST(OutputTransaction, FailedWriterLeavesTheOldFolderAndNoStage) {
  const auto dir = freshDir("fail");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  put((out / "a.txt").string(), "old A");
  try {
    OutputSet set(out.string());
    set.write((out / "a.txt").string(), [](const std::string& t) { put(t, "new A"); });
    set.write((out / "b.txt").string(), [](const std::string& t) { throw std::runtime_error("cannot write " + t); });
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + (out / "b.txt").string());
  }
  EXPECT_EQ(entries(dir), (std::set<std::string>{"out", "out/a.txt"}));
  EXPECT_EQ(slurp(out / "a.txt"), "old A");
}

// The stage of a process killed with SIGKILL (nothing could clean it) goes with the next run over that folder;
// a live process's stage is left alone.
TEST(OutputTransaction, StageOfADeadProcessIsRemovedByTheNextRun) {
  const auto dir = freshDir("stale");
  const fs::path out = dir / "out";
  fs::create_directories(dir / ".out.tmp-999999999-3/sub");
  put((dir / ".out.tmp-999999999-3/sub/x").string(), "x");
  const std::string live = ".out.tmp-" + std::to_string(::getpid()) + "-999999";
  fs::create_directories(dir / live);
  fs::create_directories(dir / ".other.tmp-999999999-1");  // another folder's: not this run's business
  {
    OutputSet set(out.string());
    set.write((out / "a.txt").string(), [](const std::string& t) { put(t, "A"); });
    set.commit();
  }
  EXPECT_EQ(entries(dir), (std::set<std::string>{"out", "out/a.txt", live, ".other.tmp-999999999-1"}));
}

TEST(OutputTransaction, CheckBeforeTheRunRefusesUnusableFolders) {
  const auto dir = freshDir("check");
  put((dir / "file").string(), "x");
  try {
    checkOutputFolder((dir / "file").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir / "file").string());
    EXPECT_NE(std::string(e.what()).find("exists and is not a folder"), std::string::npos) << e.what();
  }
  try {
    checkOutputFolder((dir / "file/sub/out").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Not a directory"), std::string::npos) << e.what();  // the system's reason
  }
  EXPECT_THROW(checkOutputFolder("/proc/gridtopo-x"), InputError);
  EXPECT_THROW(checkOutputFolder("/"), InputError);
  // A creatable folder passes and leaves nothing: neither the stage nor the parents made for it.
  checkOutputFolder((dir / "a/b/out").string());
  checkOutputFolder(dir.string());
  EXPECT_EQ(entries(dir), (std::set<std::string>{"file"}));
  // Output files: a folder at the name is refused, a creatable path passes.
  EXPECT_THROW(checkOutputFile(dir.string()), InputError);
  EXPECT_THROW(checkOutputFile((dir / "file/x.json").string()), InputError);
  checkOutputFile((dir / "x/y.json").string());
  EXPECT_EQ(entries(dir), (std::set<std::string>{"file"}));
}

// A full disk: a 64 KiB tmpfs. The error names the final file and the system's reason, whether the writer reports
// the failed write itself (writeTextFileAtomically) or ignores it (an unchecked ofstream); nothing is left.
TEST(OutputTransaction, FullDiskNamesTheFileAndTheReasonAndLeavesNothing) {
  const auto mnt = freshDir("tmpfs");
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno) << "): needs root";
  struct Unmount {
    fs::path p;
    ~Unmount() { ::umount2(p.c_str(), MNT_DETACH); }
  } unmount{mnt};
  const fs::path out = mnt / "out";
  const std::string big(200 * 1024, 'x');
  try {
    OutputSet set(out.string());
    set.write((out / "small.txt").string(), [](const std::string& t) { put(t, "ok"); });
    set.write((out / "big.txt").string(), [&](const std::string& t) { writeTextFileAtomically(t, big); });
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (out / "big.txt").string() + ": cannot write: No space left on device");
  }
  EXPECT_TRUE(entries(mnt).empty());
  try {
    OutputSet set(out.string());
    set.write((out / "quiet.txt").string(), [&](const std::string& t) { std::ofstream(t) << big; });
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (out / "quiet.txt").string() + ": cannot write: No space left on device");
  }
  EXPECT_TRUE(entries(mnt).empty());
}

// SIGTERM while a run writes its outputs (a child process, killed from outside in its write phase): the process
// dies of the signal (exit status 143 in a shell), the earlier folder is intact and no stage is left.
TEST(OutputTransaction, SigtermDuringTheWritePhaseLeavesNoDebris) {
  const auto dir = freshDir("sigterm");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  put((out / "a.txt").string(), "old A");
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    installOutputCleanupOnSignals();
    OutputSet set(out.string());
    set.write((out / "a.txt").string(), [](const std::string& t) { put(t, "new A"); });
    set.write((out / "sub/b.txt").string(), [&](const std::string& t) {
      put(t, "half");
      const char c = 'w';
      (void)!::write(ready[1], &c, 1);  // in the write phase now
      ::sleep(30);
    });
    set.commit();
    ::_exit(0);
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  ::close(ready[0]);
  ::close(ready[1]);
  // The child's stage is there, with its files, until the signal.
  std::size_t staged = 0;
  for (const auto& e : fs::directory_iterator(dir)) staged += e.path().filename().string().rfind(".out.tmp-", 0) == 0;
  EXPECT_EQ(staged, 1u);
  ASSERT_EQ(::kill(child, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_EQ(entries(dir), (std::set<std::string>{"out", "out/a.txt"}));
  EXPECT_EQ(slurp(out / "a.txt"), "old A");
}

// The same for loose files (an OutputSet without a folder, e.g. gridtopo-eval --json) and SIGINT.
TEST(OutputTransaction, SigintRemovesLooseTemporaries) {
  const auto dir = freshDir("sigint");
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    installOutputCleanupOnSignals();
    OutputSet set;
    set.write((dir / "x.json").string(), [](const std::string& t) { put(t, "{}"); });
    set.write((dir / "y.txt").string(), [&](const std::string& t) {
      put(t, "half");
      const char c = 'w';
      (void)!::write(ready[1], &c, 1);
      ::sleep(30);
    });
    set.commit();
    ::_exit(0);
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  ::close(ready[0]);
  ::close(ready[1]);
  EXPECT_EQ(entries(dir).size(), 2u);  // the two temporary files
  ASSERT_EQ(::kill(child, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_TRUE(entries(dir).empty());
}
