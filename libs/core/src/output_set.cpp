#include "gridtopo/core/output_set.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include "gridtopo/core/error.h"

namespace fs = std::filesystem;

namespace gridtopo {
namespace {
std::atomic<unsigned> g_counter{0};

// ---- signal-time cleanup -------------------------------------------------------------------------------------
// A fixed table of absolute paths to remove (files or folder trees) when a signal ends the process; written by
// the sets, read by the handler with nothing but system calls.
constexpr int kSlots = 256;
constexpr std::size_t kPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 live
  char path[kPathMax];
};
Slot g_slots[kSlots];
std::atomic<int> g_committing{0};      // commits in progress: a signal waits for them
std::atomic<int> g_cleaning{0};        // the handler is removing the slots' paths
std::atomic<int> g_pending_signal{0};  // a signal that arrived during a commit
std::atomic<bool> g_installed{false};

int registerPath(const std::string& path) {
  if (path.size() + 1 > kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (g_slots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].state.store(2);
      return i;
    }
  }
  return -1;  // table full: that path is still removed on every error path, only not on a signal
}

void unregisterPath(int slot) {
  if (slot >= 0) g_slots[slot].state.store(0);
}

struct Dirent64 {
  unsigned long long d_ino;
  long long d_off;
  unsigned short d_reclen;
  unsigned char d_type;
  char d_name[1];
};

// Removes `name` (relative to dirfd) and, if it is a folder, everything in it: open / getdents64 / unlinkat /
// close only, so that it may run in a signal handler.
void removeTreeAt(int dirfd, const char* name, int depth) {
  if (::unlinkat(dirfd, name, 0) == 0 || errno == ENOENT) return;
  const int fd = ::openat(dirfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  if (depth < 32) {
    alignas(8) char buf[2048];
    for (bool removed = true; removed;) {
      removed = false;
      ::lseek(fd, 0, SEEK_SET);
      for (;;) {
        const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
        if (n <= 0) break;
        for (long off = 0; off < n;) {
          const auto* d = reinterpret_cast<const Dirent64*>(buf + off);
          off += d->d_reclen;
          if (std::strcmp(d->d_name, ".") == 0 || std::strcmp(d->d_name, "..") == 0) continue;
          removeTreeAt(fd, d->d_name, depth + 1);
          removed = true;
        }
      }
    }
  }
  ::close(fd);
  ::unlinkat(dirfd, name, AT_REMOVEDIR);
}

void removeRegisteredPaths() {
  for (auto& s : g_slots)
    if (s.state.load() == 2) removeTreeAt(AT_FDCWD, s.path, 0);
}

void onSignal(int sig) {
  const int saved = errno;
  g_cleaning.store(1);
  if (g_committing.load() > 0) {  // the commit finishes, then dies of the signal (see endCommit)
    g_pending_signal.store(sig);
    g_cleaning.store(0);
    errno = saved;
    return;
  }
  removeRegisteredPaths();
  ::signal(sig, SIG_DFL);
  ::raise(sig);
  errno = saved;
}

void beginCommit() {
  g_committing.fetch_add(1);
  // A handler that started cleaning before it could see this commit: the process is about to die of it.
  while (g_cleaning.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void endCommit() {
  if (g_committing.fetch_sub(1) == 1) {
    const int sig = g_pending_signal.exchange(0);
    if (sig != 0) {
      removeRegisteredPaths();
      ::signal(sig, SIG_DFL);
      ::raise(sig);
    }
  }
}

struct CommitGuard {
  CommitGuard() { beginCommit(); }
  ~CommitGuard() { endCommit(); }
};

// ---- names ---------------------------------------------------------------------------------------------------

// Everything after the first '.' of the file name that is not at its start, e.g. ".gridmap.gz".
std::string extensionsOf(const std::string& name) {
  const auto pos = name.find('.', 1);
  return pos == std::string::npos ? std::string() : name.substr(pos);
}

std::string tmpSuffix() { return ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(g_counter++); }

fs::path absoluteNormal(const std::string& p) {
  fs::path n = fs::absolute(fs::path(p)).lexically_normal();
  if (n.filename().empty() && n != n.root_path()) n = n.parent_path();  // "out/" -> "out"
  return n;
}

// `p` strictly inside `dir` (both absolute and normal).
bool isInside(const fs::path& p, const fs::path& dir) {
  const fs::path rel = p.lexically_relative(dir);
  return !rel.empty() && *rel.begin() != ".." && rel != ".";
}

// A hidden temporary entry left by a process that no longer runs: ".NAME.tmp-PID-..." with PID gone.
bool isStaleTemporary(const std::string& name) {
  if (name.empty() || name[0] != '.') return false;
  const auto pos = name.find(".tmp-", 1);
  if (pos == std::string::npos) return false;
  const char* digits = name.c_str() + pos + 5;
  char* end = nullptr;
  const long pid = std::strtol(digits, &end, 10);
  if (end == digits || *end != '-' || pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

// Any hidden temporary entry of an OutputSet (this process's or a dead one's).
bool isOutputTemporary(const std::string& name) {
  return !name.empty() && name[0] == '.' && name.find(".tmp-", 1) != std::string::npos;
}

// Removes the entries of `dir` that start with `prefix` and are temporaries of a process that no longer runs.
void removeStaleTemporaries(const fs::path& dir, const std::string& prefix) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) == 0 && isStaleTemporary(name)) {
      std::error_code rm;
      fs::remove_all(it->path(), rm);
    }
  }
}

std::string reasonOf(const std::exception& e) {
  if (const auto* fe = dynamic_cast<const fs::filesystem_error*>(&e)) return fe->code().message();
  return e.what();
}

// The folder that `folder` names, symbolic links resolved: the stage goes beside it, on its file system, and the
// swap replaces it (a link to it stays a link).
fs::path realFolder(const std::string& folder) {
  std::error_code ec;
  const fs::path r = fs::weakly_canonical(fs::path(folder), ec);
  return ec ? fs::path(folder) : absoluteNormal(r.string());
}

void replaceAll(std::string& s, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (std::size_t pos = 0; (pos = s.find(from, pos)) != std::string::npos; pos += to.size()) s.replace(pos, from.size(), to);
}

// The file system of `path` has no free block left: a write there has failed or was cut short.
bool noSpaceLeft(const fs::path& path) {
  struct statvfs st {};
  return ::statvfs(path.c_str(), &st) == 0 && st.f_bfree == 0 && st.f_blocks > 0;
}

[[noreturn]] void throwSystem(const std::string& what, int err) {
  throw std::runtime_error(what + ": " + std::strerror(err));
}

void renameOrThrow(const fs::path& from, const fs::path& to, const std::string& final_name) {
  if (::rename(from.c_str(), to.c_str()) != 0) throwSystem(final_name + ": cannot move into place", errno);
}
}  // namespace

