#include "isolated_parse.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <new>

#include "gridtopo/core/error.h"

namespace gridtopo::io {
namespace {

constexpr std::uint64_t kNoEntry = ~std::uint64_t{0};

std::string entryName(std::uint64_t entry) {
  return entry == kNoEntry ? std::string() : "entry " + std::to_string(entry);
}

/// What the checking child leaves for its parent (in shared memory).
struct ChildReport {
  volatile std::uint64_t entry;  ///< the top-level entry being read
  volatile int status;           ///< 0 running / parsed, 1 an exception, 2 out of its address space
  char field[128];
  char message[1024];
};

void copyText(char* dst, std::size_t cap, const std::string& src) {
  const std::size_t n = std::min(cap - 1, src.size());
  std::memcpy(dst, src.data(), n);
  dst[n] = '\0';
}

}  // namespace

void checkParsesInChild(const std::string& path, const std::function<void(volatile std::uint64_t* entry)>& parse) {
  void* shared = ::mmap(nullptr, sizeof(ChildReport), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (shared == MAP_FAILED) return;  // no isolation possible: parse in process as before
  auto* report = static_cast<ChildReport*>(shared);
  report->entry = kNoEntry;
  report->status = 0;
  report->field[0] = report->message[0] = '\0';
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  const std::uintmax_t file_size = ec ? 0 : size;
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::munmap(shared, sizeof(ChildReport));
    return;
  }
  if (pid == 0) {
    // Child: no core file, no output, an address space of what it has now + 1 GiB + 64 x the file size.
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    long pages = 0;
    if (FILE* statm = std::fopen("/proc/self/statm", "r")) {
      if (std::fscanf(statm, "%ld", &pages) != 1) pages = 0;
      std::fclose(statm);
    }
    if (pages > 0) {
      const auto page = static_cast<std::uintmax_t>(::sysconf(_SC_PAGESIZE));
      const std::uintmax_t limit =
          static_cast<std::uintmax_t>(pages) * page + (std::uintmax_t{1} << 30) + 64 * file_size;
      rlimit as{};
      if (::getrlimit(RLIMIT_AS, &as) == 0 && (as.rlim_max == RLIM_INFINITY || limit < as.rlim_max)) {
        as.rlim_cur = static_cast<rlim_t>(limit);
        ::setrlimit(RLIMIT_AS, &as);
      }
    }
    const int devnull = ::open("/dev/null", O_WRONLY);
    if (devnull >= 0) {
      ::dup2(devnull, STDOUT_FILENO);
      ::dup2(devnull, STDERR_FILENO);
    }
    try {
      parse(&report->entry);
    } catch (const InputError& e) {
      copyText(report->field, sizeof report->field, e.field());
      copyText(report->message, sizeof report->message, e.message());
      report->status = 1;
    } catch (const std::bad_alloc&) {
      report->status = 2;
    } catch (const std::exception& e) {
      copyText(report->field, sizeof report->field, entryName(report->entry));
      copyText(report->message, sizeof report->message, innermostMrptMessage(e.what()));
      report->status = 1;
    } catch (...) {
      copyText(report->field, sizeof report->field, entryName(report->entry));
      copyText(report->message, sizeof report->message, "unknown error while reading the file");
      report->status = 1;
    }
    ::_exit(0);
  }
  int status = 0;
  pid_t r;
  do {
    r = ::waitpid(pid, &status, 0);
  } while (r < 0 && errno == EINTR);
  const ChildReport rep = [&] {
    ChildReport c;
    c.entry = report->entry;
    c.status = report->status;
    std::memcpy(c.field, report->field, sizeof c.field);
    std::memcpy(c.message, report->message, sizeof c.message);
    return c;
  }();
  ::munmap(shared, sizeof(ChildReport));
  const std::string where = entryName(rep.entry);
  if (r == pid && WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::strsignal(sig);
    throw InputError(path, 0, where,
                     std::string("MRPT's deserialiser crashed (") + (name ? name : "signal") + ", signal " +
                         std::to_string(sig) + ") reading this object: the file is corrupted");
  }
  if (rep.status == 2)
    throw InputError(path, 0, where,
                     "reading this object needs more memory than the file can justify: the file is corrupted");
  if (rep.status == 1) throw InputError(path, 0, rep.field, rep.message);
}

/// The useful line of an MRPT exception text: MRPT nests "==== MRPT exception ====" blocks, each with a
/// "Message: ..." line, a location and a call stack; the innermost message says what went wrong (e.g. "Stored
/// object has class '...' which is not registered!"). Bytes that are not printable ASCII (corrupted class
/// names) are shown as '?'.
std::string innermostMrptMessage(const std::string& text) {
  std::string line;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string l = text.substr(pos, end - pos);
    if (l.rfind("Message:", 0) == 0) {
      line = l.substr(8);
    } else if (line.empty() && !l.empty() && l.rfind("====", 0) != 0 && text.find("Message:") == std::string::npos) {
      line = l;  // not an MRPT-formatted text: its first line
    }
    pos = end + 1;
  }
  const std::size_t first = line.find_first_not_of(' ');
  line = first == std::string::npos ? std::string() : line.substr(first);
  for (char& c : line)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return line.empty() ? "unknown error" : line;
}

}  // namespace gridtopo::io
