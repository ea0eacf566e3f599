// CARMEN log reader (plain text or gzip). Format reference: the CARMEN logger's header comments and the
// Freiburg SLAM benchmark's description (Kümmerle et al. 2009); see doc/carmen.md for every quirk handled.
#include "gridtopo/io/carmen_log.h"

#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>
#include <set>
#include <string_view>

#include "gridtopo/core/error.h"

namespace gridtopo::io {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

double wrapAngle(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0) a += 2.0 * kPi;
  return a - kPi;
}

/// p1⁻¹ ⊕ p2: the pose p2 expressed in the frame of p1.
mrpt::math::TPose2D relativePose(const mrpt::math::TPose2D& p1, const mrpt::math::TPose2D& p2) {
  const double c = std::cos(p1.phi), s = std::sin(p1.phi);
  const double dx = p2.x - p1.x, dy = p2.y - p1.y;
  return {c * dx + s * dy, -s * dx + c * dy, wrapAngle(p2.phi - p1.phi)};
}

// ---------------------------------------------------------------------------------------------------------
// gzip

bool hasGzipMagic(const std::string& data) {
  return data.size() >= 2 && static_cast<unsigned char>(data[0]) == 0x1f &&
         static_cast<unsigned char>(data[1]) == 0x8b;
}

/// Inflates every gzip member of `in`. Truncated or corrupt data throws InputError (never returns a prefix).
std::string gunzip(const std::string& in, const std::string& name) {
  std::string out;
  out.resize(std::max<std::size_t>(in.size() * 4, 1 << 16));
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 16) != Z_OK) throw InputError(name, 0, "gzip", "cannot initialise zlib");
  struct Guard {
    z_stream* z;
    ~Guard() { inflateEnd(z); }
  } guard{&zs};

  std::size_t in_pos = 0, out_pos = 0;
  for (;;) {
    if (zs.avail_in == 0 && in_pos < in.size()) {
      const std::size_t chunk = std::min<std::size_t>(in.size() - in_pos, 1u << 30);
      zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data() + in_pos));
      zs.avail_in = static_cast<uInt>(chunk);
      in_pos += chunk;
    }
    if (out_pos == out.size()) out.resize(out.size() * 2);
    const std::size_t out_room = std::min<std::size_t>(out.size() - out_pos, 1u << 30);
    zs.next_out = reinterpret_cast<Bytef*>(out.data() + out_pos);
    zs.avail_out = static_cast<uInt>(out_room);
    const int ret = inflate(&zs, Z_NO_FLUSH);
    out_pos += out_room - zs.avail_out;
    if (ret == Z_STREAM_END) {
      // Concatenated members (gzip allows them): continue if another member follows, else stop (trailing
      // zero padding is ignored like gzip does).
      const std::size_t consumed = in_pos - zs.avail_in;
      if (consumed + 2 <= in.size() && static_cast<unsigned char>(in[consumed]) == 0x1f &&
          static_cast<unsigned char>(in[consumed + 1]) == 0x8b) {
        inflateReset(&zs);
        continue;
      }
      break;
    }
    if (ret == Z_OK) continue;
    if (ret == Z_BUF_ERROR && zs.avail_in == 0 && in_pos >= in.size())
      throw InputError(name, 0, "gzip",
                       "truncated compressed file (unexpected end after " + std::to_string(out_pos) +
                           " decompressed bytes)");
    if (ret == Z_BUF_ERROR) continue;  // needs more output room: loop grows the buffer
    throw InputError(name, 0, "gzip",
                     std::string("corrupt compressed data: ") + (zs.msg ? zs.msg : "zlib error " +
                                                                                     std::to_string(ret)));
  }
  out.resize(out_pos);
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// Line parsing

/// Message names that are CARMEN (or GMapping log) messages gridtopo does not need: skipped silently.
const std::set<std::string_view>& ignoredMessages() {
  static const std::set<std::string_view> names = {
      "TRUEPOS",   "SYNC",       "NMEA-GGA",  "NMEA-RMC",    "NMEA-GSA",    "NMEA-GSV",     "NMEA-VTG",
      "GPSNMEA",   "RAWLASER2",  "RAWLASER3", "RAWLASER4",   "ROBOTLASER3", "ROBOTLASER4",  "ROBOTVELOCITY",
      "VELOCITY",  "VECTORMOVE", "SONAR",     "BUMPER",      "SCANMARK",    "POSITIONLASER", "IMU",
      "FUSED_ODOM", "ARM",       "BASE",      "NEFF",        "LOCALIZEPOS", "GLOBALPOS",    "MARKER",
      "LASER3D",   "KINECT",     "CAMERA",    "PANTILT",     "BASEVELOCITY", "PEARLASER"};
  return names;
}