// ---- OutputSet -----------------------------------------------------------------------------------------------

OutputSet::OutputSet(const std::string& folder) : folder_(absoluteNormal(folder).string()) {
  if (folder_ == "/" || realFolder(folder_).filename().empty())
    throw InputError(folder, "cannot be an output folder (give a folder of its own)");
}

OutputSet::~OutputSet() {
  if (!committed_) {
    for (std::size_t i = 0; i < temps_.size(); ++i)
      if (!staged_[i]) {
        std::error_code ec;
        fs::remove(temps_[i], ec);
      }
    if (!stage_.empty()) {
      std::error_code ec;
      fs::remove_all(stage_, ec);
    }
    // The directories the set created, deepest first: removed when empty (fs::remove leaves a non-empty one).
    for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) {
      std::error_code ec;
      fs::remove(*it, ec);
    }
  }
  for (int s : slots_) unregisterPath(s);
  unregisterPath(stage_slot_);
}

namespace {
// Creates the missing directories of `dir`, recording the ones it made (outermost first).
void createDirectories(const fs::path& dir, std::vector<std::string>& created) {
  std::vector<fs::path> missing;
  for (fs::path d = dir; !d.empty() && !fs::exists(d); d = d.parent_path()) {
    missing.push_back(d);
    if (d == d.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) != 0 && errno != EEXIST)
      throwSystem("cannot create the output folder " + it->string(), errno);
    created.push_back(it->string());
  }
  if (!fs::is_directory(dir)) throw std::runtime_error("cannot create the output folder " + dir.string() + ": not a folder");
}
}  // namespace

