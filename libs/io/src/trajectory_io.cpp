#include "gridtopo/io/trajectory_io.h"

#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"

namespace gridtopo::io {

std::string formatDouble(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string formatTrajectory(const std::vector<TimedPose>& poses, const std::vector<std::string>& header) {
  std::string out;
  for (const auto& h : header) out += "# " + h + "\n";
  out += "# timestamp x y theta\n";
  for (const auto& p : poses) {
    out += formatDouble(p.timestamp) + ' ' + formatDouble(p.pose.x) + ' ' + formatDouble(p.pose.y) + ' ' +
           formatDouble(p.pose.phi) + '\n';
  }
  return out;
}

void writeTrajectory(const std::string& path, const std::vector<TimedPose>& poses,
                     const std::vector<std::string>& header) {
  writeTextFileAtomically(path, formatTrajectory(poses, header));
}

std::vector<TimedPose> readTrajectory(const std::string& path) {
  errno = 0;
  std::ifstream f(path);
  if (!f || std::filesystem::is_directory(path))
    throw InputError(path, std::string("cannot open the trajectory file: ") +
                               std::strerror(std::filesystem::is_directory(path) ? EISDIR : errno ? errno : ENOENT));
  std::vector<TimedPose> out;
  std::string line;
  std::size_t lineno = 0;
  static const char* kFields[] = {"timestamp", "x", "y", "theta"};
  while (std::getline(f, line)) {
    ++lineno;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    double v[4];
    const char* p = line.data() + first;
    const char* end = line.data() + line.size();
    for (int i = 0; i < 4; ++i) {
      while (p < end && (*p == ' ' || *p == '\t')) ++p;
      if (p == end || *p == '\r')
        throw InputError(path, lineno, kFields[i], "missing (each line is 'timestamp x y theta')");
      const auto res = std::from_chars(p, end, v[i]);
      if (res.ec != std::errc() || !std::isfinite(v[i]))
        throw InputError(path, lineno, kFields[i], "expected a finite number");
      p = res.ptr;
    }
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
    if (p != end) throw InputError(path, lineno, "line", "unexpected text after theta");
    out.push_back({v[0], {v[1], v[2], v[3]}});
  }
  if (f.bad()) throw InputError(path, lineno, "", "read error");
  return out;
}

}  // namespace gridtopo::io