void tokenize(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r' || line[i] == '\v' || line[i] == '\f'))
      ++i;
    if (i >= n) break;
    const std::size_t b = i;
    while (i < n && !(line[i] == ' ' || line[i] == '\t' || line[i] == '\r' || line[i] == '\v' || line[i] == '\f'))
      ++i;
    out.push_back(line.substr(b, i - b));
  }
}

/// Printable excerpt of a token for error messages.
std::string excerpt(std::string_view t) {
  std::string s;
  for (std::size_t i = 0; i < t.size() && i < 24; ++i) {
    const auto c = static_cast<unsigned char>(t[i]);
    s += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
  }
  if (t.size() > 24) s += "...";
  return s;
}

/// Laser geometry that a FLASER/RLASER line does not carry; completed from the PARAMs after the whole log is
/// read (PARAM lines may come anywhere).
struct PendingGeometry {
  std::size_t index;      // into CarmenLog::scans or raw scans
  bool rear;              // RLASER / ROBOTLASER2
  bool infer_angles;      // FLASER/RLASER: aperture from beam count and PARAMs
  bool infer_max_range;   // FLASER/RLASER: max range from PARAMs or the default
  bool pose_from_params;  // laser pose equals robot pose in the line: use PARAM offsets if they say otherwise
};

class Parser {
 public:
  Parser(const std::string& name, const CarmenReadOptions& options, CarmenLog& log)
      : name_(name), options_(options), log_(log) {}

  void parseAll(std::string_view text) {
    std::size_t pos = 0;
    std::size_t lineno = 0;
    while (pos < text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      ++lineno;
      const std::string_view line = text.substr(pos, end - pos);
      pos = end + 1;
      try {
        parseLine(line, lineno);
      } catch (const InputError& e) {
        if (!options_.skip_bad_lines) throw;
        ++log_.skipped_lines;
        if (log_.skipped.size() < options_.max_reported_skips) log_.skipped.push_back(e.what());
      }
    }
    log_.lines = lineno;
    finish();
  }