void OutputSet::ensureStage() {
  if (!stage_.empty()) return;
  const fs::path folder = realFolder(folder_);
  if (fs::exists(folder) && !fs::is_directory(folder))
    throw InputError(folder_, "cannot write the output folder: it exists and is not a folder");
  try {
    createDirectories(folder.parent_path(), created_dirs_);
  } catch (const std::runtime_error& e) {
    throw InputError(folder_, e.what());
  }
  removeStaleTemporaries(folder.parent_path(), "." + folder.filename().string() + ".tmp-");
  const fs::path stage = folder.parent_path() / ("." + folder.filename().string() + tmpSuffix());
  stage_slot_ = registerPath(stage.string());  // before the folder exists: a signal never misses it
  if (::mkdir(stage.c_str(), 0777) != 0) {
    const int err = errno;
    unregisterPath(stage_slot_);
    stage_slot_ = -1;
    throw InputError(folder_, std::string("cannot write the output folder: ") + std::strerror(err));
  }
  stage_ = stage.string();
}

std::string OutputSet::add(const std::string& final_path) {
  const fs::path p = absoluteNormal(final_path);
  if (!folder_.empty() && isInside(p, fs::path(folder_))) {
    ensureStage();
    const fs::path tmp = fs::path(stage_) / p.lexically_relative(fs::path(folder_));
    std::vector<std::string> inside;  // removed with the stage
    try {
      createDirectories(tmp.parent_path(), inside);
    } catch (const std::runtime_error& e) {
      throw InputError(fs::path(final_path).parent_path().string(), e.what());
    }
    finals_.push_back(final_path);
    temps_.push_back(tmp.string());
    staged_.push_back(true);
    return tmp.string();
  }
  const fs::path fp(final_path);
  if (fp.has_parent_path()) {
    try {
      createDirectories(fp.parent_path(), created_dirs_);
    } catch (const std::runtime_error& e) {
      throw InputError(fp.parent_path().string(), e.what());
    }
  }
  const std::string name = fp.filename().string();
  const std::string tmp = (fp.parent_path() / ("." + name + tmpSuffix() + extensionsOf(name))).string();
  slots_.push_back(registerPath(absoluteNormal(tmp).string()));
  finals_.push_back(final_path);
  temps_.push_back(tmp);
  staged_.push_back(false);
  return tmp;
}

void OutputSet::write(const std::string& final_path, const std::function<void(const std::string&)>& writer) {
  const std::string tmp = add(final_path);
  const fs::path dir = fs::path(tmp).parent_path().empty() ? fs::path(".") : fs::path(tmp).parent_path();
  try {
    writer(tmp);
  } catch (const InputError&) {
    throw;  // bad input found while writing: already names its file
  } catch (const std::exception& e) {
    if (noSpaceLeft(dir)) throw std::runtime_error(final_path + ": cannot write: " + std::strerror(ENOSPC));
    std::string reason = reasonOf(e);
    replaceAll(reason, tmp, final_path);
    if (reason.find(final_path) == std::string::npos) reason = final_path + ": cannot write: " + reason;
    throw std::runtime_error(reason);
  }
  if (noSpaceLeft(dir)) throw std::runtime_error(final_path + ": cannot write: " + std::strerror(ENOSPC));
}

