#include "gridtopo/experiment/subprocess.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace gridtopo::experiment {

pid_t spawnProcess(const std::vector<std::string>& argv, const std::string& log_path, const std::string& cwd) {
  if (argv.empty()) throw std::invalid_argument("spawnProcess: empty command");
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid > 0) return pid;
  // Child: only async-signal-safe calls until exec.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(126);  // the runner died between fork and prctl
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
  const int in = ::open("/dev/null", O_RDONLY);
  if (in >= 0) ::dup2(in, 0);
  if (!log_path.empty()) {
    const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
    }
  }
  if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) ::_exit(127);
  ::execv(args[0], args.data());
  const char* msg = "exec failed: ";
  (void)!::write(2, msg, std::strlen(msg));
  (void)!::write(2, args[0], std::strlen(args[0]));
  (void)!::write(2, "\n", 1);
  ::_exit(127);
}

pid_t reapChild(pid_t pid, bool block, ProcessResult& result) {
  int status = 0;
  struct rusage ru {};
  pid_t r;
  do {
    r = ::wait4(pid, &status, block ? 0 : WNOHANG, &ru);
  } while (r < 0 && errno == EINTR && block);
  if (r <= 0) return r < 0 && errno == EINTR ? 0 : r;
  if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);
    result.signal = 0;
  } else if (WIFSIGNALED(status)) {
    result.exit_code = -1;
    result.signal = WTERMSIG(status);
  }
  result.cpu_s = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                 1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  result.peak_rss_mb = static_cast<double>(ru.ru_maxrss) / 1024.0;
  return r;
}

ProcessResult runProcess(const std::vector<std::string>& argv, const std::string& log_path, const std::string& cwd) {
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = spawnProcess(argv, log_path, cwd);
  ProcessResult r;
  while (reapChild(pid, true, r) == 0) {
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::string shellQuote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:+,@%") ==
                        std::string::npos)
    return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string lastErrorLine(const std::string& path) {
  std::ifstream f(path);
  std::string line, last, last_error;
  while (std::getline(f, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    last = line;
    if (line.find("error") != std::string::npos) last_error = line;
  }
  return last_error.empty() ? last : last_error;
}

}  // namespace gridtopo::experiment