 private:
  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw InputError(name_, lineno_, field, message);
  }

  double number(std::string_view tok, const char* msg, const std::string& field, bool finite = true) const {
    const char* b = tok.data();
    const char* e = tok.data() + tok.size();
    if (b != e && *b == '+') ++b;
    double v = 0;
    const auto res = std::from_chars(b, e, v);
    if (res.ec == std::errc::result_out_of_range) {
      // from_chars reports overflow/underflow; strtod gives ±HUGE_VAL / 0 like the CARMEN writer intended.
      v = std::strtod(std::string(tok).c_str(), nullptr);
    } else if (res.ec != std::errc() || res.ptr != e || b == e) {
      fail(std::string(msg) + field, "not a number ('" + excerpt(tok) + "')");
    }
    if (finite && !std::isfinite(v)) fail(std::string(msg) + field, "not a finite number ('" + excerpt(tok) + "')");
    return v;
  }

  std::size_t count(std::string_view tok, const char* msg, const std::string& field) const {
    unsigned long long v = 0;
    const auto res = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (res.ec != std::errc() || res.ptr != tok.data() + tok.size() || tok.empty())
      fail(std::string(msg) + field, "not a non-negative integer ('" + excerpt(tok) + "')");
    if (v > 10'000'000ull) fail(std::string(msg) + field, "implausibly large (" + std::to_string(v) + ")");
    return static_cast<std::size_t>(v);
  }

  void expectTokens(const char* msg, std::size_t expected, const std::string& what) const {
    if (tok_.size() != expected)
      fail(msg, "expected " + std::to_string(expected) + " tokens" + what + ", found " +
                    std::to_string(tok_.size()));
  }

  mrpt::math::TPose2D pose(std::size_t i, const char* msg, const char* px, const char* py,
                           const char* pt) const {
    return {number(tok_[i], msg, px), number(tok_[i + 1], msg, py), number(tok_[i + 2], msg, pt)};
  }

  /// The last three tokens: ipc_timestamp ipc_hostname logger_timestamp.
  void timestamps(const char* msg, double& ipc, double& logger) const {
    const std::size_t n = tok_.size();
    ipc = number(tok_[n - 3], msg, " ipc_timestamp");
    logger = number(tok_[n - 1], msg, " logger_timestamp");
  }

  void readRanges(std::size_t first, std::size_t n, const char* msg, LaserScan& scan) const {
    scan.ranges.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::string_view t = tok_[first + k];
      const char* b = t.data();
      const char* e = t.data() + t.size();
      double v = 0;
      const auto res = std::from_chars(b, e, v);
      if (res.ec != std::errc() || res.ptr != e) {
        // Slow path for '+', out-of-range exponents etc.; still reports a clear error.
        v = number(t, msg, " range " + std::to_string(k + 1), /*finite=*/false);
      }
      // Out of float range (a finite double such as 1e300) becomes ±inf rather than undefined behaviour.
      scan.ranges[k] = !(std::abs(v) > static_cast<double>(std::numeric_limits<float>::max()))
                           ? static_cast<float>(v)
                           : (v > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity());
    }
  }

  void parseLine(std::string_view line, std::size_t lineno) {
    lineno_ = lineno;
    tokenize(line, tok_);
    if (tok_.empty() || tok_[0][0] == '#') return;
    const std::string_view type = tok_[0];
    if (type == "FLASER" || type == "RLASER") {
      parseOldLaser(type == "RLASER");
    } else if (type == "ODOM") {
      parseOdom();
    } else if (type == "ROBOTLASER1" || type == "ROBOTLASER2") {
      parseRobotLaser(type == "ROBOTLASER2");
    } else if (type == "RAWLASER1") {
      parseRawLaser();
    } else if (type == "PARAM") {
      parseParam();
    } else if (ignoredMessages().count(type) == 0) {
      fail("message", "unknown message type '" + excerpt(type) + "'");
    }
  }

  // FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname logger_timestamp
  void parseOldLaser(bool rear) {
    const char* msg = rear ? "RLASER" : "FLASER";
    if (tok_.size() < 2) fail(msg, "missing num_readings");
    const std::size_t n = count(tok_[1], msg, " num_readings");
    if (n == 0) fail(std::string(msg) + " num_readings", "a scan needs at least one reading");
    expectTokens(msg, n + 11, " for " + std::to_string(n) + " readings");
    ScanRecord rec;
    readRanges(2, n, msg, rec.scan);
    const auto laser = pose(2 + n, msg, " x", " y", " theta");
    rec.odometry = pose(5 + n, msg, " odom_x", " odom_y", " odom_theta");
    rec.has_odometry = true;
    timestamps(msg, rec.scan.timestamp, rec.scan.logger_timestamp);
    rec.scan.sensor_pose = relativePose(rec.odometry, laser);
    rec.source_index = lineno_;
    const bool centred = std::abs(rec.scan.sensor_pose.x) < 1e-12 && std::abs(rec.scan.sensor_pose.y) < 1e-12 &&
                         std::abs(rec.scan.sensor_pose.phi) < 1e-12;
    if (rear && !options_.read_rear_laser) return;
    pending_.push_back({log_.scans.size(), rear, true, true, centred});
    log_.scans.push_back(std::move(rec));
  }

  // The part ROBOTLASER1/2 and RAWLASER1 share: laser_type start_angle fov angular_res max_range accuracy
  //   remission_mode n r1..rn m rem1..remm, followed by `trailing` more tokens. Fills the scan's geometry and
  //   ranges; returns the index of the first trailing token.
  std::size_t parseLaserConfigAndReadings(const char* msg, std::size_t trailing, LaserScan& s) {
    if (tok_.size() < 9) fail(msg, "expected at least 9 tokens, found " + std::to_string(tok_.size()));
    number(tok_[1], msg, " laser_type");
    s.start_angle = number(tok_[2], msg, " start_angle");
    const double fov = number(tok_[3], msg, " fov");
    s.angle_increment = number(tok_[4], msg, " angular_resolution");
    s.max_range = number(tok_[5], msg, " max_range");
    number(tok_[6], msg, " accuracy");
    number(tok_[7], msg, " remission_mode");
    const std::size_t n = count(tok_[8], msg, " num_readings");
    if (n == 0) fail(std::string(msg) + " num_readings", "a scan needs at least one reading");
    if (9 + n + 1 > tok_.size()) expectTokens(msg, 9 + n + 1 + trailing, " for " + std::to_string(n) + " readings");
    const std::size_t m = count(tok_[9 + n], msg, " num_remissions");
    expectTokens(msg, 9 + n + 1 + m + trailing,
                 " for " + std::to_string(n) + " readings and " + std::to_string(m) + " remissions");
    if (s.angle_increment == 0.0 && n > 1) {
      // Some writers leave the resolution empty: derive it from the field of view.
      s.angle_increment = fov / static_cast<double>(n - 1);
    }
    readRanges(9, n, msg, s);
    for (std::size_t k = 0; k < m; ++k) number(tok_[10 + n + k], msg, " remission " + std::to_string(k + 1), false);
    return 10 + n + m;
  }

  // ROBOTLASER1 <laser config and readings> laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv
  //   forward_safety side_safety turn_axis ipc_timestamp ipc_hostname logger_timestamp
  void parseRobotLaser(bool rear) {
    const char* msg = rear ? "ROBOTLASER2" : "ROBOTLASER1";
    ScanRecord rec;
    LaserScan& s = rec.scan;
    const std::size_t p = parseLaserConfigAndReadings(msg, 14, s);
    const auto laser = pose(p, msg, " laser_x", " laser_y", " laser_theta");
    rec.odometry = pose(p + 3, msg, " robot_x", " robot_y", " robot_theta");
    rec.has_odometry = true;
    number(tok_[p + 6], msg, " tv");
    number(tok_[p + 7], msg, " rv");
    timestamps(msg, s.timestamp, s.logger_timestamp);
    s.sensor_pose = relativePose(rec.odometry, laser);
    rec.source_index = lineno_;
    const bool centred = std::abs(s.sensor_pose.x) < 1e-12 && std::abs(s.sensor_pose.y) < 1e-12 &&
                         std::abs(s.sensor_pose.phi) < 1e-12;
    if (rear && !options_.read_rear_laser) return;
    const bool infer_max = !(s.max_range > 0.0);
    pending_.push_back({log_.scans.size(), rear, false, infer_max, centred});
    log_.scans.push_back(std::move(rec));
  }

  // RAWLASER1 <laser config and readings> ipc_timestamp ipc_hostname logger_timestamp
  //   (no pose: used only if the log has no posed scans)
  void parseRawLaser() {
    const char* msg = "RAWLASER1";
    ScanRecord rec;
    LaserScan& s = rec.scan;
    parseLaserConfigAndReadings(msg, 3, s);
    timestamps(msg, s.timestamp, s.logger_timestamp);
    rec.has_odometry = false;
    rec.source_index = lineno_;
    raw_pending_.push_back({raw_scans_.size(), false, false, !(s.max_range > 0.0), true});
    raw_scans_.push_back(std::move(rec));
  }

  // ODOM x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp
  void parseOdom() {
    const char* msg = "ODOM";
    expectTokens(msg, 10, "");
    OdometryReading o;
    o.pose = pose(1, msg, " x", " y", " theta");
    o.tv = number(tok_[4], msg, " tv");
    o.rv = number(tok_[5], msg, " rv");
    number(tok_[6], msg, " accel");
    timestamps(msg, o.timestamp, o.logger_timestamp);
    o.source_index = lineno_;
    log_.odometry.push_back(o);
  }

  // PARAM name value ipc_hostname logger_timestamp  (no ipc_timestamp; the value may contain spaces)
  void parseParam() {
    const char* msg = "PARAM";
    if (tok_.size() < 5) fail(msg, "expected at least 5 tokens, found " + std::to_string(tok_.size()));
    number(tok_.back(), msg, " logger_timestamp");
    const std::string name(tok_[1]);
    std::string value;
    for (std::size_t i = 2; i + 2 < tok_.size(); ++i) {
      if (!value.empty()) value += ' ';
      value += tok_[i];
    }
    static const std::set<std::string_view> numeric = {
        "robot_frontlaser_offset",      "robot_rearlaser_offset",      "robot_frontlaser_side_offset",
        "robot_rearlaser_side_offset",  "robot_frontlaser_angular_offset", "robot_rearlaser_angular_offset",
        "laser_front_laser_resolution", "laser_rear_laser_resolution", "laser_front_laser_fov",
        "laser_rear_laser_fov",         "robot_front_laser_max",       "robot_rear_laser_max"};
    if (numeric.count(name)) {
      if (tok_.size() != 5) fail(std::string(msg) + " " + name, "expected one numeric value");
      const double v = number(tok_[2], msg, " " + name);
      if ((name.find("resolution") != std::string::npos || name.find("_fov") != std::string::npos ||
           name.find("laser_max") != std::string::npos) &&
          !(v > 0.0))
        fail(std::string(msg) + " " + name, "must be positive");
    }
    log_.params[name] = value;
  }

  double param(const std::string& name, double fallback) const {
    const auto it = log_.params.find(name);
    if (it == log_.params.end()) return fallback;
    return std::strtod(it->second.c_str(), nullptr);  // validated when parsed
  }

  void complete(ScanRecord& rec, const PendingGeometry& g) const {
    LaserScan& s = rec.scan;
    const std::string side = g.rear ? "rear" : "front";
    if (g.infer_angles) {
      // FLASER/RLASER carry no angles: n beams spread over the field of view (180° unless PARAM says), starting
      // at −fov/2. Even counts (180, 360) stop one step short of +fov/2, odd counts (181, 361) reach it.
      const std::size_t n = s.ranges.size();
      const double fov = param("laser_" + side + "_laser_fov", 180.0) * kDeg;
      const double res = param("laser_" + side + "_laser_resolution", 0.0) * kDeg;
      if (res > 0.0) {
        s.angle_increment = res;
      } else if (n <= 1) {
        s.angle_increment = fov;
      } else {
        s.angle_increment = (n % 2 == 0) ? fov / static_cast<double>(n) : fov / static_cast<double>(n - 1);
      }
      s.start_angle = -0.5 * fov;
    }
    if (g.infer_max_range) s.max_range = param("robot_" + side + "_laser_max", options_.default_max_range);
    if (g.pose_from_params) {
      // The line's laser pose equals the robot pose: either the laser is centred or the writer did not apply
      // the mounting offset; the PARAM offsets (CARMEN robot module convention) decide.
      const double off = param("robot_" + side + "laser_offset", 0.0);
      const double side_off = param("robot_" + side + "laser_side_offset", 0.0);
      const double ang = param("robot_" + side + "laser_angular_offset", 0.0);
      if (g.rear) {
        if (off != 0.0 || side_off != 0.0 || ang != 0.0 || g.infer_angles)
          s.sensor_pose = {-off, side_off, wrapAngle(kPi + ang)};
      } else {
        s.sensor_pose = {off, side_off, wrapAngle(ang)};
      }
    }
    s.valid.resize(s.ranges.size());
    const float maxr = static_cast<float>(s.max_range);
    for (std::size_t k = 0; k < s.ranges.size(); ++k) {
      const float r = s.ranges[k];
      s.valid[k] = (std::isfinite(r) && r > 0.0f && r < maxr) ? 1 : 0;
    }
  }

  void finish() {
    for (const auto& g : pending_) complete(log_.scans[g.index], g);
    bool has_front = false;
    for (const auto& g : pending_) has_front = has_front || !g.rear;
    if (!has_front && !raw_scans_.empty()) {
      // A log with only RAWLASER1 lines (no odometry at all): its scans, without odometry.
      for (const auto& g : raw_pending_) complete(raw_scans_[g.index], g);
      for (auto& r : raw_scans_) log_.scans.push_back(std::move(r));
    }
    // Max range must be usable: a line with max_range <= 0 and no PARAM gets the default above.
  }

  const std::string& name_;
  const CarmenReadOptions& options_;
  CarmenLog& log_;
  std::size_t lineno_ = 0;
  std::vector<std::string_view> tok_;
  std::vector<PendingGeometry> pending_, raw_pending_;
  std::vector<ScanRecord> raw_scans_;
};

CarmenLog parseText(std::string data, const std::string& name, const CarmenReadOptions& options) {
  if (hasGzipMagic(data)) data = gunzip(data, name);
  CarmenLog log;
  log.path = name;
  Parser parser(name, options, log);
  parser.parseAll(data);
  return log;
}

}  // namespace

CarmenLog parseCarmenLog(std::istream& in, const std::string& name, const CarmenReadOptions& options) {
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(name, "read error");
  return parseText(std::move(data), name, options);
}

CarmenLog readCarmenLog(const std::string& path, const CarmenReadOptions& options) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path, std::string("cannot open CARMEN log: ") + std::strerror(errno));
  std::string data;
  char buf[1 << 16];
  std::size_t got = 0;
  while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) data.append(buf, got);
  const bool err = std::ferror(f) != 0;
  std::fclose(f);
  if (err) throw InputError(path, "read error");
  return parseText(std::move(data), path, options);
}

}  // namespace gridtopo::io