void OutputSet::commit() {
  for (std::size_t i = 0; i < temps_.size(); ++i) {
    if (!fs::exists(temps_[i]))
      throw std::runtime_error("output " + finals_[i] + " was not written (temporary file missing)");
    if (!staged_[i] && fs::is_directory(finals_[i])) throw std::runtime_error("output " + finals_[i] + " is a directory");
  }
  CommitGuard guard;  // SIGINT / SIGTERM wait until the set has landed or was put back
  // The loose files: existing files first moved aside, so that a rename failing half-way can put every final path
  // back as it was.
  std::vector<std::string> backups(finals_.size());
  std::size_t moved_aside = 0, renamed = 0;
  auto put_back = [&] {
    std::error_code ec;
    for (std::size_t i = 0; i < renamed; ++i)
      if (!staged_[i]) fs::rename(finals_[i], temps_[i], ec);  // the destructor removes them
    for (std::size_t i = 0; i < moved_aside; ++i)
      if (!backups[i].empty()) fs::rename(backups[i], finals_[i], ec);
  };
  try {
    for (; moved_aside < finals_.size(); ++moved_aside) {
      const std::string& f = finals_[moved_aside];
      if (staged_[moved_aside] || !fs::exists(fs::symlink_status(f))) continue;
      backups[moved_aside] = temps_[moved_aside] + ".previous";
      renameOrThrow(f, backups[moved_aside], f);
    }
    for (; renamed < temps_.size(); ++renamed)
      if (!staged_[renamed]) renameOrThrow(temps_[renamed], finals_[renamed], finals_[renamed]);
    commitStage();
  } catch (...) {
    put_back();
    throw;
  }
  for (const auto& b : backups)
    if (!b.empty()) {
      std::error_code ec;
      fs::remove(b, ec);
    }
  committed_ = true;
  for (int& s : slots_) unregisterPath(std::exchange(s, -1));
  unregisterPath(std::exchange(stage_slot_, -1));
}

void OutputSet::commitStage() {
  if (stage_.empty()) return;
  const fs::path folder = realFolder(folder_), stage(stage_);
  struct stat st {};
  if (::lstat(folder.c_str(), &st) != 0) {
    if (errno != ENOENT) throwSystem(folder_ + ": cannot write the output folder", errno);
    renameOrThrow(stage, folder, folder_);  // a new folder: one rename
    return;
  }
  if (!S_ISDIR(st.st_mode)) throw std::runtime_error(folder_ + ": cannot write the output folder: it is not a folder");
  // The run's files, by their paths inside the folder; the old folder is "foreign" when it holds a file the run
  // does not write (a user's, or an earlier run's with other options: never removed) or a folder where the run
  // writes a file.
  std::set<std::string> ours;
  for (const auto& e : fs::recursive_directory_iterator(stage))
    if (!e.is_directory()) ours.insert(fs::relative(e.path(), stage).string());
  bool foreign = false;
  for (auto it = fs::recursive_directory_iterator(folder); it != fs::recursive_directory_iterator(); ++it) {
    const std::string rel = fs::relative(it->path(), folder).string();
    if (isOutputTemporary(it->path().filename().string())) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    if (it->is_directory() && !it->is_symlink() ? ours.count(rel) > 0 : ours.count(rel) == 0) foreign = true;
  }
  // The current folder of this process (or a folder around it) is never swapped: the shell would be left in a
  // removed folder.
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  const bool holds_cwd = !ec && (fs::equivalent(cwd, folder, ec) || isInside(cwd, fs::canonical(folder, ec)));
  if (!foreign && !holds_cwd) {
    // The old folder holds nothing but outputs of this kind: the new one replaces it with one atomic exchange,
    // then the old one (now at the stage's name) is removed.
    if (::syscall(SYS_renameat2, AT_FDCWD, stage.c_str(), AT_FDCWD, folder.c_str(), 2 /* RENAME_EXCHANGE */) == 0) {
      std::error_code rm;
      fs::remove_all(stage, rm);
      return;
    }
    if (errno != EINVAL && errno != ENOSYS && errno != EPERM)
      throwSystem(folder_ + ": cannot move the new output folder into place", errno);
    // No exchange on this file system: two renames, the old folder aside first.
    const fs::path old = fs::path(stage_ + ".old");
    const int old_slot = registerPath(old.string());
    renameOrThrow(folder, old, folder_);
    if (::rename(stage.c_str(), folder.c_str()) != 0) {
      const int err = errno;
      ::rename(old.c_str(), folder.c_str());
      unregisterPath(old_slot);
      throwSystem(folder_ + ": cannot move the new output folder into place", err);
    }
    std::error_code rm;
    fs::remove_all(old, rm);
    unregisterPath(old_slot);
    return;
  }
  // A folder with other files: the run's files are moved in one by one (each one rename; the folders they need
  // made), what they replace moved aside first; if one move fails, everything is put back as it was.
  removeStaleTemporaries(folder, ".");
  const std::vector<std::string> files(ours.begin(), ours.end());
  for (const auto& rel : files)
    if (fs::is_directory(folder / rel)) throw std::runtime_error("output " + (folder / rel).string() + " is a directory");
  std::vector<std::string> backups(files.size()), made_dirs;
  std::size_t aside = 0, moved = 0;
  try {
    for (const auto& rel : files) createDirectories((folder / rel).parent_path(), made_dirs);
    for (; aside < files.size(); ++aside) {
      const fs::path target = folder / files[aside];
      if (!fs::exists(fs::symlink_status(target))) continue;
      backups[aside] = (target.parent_path() / ("." + target.filename().string() + tmpSuffix() + ".previous")).string();
      renameOrThrow(target, backups[aside], target.string());
    }
    for (; moved < files.size(); ++moved)
      renameOrThrow(stage / files[moved], folder / files[moved], (folder / files[moved]).string());
  } catch (...) {
    std::error_code e2;
    for (std::size_t i = 0; i < moved; ++i) fs::rename(folder / files[i], stage / files[i], e2);
    for (std::size_t i = 0; i < aside; ++i)
      if (!backups[i].empty()) fs::rename(backups[i], folder / files[i], e2);
    for (auto it = made_dirs.rbegin(); it != made_dirs.rend(); ++it) fs::remove(*it, e2);
    throw;
  }
  for (const auto& b : backups)
    if (!b.empty()) {
      std::error_code rm;
      fs::remove(b, rm);
    }
  std::error_code rm;
  fs::remove_all(stage, rm);
}

