#pragma once
// Runs one of the built gridtopo apps (GRIDTOPO_BIN_DIR) with arguments, for the apps' tests: exit status and the
// output of stdout and stderr together.
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace gridtopo::testing_app {

struct AppRun {
  int status;          ///< exit code; -1 when the app did not exit normally (a crash)
  std::string output;  ///< stdout and stderr
};

inline AppRun runApp(const std::string& app, const std::string& args) {
  const std::string cmd = std::string(GRIDTOPO_BIN_DIR) + "/" + app + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

}  // namespace gridtopo::testing_app
