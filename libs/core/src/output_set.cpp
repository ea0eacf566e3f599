#include "gridtopo/core/output_set.h"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "gridtopo/core/error.h"

namespace fs = std::filesystem;

namespace gridtopo {
namespace {
std::atomic<unsigned> g_counter{0};

// Everything after the first '.' of the file name that is not at its start, e.g. ".gridmap.gz".
std::string extensionsOf(const std::string& name) {
  const auto pos = name.find('.', 1);
  return pos == std::string::npos ? std::string() : name.substr(pos);
}
}  // namespace

OutputSet::~OutputSet() {
  if (committed_) return;
  for (const auto& t : temps_) {
    std::error_code ec;
    fs::remove(t, ec);
  }
  // The directories add() created, deepest first: removed when empty (fs::remove leaves a non-empty one).
  for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) {
    std::error_code ec;
    fs::remove(*it, ec);
  }
}

std::string OutputSet::add(const std::string& final_path) {
  const fs::path p(final_path);
  if (p.has_parent_path()) {
    // The directories about to be made, outermost first, so that an uncommitted set can take them away again.
    std::vector<fs::path> missing;
    for (fs::path d = p.parent_path(); !d.empty() && !fs::exists(d); d = d.parent_path()) missing.push_back(d);
    std::error_code ec;
    fs::create_directories(p.parent_path(), ec);
    for (auto it = missing.rbegin(); it != missing.rend(); ++it)
      if (fs::is_directory(*it)) created_dirs_.push_back(*it);
    if (ec) throw InputError(p.parent_path().string(), "cannot create the output folder: " + ec.message());
  }
  const std::string name = p.filename().string();
  const std::string tmp_name = "." + name + ".tmp-" + std::to_string(::getpid()) + "-" +
                               std::to_string(g_counter++) + extensionsOf(name);
  const std::string tmp = (p.parent_path() / tmp_name).string();
  finals_.push_back(final_path);
  temps_.push_back(tmp);
  return tmp;
}

void OutputSet::write(const std::string& final_path, const std::function<void(const std::string&)>& writer) {
  writer(add(final_path));
}

void OutputSet::commit() {
  for (std::size_t i = 0; i < temps_.size(); ++i) {
    if (!fs::exists(temps_[i]))
      throw std::runtime_error("output " + finals_[i] + " was not written (temporary file missing)");
  }
  // A final path that is a directory cannot be replaced: say so before anything moves.
  for (const auto& f : finals_)
    if (fs::is_directory(f)) throw std::runtime_error("output " + f + " is a directory");
  // Existing files are first moved aside, so that a rename failing half-way can put every final path back as it
  // was: the set lands whole or not at all.
  std::vector<std::string> backups(finals_.size());
  std::size_t moved_aside = 0, renamed = 0;
  try {
    for (; moved_aside < finals_.size(); ++moved_aside) {
      const std::string& f = finals_[moved_aside];
      if (!fs::exists(fs::symlink_status(f))) continue;
      backups[moved_aside] = temps_[moved_aside] + ".previous";
      fs::rename(f, backups[moved_aside]);
    }
    for (; renamed < temps_.size(); ++renamed) fs::rename(temps_[renamed], finals_[renamed]);
  } catch (...) {
    std::error_code ec;
    for (std::size_t i = 0; i < renamed; ++i) fs::rename(finals_[i], temps_[i], ec);  // the destructor removes them
    for (std::size_t i = 0; i < moved_aside; ++i)
      if (!backups[i].empty()) fs::rename(backups[i], finals_[i], ec);
    throw;
  }
  for (const auto& b : backups)
    if (!b.empty()) {
      std::error_code ec;
      fs::remove(b, ec);
    }
  committed_ = true;
}

void writeFileAtomically(const std::string& path, const std::function<void(const std::string&)>& writer) {
  OutputSet set;
  set.write(path, writer);
  set.commit();
}

void writeTextFileAtomically(const std::string& path, const std::string& content) {
  writeFileAtomically(path, [&](const std::string& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) throw std::runtime_error("cannot open " + tmp + " for writing");
    f << content;
    f.flush();
    if (!f) throw std::runtime_error("error writing " + path);
  });
}

}  // namespace gridtopo