// ---- checks before a run -------------------------------------------------------------------------------------

void checkOutputFolder(const std::string& folder) {
  if (folder.empty()) throw InputError("<output>", "no output folder given");
  const fs::path f = absoluteNormal(folder);
  struct stat st {};
  if (::stat(f.c_str(), &st) == 0) {
    if (!S_ISDIR(st.st_mode)) throw InputError(folder, "cannot write the output folder: it exists and is not a folder");
    struct stat parent {};
    if (::stat(f.parent_path().c_str(), &parent) == 0 && parent.st_dev != st.st_dev)
      throw InputError(folder, "cannot write the output folder: it is a mount point (give a folder inside it)");
    if (::access(f.c_str(), W_OK | X_OK) != 0)
      throw InputError(folder, std::string("cannot write the output folder: ") + std::strerror(errno));
  }
  // What commit needs: a stage folder beside it (made, then removed with the folders made for it).
  OutputSet probe(folder);
  probe.add((f / "probe").string());
}

void checkOutputFile(const std::string& path) {
  if (path.empty()) throw InputError("<output>", "no output file given");
  const fs::path p = absoluteNormal(path);
  if (fs::is_directory(p)) throw InputError(path, "cannot write the output file: it is a folder");
  std::vector<std::string> created;
  try {
    createDirectories(p.parent_path(), created);
  } catch (const std::runtime_error& e) {
    for (auto it = created.rbegin(); it != created.rend(); ++it) ::rmdir(it->c_str());
    throw InputError(path, e.what());
  }
  const int err = ::access(p.parent_path().c_str(), W_OK | X_OK) == 0 ? 0 : errno;
  for (auto it = created.rbegin(); it != created.rend(); ++it) ::rmdir(it->c_str());
  if (err != 0) throw InputError(path, std::string("cannot write the output file: ") + std::strerror(err));
}

void installOutputCleanupOnSignals() {
  if (g_installed.exchange(true)) return;
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    ::sigaction(sig, nullptr, &old);
    if (old.sa_handler == SIG_IGN) continue;  // e.g. nohup: stay ignored
    ::sigaction(sig, &sa, nullptr);
  }
}

// ---- single files --------------------------------------------------------------------------------------------

void writeFileAtomically(const std::string& path, const std::function<void(const std::string&)>& writer) {
  OutputSet set;
  set.write(path, writer);
  set.commit();
}

void writeTextFileAtomically(const std::string& path, const std::string& content) {
  writeFileAtomically(path, [&](const std::string& tmp) {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) throwSystem(path + ": cannot open for writing", errno);
    std::size_t done = 0;
    while (done < content.size()) {
      const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const int err = n < 0 ? errno : EIO;
        ::close(fd);
        throwSystem(path + ": cannot write", err);
      }
      done += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0) throwSystem(path + ": cannot write", errno);
  });
}

}  // namespace gridtopo
