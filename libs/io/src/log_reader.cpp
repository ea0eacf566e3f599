#include "gridtopo/io/log_reader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numeric>

#include "gridtopo/core/error.h"
#include "gridtopo/core/lazy_library.h"
#include "gridtopo/io/scan_geometry.h"
#include "rawlog_entry.h"

namespace gridtopo::io {
namespace {

double wrapToPi(double a) {
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a < 0) a += 2.0 * M_PI;
  return a - M_PI;
}

// Up to `n` leading bytes of the file, decompressed if it is gzip (zlib reads plain files as they are).
std::string leadingBytes(const std::string& path, std::size_t n) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path, std::string("cannot open the log file: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
    ::close(fd);
    throw InputError(path, std::string("cannot open the log file: ") + std::strerror(EISDIR));
  }
  gzFile f = gzdopen(fd, "rb");
  if (!f) {
    ::close(fd);
    throw InputError(path, std::string("cannot open the log file: ") + std::strerror(errno ? errno : ENOMEM));
  }
  std::string buf(n, '\0');
  const int got = gzread(f, buf.data(), static_cast<unsigned>(n));
  gzclose(f);
  // A gzip file truncated early still gives its first bytes; a hard error gives -1.
  if (got < 0) throw InputError(path, 0, "gzip", "cannot decompress the start of the file");
  buf.resize(static_cast<std::size_t>(got));
  return buf;
}

}  // namespace

const char* logFormatName(LogFormat format) {
  switch (format) {
    case LogFormat::Carmen:
      return "CARMEN";
    case LogFormat::Rawlog:
      return "MRPT rawlog";
    case LogFormat::Simulated:
      return "simulated";
    default:
      return "empty";
  }
}

LogFormat detectLogFormat(const std::string& path) {
  if (std::filesystem::is_directory(path)) throw InputError(path, "is a folder, not a log file");
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "no such log file");
  const std::string head = leadingBytes(path, 4096);
  if (head.empty()) return LogFormat::Empty;
  // MRPT serialisation starts every object with its class name: one byte holding the name's length (with the
  // high bit set in the current format), then the name ("mrpt::obs::CActionCollection", ...). CARMEN logs are
  // text lines, whose first "name" would contain spaces.
  const std::size_t len = static_cast<unsigned char>(head[0]) & 0x7f;
  if (len >= 1 && head.size() > len) {
    const bool identifier =
        std::all_of(head.begin() + 1, head.begin() + 1 + static_cast<std::ptrdiff_t>(len),
                    [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == ':'; });
    if (identifier) return LogFormat::Rawlog;
  }
  return LogFormat::Carmen;
}

std::size_t interpolateOdometry(std::vector<ScanRecord>& scans, const std::vector<OdometryReading>& odometry) {
  if (odometry.empty()) return scans.size();
  std::vector<std::size_t> order(odometry.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return odometry[a].timestamp < odometry[b].timestamp; });
  std::size_t fallbacks = 0;
  for (auto& rec : scans) {
    const double t = rec.scan.timestamp;
    // First reading later than t; the one before it is the latest at or before t.
    const auto it = std::upper_bound(order.begin(), order.end(), t,
                                     [&](double v, std::size_t i) { return v < odometry[i].timestamp; });
    if (it == order.begin()) {
      ++fallbacks;
      continue;
    }
    const OdometryReading& a = odometry[*(it - 1)];
    if (a.timestamp == t) {
      rec.odometry = a.pose;
    } else if (it == order.end()) {
      ++fallbacks;
      continue;
    } else {
      const OdometryReading& b = odometry[*it];
      const double f = (t - a.timestamp) / (b.timestamp - a.timestamp);
      rec.odometry = {a.pose.x + f * (b.pose.x - a.pose.x), a.pose.y + f * (b.pose.y - a.pose.y),
                      wrapToPi(a.pose.phi + f * wrapToPi(b.pose.phi - a.pose.phi))};
    }
    rec.has_odometry = true;
  }
  return fallbacks;
}

std::vector<ScanRecord> readScanLog(const std::string& path, const LogReadOptions& options) {
  ScanLogInfo info;
  return readScanLog(path, options, info);
}

std::vector<ScanRecord> readScanLog(const std::string& path, const LogReadOptions& options, ScanLogInfo& info) {
  info = ScanLogInfo{};
  info.format = detectLogFormat(path);
  switch (info.format) {
    case LogFormat::Empty:
      return {};
    case LogFormat::Rawlog: {
      // MRPT's observations (and the ~170 libraries they bring) only for a rawlog: libgridtopo_io, loaded now.
      RawlogScans raw;
      lazyLibraryFunction<ReadRawlogScansFunction>("io", kReadRawlogScansSymbol)(path, raw);
      info.odometry_messages = raw.odometry_observations;
      info.lines_or_entries = raw.entries;
      info.rawlog_has_actions = raw.has_actions;
      return std::move(raw.scans);
    }
    case LogFormat::Carmen:
    case LogFormat::Simulated:
      break;
  }
  CarmenLog log = readCarmenLog(path, options.carmen);
  info.odometry_messages = log.odometry.size();
  info.lines_or_entries = log.lines;
  info.skipped_lines = log.skipped_lines;
  info.skipped = std::move(log.skipped);
  info.skipped_messages = std::move(log.skipped_messages);
  info.warnings = std::move(log.warnings);
  info.notes = std::move(log.notes);
  if (options.odometry == OdometrySource::OdomLines)
    info.odometry_fallbacks = interpolateOdometry(log.scans, log.odometry);
  // The geometry an MRPT rawlog of this log would hold (a rawlog's scans come through fromMrptScan already).
  for (ScanRecord& r : log.scans) useMrptScanGeometry(r.scan);
  return std::move(log.scans);
}

}  // namespace gridtopo::io
