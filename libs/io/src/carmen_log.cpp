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
#include <tuple>
#include <string_view>

#include "gridtopo/core/error.h"
#include "gridtopo/io/trajectory_io.h"

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

/// CARMEN (and GMapping log) messages that carry nothing gridtopo uses: skipped and counted per type. The
/// names are those of the CARMEN logger's header (old and new releases: `NMEA-GGA` and `NMEAGGA`), of the
/// "(old)" messages it still lists (LASER3/4 and the REMISSION* lasers carry no pose), and of modules whose
/// logs circulate with the benchmark data sets. RAWLASER1, ROBOTLASER0 and the rear lasers are handled (and
/// counted when not used) by the parser itself.
const std::set<std::string_view>& ignoredMessages() {
  static const std::set<std::string_view> names = {
      "TRUEPOS",         "SYNC",          "COMMENT",         "NMEA-GGA",        "NMEA-RMC",     "NMEA-GSA",
      "NMEA-GSV",        "NMEA-VTG",      "NMEAGGA",         "NMEARMC",         "GPSNMEA",      "RAWLASER2",
      "RAWLASER3",       "RAWLASER4",     "ROBOTLASER3",     "ROBOTLASER4",     "LASER3",       "LASER4",
      "REMISSIONFLASER", "REMISSIONRLASER", "REMISSIONLASER3", "REMISSIONLASER4", "ROBOTVELOCITY", "VELOCITY",
      "VECTORMOVE",      "FOLLOWTRAJECTORY", "SONAR",          "BUMPER",          "SCANMARK",     "POSITIONLASER",
      "IMU",             "FUSED_ODOM",    "ARM",             "BASE",            "NEFF",         "LOCALIZEPOS",
      "GLOBALPOS",       "MARKER",        "LASER3D",         "KINECT",          "CAMERA",       "PANTILT",
      "BASEVELOCITY",    "PEARLASER"};
  return names;
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

void tokenize(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && isSpace(line[i])) ++i;
    if (i >= n) break;
    const std::size_t b = i;
    while (i < n && !isSpace(line[i])) ++i;
    out.push_back(line.substr(b, i - b));
  }
}

/// A finite number written as the whole token (CARMEN's %f / %g output, an optional '+').
bool parseFinite(std::string_view tok, double& v) {
  const char* b = tok.data();
  const char* e = tok.data() + tok.size();
  if (b != e && *b == '+') ++b;
  if (b == e) return false;
  const auto res = std::from_chars(b, e, v);
  return res.ec == std::errc() && res.ptr == e && std::isfinite(v);
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

/// Short human form of a number for warnings (full precision is in the data, not in the message).
std::string num(double v, int digits = 4) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string percent(std::size_t part, std::size_t whole) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", whole ? 100.0 * static_cast<double>(part) / whole : 0.0);
  return buf;
}

// ---------------------------------------------------------------------------------------------------------
// PARAM layouts

/// The two PARAM layouts: `PARAM name value host logger` (old logs such as Intel and ACES, GMapping) and
/// `PARAM name value ipc_timestamp host logger` (the CARMEN logger since 2004). Values may contain spaces, so
/// the layout cannot be read off one line: it is a property of the writer, decided once per file.
enum class ParamLayout { HostLogger, IpcHostLogger };

const char* layoutText(ParamLayout l) {
  return l == ParamLayout::IpcHostLogger ? "PARAM name value ipc_timestamp host logger_timestamp"
                                         : "PARAM name value host logger_timestamp";
}

struct ParamLayoutDecision {
  ParamLayout layout = ParamLayout::HostLogger;
  std::size_t lines = 0;
  std::vector<std::string> warnings;
};

bool startsWithWord(std::string_view line, std::string_view word) {
  std::size_t i = 0;
  while (i < line.size() && isSpace(line[i])) ++i;
  return line.size() >= i + word.size() && line.substr(i, word.size()) == word &&
         (line.size() == i + word.size() || isSpace(line[i + word.size()]));
}

/// Reads the third-last token (the ipc_timestamp of every CARMEN data line) of the lines that carry laser
/// scans or odometry: the time range a PARAM's ipc_timestamp would fall into.
bool dataIpcRange(std::string_view text, double& lo, double& hi) {
  static const std::set<std::string_view> data = {"FLASER", "RLASER", "ODOM", "ROBOTLASER1", "ROBOTLASER2",
                                                  "RAWLASER1"};
  std::vector<std::string_view> tok;
  bool any = false;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    tokenize(text.substr(pos, end - pos), tok);
    pos = end + 1;
    double t = 0;
    if (tok.size() < 4 || data.count(tok[0]) == 0 || !parseFinite(tok[tok.size() - 3], t)) continue;
    lo = any ? std::min(lo, t) : t;
    hi = any ? std::max(hi, t) : t;
    any = true;
  }
  return any;
}

/// Decides the PARAM layout of a file from all its PARAM lines:
///  - a line of 6+ tokens whose third-last token is not a number can only be `name value host logger`;
///  - a line of exactly 5 tokens has a value only in that layout too (weak evidence: an empty value);
///  - a third-last token that is a number within 1 s of the logger timestamp is the ipc_timestamp of the
///    CARMEN logger, which stamps a PARAM with both clocks at once.
/// Certain old lines win; otherwise the majority of 5-token lines against ipc-looking lines decides; a file
/// with only undecided lines (numeric third-last token far from the logger time) takes the new layout when
/// those numbers fall within a day of the data lines' ipc timestamps. Every line is then read in the file's
/// layout, and lines that fit the other layout better are reported.
ParamLayoutDecision decideParamLayout(std::string_view text) {
  ParamLayoutDecision d;
  std::size_t strong_old = 0, weak_old = 0, new_likely = 0;
  std::vector<std::size_t> new_lines, weak_lines;
  std::vector<double> undecided_ipc;
  std::vector<std::string_view> tok;
  std::size_t pos = 0, lineno = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++lineno;
    if (!startsWithWord(line, "PARAM")) continue;
    tokenize(line, tok);
    const std::size_t n = tok.size();
    double logger = 0, ipc = 0;
    if (n < 5 || !parseFinite(tok[n - 1], logger)) continue;  // malformed: the parser reports it
    ++d.lines;
    if (n == 5) {
      ++weak_old;
      weak_lines.push_back(lineno);
    } else if (!parseFinite(tok[n - 3], ipc)) {
      ++strong_old;
    } else if (std::abs(ipc - logger) <= 1.0) {
      ++new_likely;
      new_lines.push_back(lineno);
    } else {
      undecided_ipc.push_back(ipc);
    }
  }
  auto lineList = [](const std::vector<std::size_t>& v) {
    std::string s;
    for (std::size_t i = 0; i < v.size() && i < 5; ++i) s += (i ? ", " : "") + std::to_string(v[i]);
    if (v.size() > 5) s += ", ...";
    return s;
  };
  if (strong_old > 0 || (weak_old >= new_likely && (weak_old > 0 || new_likely > 0))) {
    d.layout = ParamLayout::HostLogger;
    if (new_likely > 0)
      d.warnings.push_back(std::to_string(new_likely) + " PARAM line(s) (line " + lineList(new_lines) +
                           ") also fit `" + layoutText(ParamLayout::IpcHostLogger) + "` but were read as `" +
                           layoutText(ParamLayout::HostLogger) + "` like the file's other PARAM lines: their " +
                           "value ends with the number before the host");
  } else if (new_likely > 0) {
    d.layout = ParamLayout::IpcHostLogger;
    if (weak_old > 0)
      d.warnings.push_back(std::to_string(weak_old) + " PARAM line(s) (line " + lineList(weak_lines) +
                           ") have 5 tokens, too few for `" + layoutText(ParamLayout::IpcHostLogger) +
                           "`: read as `" + layoutText(ParamLayout::HostLogger) + "`");
  } else if (!undecided_ipc.empty()) {
    double lo = 0, hi = 0;
    bool within = dataIpcRange(text, lo, hi);
    for (const double t : undecided_ipc) within = within && t >= lo - 86400.0 && t <= hi + 86400.0;
    d.layout = within ? ParamLayout::IpcHostLogger : ParamLayout::HostLogger;
    d.warnings.push_back(
        "PARAM layout undecided by the PARAM lines themselves (numeric token before the host, far from the "
        "logger timestamp): read as `" + std::string(layoutText(d.layout)) + "` because those numbers " +
        (within ? "lie" : "do not lie") + " within a day of the laser/ODOM ipc timestamps");
  }
  return d;
}

// ---------------------------------------------------------------------------------------------------------
// Timestamps

/// What is wrong, if anything, with one timestamp column (ipc or logger) of one stream (laser or ODOM lines)
/// in file order.
struct ColumnHealth {
  std::size_t n = 0, equal_pairs = 0, zeros = 0, backward = 0, wraps = 0;
  double largest_back = 0, largest_wrap = 0, first = 0, last = 0;
  bool constant = false, coarse = false;
  bool degenerate() const { return constant || coarse || wraps > 0; }
  std::string describe() const {
    std::string s;
    if (constant) s = "all " + std::to_string(n) + " equal to " + formatDouble(first);
    if (coarse)
      s = std::to_string(equal_pairs) + " of " + std::to_string(n - 1) +
          " consecutive lines share their value (printed with too few digits?)";
    if (wraps) {
      if (!s.empty()) s += "; ";
      s += std::to_string(wraps) + " jump(s) back by up to " + num(largest_wrap, 6) +
           " s after which the values continue from the lower value (wrapped or negative)";
    }
    if (zeros && !constant) s += "; " + std::to_string(zeros) + " zero values";
    return s;
  }
};

double medianPositiveStep(const std::vector<double>& t) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < t.size(); ++i)
    if (t[i] > t[i - 1]) steps.push_back(t[i] - t[i - 1]);
  if (steps.empty()) return 0.0;
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

/// A step back larger than this is not jitter between processes (Intel's laser timestamps step back by up
/// to 0.9 s, 631 times: kept) but a clock that wrapped or restarted.
double wrapThreshold(const std::vector<double>& t) { return std::max(10.0, 100.0 * medianPositiveStep(t)); }

bool isWrap(const std::vector<double>& t, std::size_t i, double threshold) {
  // The values after the jump stay low: a single stray value is not a wrap.
  return t[i] < t[i - 1] - threshold && (i + 1 == t.size() || t[i + 1] < t[i - 1] - threshold);
}

ColumnHealth diagnose(const std::vector<double>& t) {
  ColumnHealth h;
  h.n = t.size();
  if (h.n < 3) return h;  // too short to judge anything
  h.first = t.front();
  h.last = t.back();
  const double wrap = wrapThreshold(t);
  for (std::size_t i = 0; i < h.n; ++i) {
    h.zeros += t[i] == 0.0;
    if (i == 0) continue;
    const double d = t[i] - t[i - 1];
    h.equal_pairs += d == 0.0;
    if (d < 0) {
      ++h.backward;
      h.largest_back = std::max(h.largest_back, -d);
      if (isWrap(t, i, wrap)) {
        ++h.wraps;
        h.largest_wrap = std::max(h.largest_wrap, -d);
      }
    }
  }
  h.constant = h.equal_pairs == h.n - 1;
  // Healthy logs (Intel, ACES, MIT, Freiburg: 0 or 1 repeats in thousands of lines) never come close.
  h.coarse = !h.constant && h.n >= 10 && h.equal_pairs * 10 >= h.n - 1;
  return h;
}

/// Makes one column usable in place: wraps are undone (each later value shifted by the jump plus the typical
/// step), then runs of equal values are spread by line order between their value and the next distinct one
/// (the last run continues at the column's mean rate). A constant column stays constant: there is no time in it.
/// Returns false if the column had to stay as read.
bool repairColumn(std::vector<double>& t) {
  const std::size_t n = t.size();
  if (n < 2) return false;
  const std::vector<double> raw = t;
  const double step = medianPositiveStep(raw);
  const double wrap = wrapThreshold(raw);
  double offset = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (isWrap(raw, i, wrap)) offset += raw[i - 1] - raw[i] + step;
    t[i] = raw[i] + offset;
  }
  std::size_t last_run = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (t[i] != t[i - 1]) last_run = i;
  const double rate = last_run > 0 ? (t[last_run] - t[0]) / static_cast<double>(last_run) : 0.0;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j + 1 < n && t[j + 1] == t[i]) ++j;
    if (j > i) {
      double d = rate;
      if (j + 1 < n && t[j + 1] > t[i]) d = (t[j + 1] - t[i]) / static_cast<double>(j + 1 - i);
      if (d > 0)
        for (std::size_t k = i + 1; k <= j; ++k) t[k] = t[i] + d * static_cast<double>(k - i);
    }
    i = j + 1;
  }
  // Absurd values (±1e308 in a damaged file) can overflow the shifts: then the column stays as read.
  if (!std::all_of(t.begin(), t.end(), [](double v) { return std::isfinite(v); })) {
    t = raw;
    return false;
  }
  return t != raw;
}

// ---------------------------------------------------------------------------------------------------------
// The parser

/// A laser line read but not yet complete: what the line does not carry (FLASER angles, max range, the
/// mounting offset) is decided from the PARAMs and from the whole log once every line is read.
struct PendingScan {
  ScanRecord rec;
  const char* type = "";          // message name, for warnings
  bool rear = false;              // RLASER / ROBOTLASER2
  bool infer_angles = false;      // FLASER/RLASER: aperture from beam count and PARAMs
  bool infer_max_range = false;   // max range from PARAMs or the default
  bool pose_from_params = false;  // laser pose equals robot pose in the line: PARAM offsets decide
  std::string max_source;         // where the max range came from (for warnings)
};

/// Field of view and increment (radians) of the FLASER/RLASER lines of one laser, decided once from the PARAMs.
struct OldLaserGeometry {
  double fov = kPi;           // 180°, CARMEN's default
  double res = 0.0;           // 0: from the field of view and each line's beam count
  bool fov_from_res = false;  // no fov PARAM: the scan spans its beams at the given resolution, centred
};

class Parser {
 public:
  Parser(const std::string& name, const CarmenReadOptions& options, CarmenLog& log)
      : name_(name), options_(options), log_(log) {}

  void parseAll(std::string_view text) {
    const ParamLayoutDecision layout = decideParamLayout(text);
    param_layout_ = layout.layout;
    for (const auto& w : layout.warnings) log_.warnings.push_back(w);
    if (layout.lines)
      log_.notes.push_back(std::to_string(layout.lines) + " PARAM lines read as `" + layoutText(layout.layout) + "`");
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

  /// `NAME ... ipc_timestamp host logger_timestamp` with an upper-case name: a CARMEN message of a module
  /// gridtopo does not know (skipped and counted), as opposed to garbage (an error).
  bool looksLikeCarmenMessage() const {
    const std::string_view type = tok_[0];
    if (!(type[0] >= 'A' && type[0] <= 'Z')) return false;
    for (const char c : type)
      if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-')) return false;
    const std::size_t n = tok_.size();
    double v = 0;
    return n >= 4 && parseFinite(tok_[n - 3], v) && !parseFinite(tok_[n - 2], v) && parseFinite(tok_[n - 1], v);
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
    } else if (type == "ROBOTLASER1" || type == "ROBOTLASER2" || type == "ROBOTLASER0") {
      parseRobotLaser(type);
    } else if (type == "RAWLASER1") {
      parseRawLaser();
    } else if (type == "PARAM") {
      parseParam();
    } else if (ignoredMessages().count(type)) {
      ++log_.skipped_messages[std::string(type)];
    } else if (looksLikeCarmenMessage()) {
      ++log_.skipped_messages[std::string(type)];
      unknown_.emplace(std::string(type), lineno_);  // keeps the first line
    } else {
      fail("message", "unknown message type '" + excerpt(type) + "'");
    }
  }

  // FLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname logger_timestamp
  // and, from writers that had no pose to log, FLASER n r1..rn ipc_timestamp ipc_hostname logger_timestamp
  void parseOldLaser(bool rear) {
    const char* msg = rear ? "RLASER" : "FLASER";
    if (tok_.size() < 2) fail(msg, "missing num_readings");
    const std::size_t n = count(tok_[1], msg, " num_readings");
    if (n == 0) fail(std::string(msg) + " num_readings", "a scan needs at least one reading");
    const bool posed = tok_.size() != n + 5;
    if (posed)
      expectTokens(msg, n + 11,
                   " for " + std::to_string(n) + " readings (" + std::to_string(n + 5) + " without poses)");
    PendingScan p;
    p.type = msg;
    p.rear = rear;
    p.infer_angles = true;
    p.infer_max_range = true;
    ScanRecord& rec = p.rec;
    readRanges(2, n, msg, rec.scan);
    if (posed) {
      const auto laser = pose(2 + n, msg, " x", " y", " theta");
      rec.odometry = pose(5 + n, msg, " odom_x", " odom_y", " odom_theta");
      rec.has_odometry = true;
      rec.scan.sensor_pose = relativePose(rec.odometry, laser);
      p.pose_from_params = std::abs(rec.scan.sensor_pose.x) < 1e-12 && std::abs(rec.scan.sensor_pose.y) < 1e-12 &&
                           std::abs(rec.scan.sensor_pose.phi) < 1e-12;
    } else {
      p.pose_from_params = true;
    }
    timestamps(msg, rec.scan.timestamp, rec.scan.logger_timestamp);
    rec.source_index = lineno_;
    if (rear && !options_.read_rear_laser) {
      ++log_.skipped_messages[msg];
      return;
    }
    if (!posed) ++poseless_;
    lasers_.push_back(std::move(p));
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
  // ROBOTLASER2 is the rear laser; ROBOTLASER0 (named in some CARMEN headers, never defined) is used only by a
  // log without any other front laser.
  void parseRobotLaser(std::string_view type) {
    const bool rear = type == "ROBOTLASER2";
    const bool zero = type == "ROBOTLASER0";
    const char* msg = rear ? "ROBOTLASER2" : (zero ? "ROBOTLASER0" : "ROBOTLASER1");
    PendingScan p;
    p.type = msg;
    p.rear = rear;
    ScanRecord& rec = p.rec;
    LaserScan& s = rec.scan;
    const std::size_t k = parseLaserConfigAndReadings(msg, 14, s);
    const auto laser = pose(k, msg, " laser_x", " laser_y", " laser_theta");
    rec.odometry = pose(k + 3, msg, " robot_x", " robot_y", " robot_theta");
    rec.has_odometry = true;
    number(tok_[k + 6], msg, " tv");
    number(tok_[k + 7], msg, " rv");
    timestamps(msg, s.timestamp, s.logger_timestamp);
    s.sensor_pose = relativePose(rec.odometry, laser);
    rec.source_index = lineno_;
    p.pose_from_params = std::abs(s.sensor_pose.x) < 1e-12 && std::abs(s.sensor_pose.y) < 1e-12 &&
                         std::abs(s.sensor_pose.phi) < 1e-12;
    if (rear && !options_.read_rear_laser) {
      ++log_.skipped_messages[msg];
      return;
    }
    p.infer_max_range = !(s.max_range > 0.0);
    (zero ? robot0_ : lasers_).push_back(std::move(p));
  }

  // RAWLASER1 <laser config and readings> ipc_timestamp ipc_hostname logger_timestamp
  //   (no pose: used only if the log has no posed scans)
  void parseRawLaser() {
    const char* msg = "RAWLASER1";
    PendingScan p;
    p.type = msg;
    p.pose_from_params = true;
    LaserScan& s = p.rec.scan;
    parseLaserConfigAndReadings(msg, 3, s);
    timestamps(msg, s.timestamp, s.logger_timestamp);
    p.rec.has_odometry = false;
    p.rec.source_index = lineno_;
    p.infer_max_range = !(s.max_range > 0.0);
    raw_.push_back(std::move(p));
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

  // PARAM name value [ipc_timestamp] ipc_hostname logger_timestamp: the value may contain spaces; whether the
  // ipc_timestamp is there is decided once for the file (decideParamLayout).
  void parseParam() {
    const char* msg = "PARAM";
    if (tok_.size() < 5) fail(msg, "expected at least 5 tokens, found " + std::to_string(tok_.size()));
    number(tok_.back(), msg, " logger_timestamp");
    const bool with_ipc = param_layout_ == ParamLayout::IpcHostLogger && tok_.size() >= 6;
    if (with_ipc) number(tok_[tok_.size() - 3], msg, " ipc_timestamp");
    const std::size_t value_end = tok_.size() - (with_ipc ? 3 : 2);
    const std::string name(tok_[1]);
    std::string value;
    for (std::size_t i = 2; i < value_end; ++i) {
      if (!value.empty()) value += ' ';
      value += tok_[i];
    }
    static const std::set<std::string_view> numeric = {
        "robot_frontlaser_offset",      "robot_rearlaser_offset",      "robot_frontlaser_side_offset",
        "robot_rearlaser_side_offset",  "robot_frontlaser_angular_offset", "robot_rearlaser_angular_offset",
        "laser_front_laser_resolution", "laser_rear_laser_resolution", "laser_front_laser_fov",
        "laser_rear_laser_fov",         "robot_front_laser_max",       "robot_rear_laser_max"};
    if (numeric.count(name)) {
      if (value_end != 3)
        fail(std::string(msg) + " " + name, "expected one numeric value, found '" + excerpt(value) + "' (read as `" +
                                                layoutText(param_layout_) + "`)");
      const double v = number(tok_[2], msg, " " + name);
      if ((name.find("resolution") != std::string::npos || name.find("_fov") != std::string::npos ||
           name.find("laser_max") != std::string::npos) &&
          !(v > 0.0))
        fail(std::string(msg) + " " + name, "must be positive");
      if (name.find("_fov") != std::string::npos && v > 360.0 + 1e-9)
        fail(std::string(msg) + " " + name, "more than 360 degrees");
    }
    log_.params[name] = value;
  }

  double param(const std::string& name, double fallback) const {
    const auto it = log_.params.find(name);
    if (it == log_.params.end()) return fallback;
    return std::strtod(it->second.c_str(), nullptr);  // validated when parsed
  }

  /// Units of the fov / resolution PARAMs of one laser's FLASER/RLASER lines. CARMEN documents degrees, but
  /// logs exist with radians (`laser_front_laser_fov 3.14159`). A field of view of at most 2π is radians (no
  /// planar CARMEN laser sees 6° or less). The resolution takes the unit that makes the beam count agree with
  /// the field of view (180° without a fov PARAM): n beams × resolution ≈ fov, degrees on a tie. `beams` is
  /// the most common beam count of those lines.
  OldLaserGeometry decideGeometry(bool rear, std::size_t beams) {
    const std::string side = rear ? "rear" : "front";
    const std::string fov_name = "laser_" + side + "_laser_fov", res_name = "laser_" + side + "_laser_resolution";
    const bool has_fov = log_.params.count(fov_name) > 0, has_res = log_.params.count(res_name) > 0;
    OldLaserGeometry g;
    if (!has_fov && !has_res) return g;
    constexpr double kTurn = 2.0 * kPi + 1e-6;
    const double f = param(fov_name, 0.0), r = param(res_name, 0.0);
    const bool fov_rad = has_fov && f <= kTurn;
    g.fov = has_fov ? (fov_rad ? f : f * kDeg) : kPi;
    if (fov_rad)
      log_.warnings.push_back("PARAM " + fov_name + " " + log_.params.at(fov_name) + " read as radians (" +
                              num(g.fov / kDeg) + " deg): a field of view of at most 2π makes no sense in degrees");
    if (!has_res) return g;
    const double n = static_cast<double>(beams);
    bool found = false, res_rad = false;
    double best = 0.0;
    for (const bool rad : {false, true}) {
      const double R = rad ? r : r * kDeg;
      if (beams > 1 && R * (n - 1.0) > kTurn) continue;  // more than a full turn
      const double err = beams > 1 ? std::min(std::abs(R * n - g.fov), std::abs(R * (n - 1.0) - g.fov)) / g.fov : 0.0;
      if (!found || err < best - 1e-9) {
        found = true;
        best = err;
        res_rad = rad;
      }
    }
    if (!found)
      log_.warnings.push_back("PARAM " + res_name + " " + log_.params.at(res_name) + " spans more than a full " +
                              "turn over " + std::to_string(beams) + " beams in degrees and in radians: read as " +
                              "degrees");
    g.res = res_rad ? r : r * kDeg;
    g.fov_from_res = !has_fov;
    if (res_rad)
      log_.warnings.push_back("PARAM " + res_name + " " + log_.params.at(res_name) + " read as radians (" +
                              num(g.res / kDeg) + " deg): " + std::to_string(beams) + " beams then span " +
                              (has_fov ? "the field of view" : "180 deg"));
    if (found && has_fov && best > 0.02)
      log_.warnings.push_back("PARAM " + fov_name + " (" + num(g.fov / kDeg) + " deg) and " + res_name + " (" +
                              num(g.res / kDeg) + " deg) disagree with the " + std::to_string(beams) +
                              "-beam scans (they span " + num(g.res * (n - 1.0) / kDeg) + " deg): beams are " +
                              "the resolution apart from -fov/2");
    return g;
  }

  void complete(PendingScan& p) {
    LaserScan& s = p.rec.scan;
    const std::string side = p.rear ? "rear" : "front";
    if (p.infer_angles) {
      // FLASER/RLASER carry no angles: n beams spread over the field of view, starting at −fov/2. Even counts
      // (180, 360) stop one step short of +fov/2, odd counts (181, 361) reach it.
      const std::size_t n = s.ranges.size();
      const OldLaserGeometry& g = geometry_[p.rear ? 1 : 0];
      double fov = g.fov;
      if (g.res > 0.0) {
        s.angle_increment = g.res;
        if (g.fov_from_res) fov = n > 1 ? g.res * static_cast<double>(n % 2 == 0 ? n : n - 1) : g.res;
      } else if (n <= 1) {
        s.angle_increment = fov;
      } else {
        s.angle_increment = (n % 2 == 0) ? fov / static_cast<double>(n) : fov / static_cast<double>(n - 1);
      }
      s.start_angle = -0.5 * fov;
    }
    if (p.infer_max_range) {
      const std::string name = "robot_" + side + "_laser_max";
      if (log_.params.count(name)) {
        s.max_range = param(name, 0.0);
        p.max_source = "PARAM " + name;
      } else {
        s.max_range = options_.default_max_range;
        p.max_source = "the default max range (no PARAM " + name + ")";
      }
    } else {
      p.max_source = std::string("the max_range field of the ") + p.type + " lines";
    }
    if (p.pose_from_params) {
      // The line's laser pose equals the robot pose (or it has none): either the laser is centred or the writer
      // did not apply the mounting offset; the PARAM offsets (CARMEN robot module convention) decide.
      const double off = param("robot_" + side + "laser_offset", 0.0);
      const double side_off = param("robot_" + side + "laser_side_offset", 0.0);
      const double ang = param("robot_" + side + "laser_angular_offset", 0.0);
      if (p.rear) {
        if (off != 0.0 || side_off != 0.0 || ang != 0.0 || p.infer_angles)
          s.sensor_pose = {-off, side_off, wrapAngle(kPi + ang)};
      } else {
        s.sensor_pose = {off, side_off, wrapAngle(ang)};
      }
    }
  }

  /// A declared max range (PARAM, default or the line's field) below which a meaningful share of the readings
  /// lie is wrong: every one of them would become a "no return". Readings beyond the declared max are counted;
  /// their largest value is the sensor's no-return code (81.83, 81.91, 50.00 in the benchmark logs) when it is
  /// also the most frequent of them. If the readings strictly between the declared max and that code reach
  /// 1 % of all positive readings (and at least 10), the max range becomes the code (or, without a code, just
  /// above the largest reading). Fewer stray readings keep the declaration (they stay no-returns). Then a
  /// no-return code just below the max range (noReturnCodeBelow) lowers the max range to it.
  void checkMaxRanges(std::vector<PendingScan>& scans) {
    std::map<std::tuple<bool, double, std::string>, std::vector<std::size_t>> groups;
    for (std::size_t i = 0; i < scans.size(); ++i)
      groups[{scans[i].rear, scans[i].rec.scan.max_range, scans[i].max_source}].push_back(i);
    for (const auto& [key, members] : groups) {
      const double declared = std::get<1>(key);
      const std::string what = std::get<2>(key) + " = " + num(declared, 6) + " m";
      const auto m = static_cast<float>(declared);
      std::size_t positive = 0, above = 0;
      std::map<float, std::size_t> beyond;  // reading beyond the declared max -> how often
      for (const std::size_t i : members)
        for (const float r : scans[i].rec.scan.ranges) {
          if (!std::isfinite(r) || !(r > 0.0f)) continue;
          ++positive;
          if (r > m) {
            ++beyond[r];
            ++above;
          }
        }
      double max_range = declared;
      // Set when the declaration was raised to just above the largest reading: those readings were judged to
      // hold no code, so none is looked for below the new max either.
      bool raised_without_code = false;
      if (!beyond.empty()) {
        const auto top = std::prev(beyond.end());
        std::size_t most_other = 0;
        for (auto it = beyond.begin(); it != top; ++it) most_other = std::max(most_other, it->second);
        const bool code = top->second >= 3 && top->second >= most_other;
        const std::size_t between = above - (code ? top->second : 0);
        const bool contradicted = between >= std::max<std::size_t>(10, (positive + 99) / 100);
        if (between > 0 && !contradicted) {
          log_.notes.push_back(std::to_string(between) + " readings lie beyond " + what + " (" +
                               percent(between, positive) + "): kept as no-returns");
        } else if (contradicted) {
          double largest_real = 0;
          for (auto it = beyond.begin(); it != beyond.end(); ++it)
            if (!(code && it == top)) largest_real = it->first;
          max_range = code ? static_cast<double>(top->first)
                           : static_cast<double>(std::nextafter(top->first, std::numeric_limits<float>::infinity()));
          raised_without_code = !code;
          log_.warnings.push_back(
              what + " is contradicted by the readings: " + std::to_string(between) + " of " +
              std::to_string(positive) + " (" + percent(between, positive) + ") lie between it and " +
              num(largest_real, 6) + " m; max range set to " +
              (code ? num(max_range, 6) + " m, the no-return code (" + std::to_string(top->second) + " readings)"
                    : "just above the largest reading (no no-return code found)"));
        }
      }
      if (!raised_without_code) noReturnCodeBelow(scans, members, positive, what, max_range);
      for (const std::size_t i : members) scans[i].rec.scan.max_range = max_range;
    }
  }

  /// A sensor's no-return code is a no-return wherever the declaration sits: the ROBOTLASER1 lines of MIT CSAIL
  /// declare 81.92 m and write 81.91 for no return, the hospital's declare 81.9 m and write 81.83 (as well as
  /// 81.91 above the declaration). The code is told from the readings: the most frequent value in the top
  /// kCodeBand of the range [max_range · (1 − kCodeBand), max_range) is the code when it is a spike, at least
  /// kCodeSpike times as frequent as all the other readings within kCodeNeighbourhood · value of it together,
  /// and holds at least kCodeShare of the positive readings (and kCodeMin). Hits of real surfaces spread over
  /// neighbouring values: ACES's most frequent value in its band (45.76 m) has 100 readings against 261 around
  /// it, and the top readings of Intel, FR079 and the FLASER CSAIL log, which lie far below their max range,
  /// stay under 0.2 times their neighbours; the codes are 27 (81.83 m in the hospital) and 23 711 (81.91 m in
  /// CSAIL, nothing around it) times theirs. Then max_range becomes the code (the float reading itself, so a
  /// float round trip of the max range, as MRPT's observation does, keeps it equal to the readings), and the
  /// readings at or above it are no-returns.
  void noReturnCodeBelow(const std::vector<PendingScan>& scans, const std::vector<std::size_t>& members,
                         std::size_t positive, const std::string& what, double& max_range) {
    constexpr double kCodeBand = 0.1, kCodeNeighbourhood = 0.01, kCodeSpike = 10.0, kCodeShare = 0.001;
    constexpr std::size_t kCodeMin = 20;
    const auto top = static_cast<float>(max_range);
    const auto low = static_cast<float>(max_range * (1.0 - kCodeBand - kCodeNeighbourhood));
    const auto band = static_cast<float>(max_range * (1.0 - kCodeBand));
    std::map<float, std::size_t> near;  // reading in [low, top) -> how often
    for (const std::size_t i : members)
      for (const float r : scans[i].rec.scan.ranges)
        if (r >= low && r < top) ++near[r];
    auto code = near.end();
    for (auto it = near.lower_bound(band); it != near.end(); ++it)
      if (code == near.end() || it->second > code->second) code = it;
    if (code == near.end()) return;
    const double value = code->first;
    const double w = kCodeNeighbourhood * value;
    std::size_t neighbours = 0, between = 0;
    for (const auto& [r, count] : near) {
      if (r != code->first && std::abs(r - value) <= w) neighbours += count;
      if (r > code->first) between += count;
    }
    const auto count = static_cast<double>(code->second);
    if (code->second < kCodeMin || count < kCodeShare * static_cast<double>(positive) ||
        count < kCodeSpike * static_cast<double>(neighbours))
      return;
    log_.notes.push_back(
        std::to_string(code->second) + " readings of " + num(value, 6) + " m (" + percent(code->second, positive) +
        ") lie below " + what + ": the no-return code (the most frequent value in the top " +
        num(100 * kCodeBand) + " % of the range, " + std::to_string(code->second) + " against " +
        std::to_string(neighbours) + " readings within " + num(w, 2) + " m of it); max range set to " +
        num(value, 6) + " m, readings at or above it are no-returns" +
        (between ? " (so are the " + std::to_string(between) + " readings between it and " + num(max_range, 6) + " m)"
                 : ""));
    max_range = value;
  }

  /// Degenerate timestamps are repaired so SLAM (temporal updates) and ODOM interpolation keep working; the
  /// evaluation matches relations by the laser ipc timestamps, so healthy ones are never touched.
  void checkTimestamps() {
    auto& scans = log_.scans;
    auto& odo = log_.odometry;
    std::vector<double> li, ll, oi, ol;
    for (const auto& r : scans) {
      li.push_back(r.scan.timestamp);
      ll.push_back(r.scan.logger_timestamp);
    }
    for (const auto& o : odo) {
      oi.push_back(o.timestamp);
      ol.push_back(o.logger_timestamp);
    }
    const ColumnHealth hli = diagnose(li), hll = diagnose(ll), hoi = diagnose(oi), hol = diagnose(ol);
    if (!hli.degenerate()) {
      // Reported only: ODOM lines are not what relations are matched by, and replacing their clock would
      // desynchronise them from the (healthy) laser lines. GMapping's corrected logs have such ODOM lines.
      if (hoi.degenerate())
        log_.warnings.push_back(std::string("ODOM ipc ") + (hol.degenerate() ? "and logger " : "") +
                                "timestamps look degenerate (" + hoi.describe() +
                                "): kept as read because the laser ipc timestamps are healthy");
      if (hll.degenerate())
        log_.warnings.push_back("laser logger timestamps look degenerate (" + hll.describe() +
                                "): kept as read (the ipc timestamps are the ones used)");
      if (hol.degenerate() && !hoi.degenerate())
        log_.warnings.push_back("ODOM logger timestamps look degenerate (" + hol.describe() +
                                "): kept as read (the ipc timestamps are the ones used)");
      return;
    }
    if (!hll.degenerate() && !hol.degenerate()) {
      for (auto& r : scans) r.scan.timestamp = r.scan.logger_timestamp;
      for (auto& o : odo) o.timestamp = o.logger_timestamp;
      log_.warnings.push_back("laser ipc timestamps are unusable (" + hli.describe() + "): every scan and ODOM " +
                              "timestamp is its logger timestamp instead (" + formatDouble(hll.first) + " .. " +
                              formatDouble(hll.last) + " s)");
      return;
    }
    const bool repaired = repairColumn(li);
    for (std::size_t i = 0; i < scans.size(); ++i) scans[i].scan.timestamp = li[i];
    if (hoi.degenerate()) {
      repairColumn(oi);
      for (std::size_t i = 0; i < odo.size(); ++i) odo[i].timestamp = oi[i];
    }
    const bool still_constant = !repaired || diagnose(li).constant;
    log_.warnings.push_back(
        "laser ipc timestamps are unusable (" + hli.describe() + ") and so are the logger timestamps (" +
        (hll.degenerate() ? hll : hol).describe() + "): " +
        (still_constant ? std::string("left as read, the log holds no usable time (SLAM temporal updates and "
                                      "ODOM interpolation cannot work)")
                        : "repaired in place: wraps undone, repeated values spread by line order between "
                          "the distinct ones (" + formatDouble(li.front()) + " .. " + formatDouble(li.back()) +
                              " s)"));
  }

  void finish() {
    // Which lines give the scans: FLASER / ROBOTLASER1 (and the rear lasers if asked); ROBOTLASER0 and
    // RAWLASER1 only when the log has no other front laser (beside them they are duplicates).
    std::vector<PendingScan> scans = std::move(lasers_);
    bool has_front = std::any_of(scans.begin(), scans.end(), [](const PendingScan& p) { return !p.rear; });
    bool merged = false;
    if (!robot0_.empty()) {
      if (has_front) {
        log_.skipped_messages["ROBOTLASER0"] += robot0_.size();
      } else {
        log_.notes.push_back("ROBOTLASER0 lines read as the front laser (the log has no FLASER or ROBOTLASER1)");
        for (auto& p : robot0_) scans.push_back(std::move(p));
        has_front = merged = true;
      }
    }
    if (!raw_.empty()) {
      if (has_front) {
        log_.skipped_messages["RAWLASER1"] += raw_.size();
      } else {
        log_.notes.push_back("RAWLASER1 lines only: scans without odometry");
        for (auto& p : raw_) scans.push_back(std::move(p));
        merged = true;
      }
    }
    if (merged)
      std::stable_sort(scans.begin(), scans.end(), [](const PendingScan& a, const PendingScan& b) {
        return a.rec.source_index < b.rec.source_index;
      });
    if (poseless_)
      log_.notes.push_back(std::to_string(poseless_) + " FLASER/RLASER lines without poses: scans without odometry");

    // Units of the FLASER/RLASER geometry PARAMs, from each laser's most common beam count.
    for (const bool rear : {false, true}) {
      std::map<std::size_t, std::size_t> beams;
      for (const auto& p : scans)
        if (p.infer_angles && p.rear == rear) ++beams[p.rec.scan.ranges.size()];
      if (beams.empty()) continue;
      const auto modal = std::max_element(beams.begin(), beams.end(),
                                          [](const auto& a, const auto& b) { return a.second < b.second; });
      geometry_[rear ? 1 : 0] = decideGeometry(rear, modal->first);
    }
    for (auto& p : scans) complete(p);
    checkMaxRanges(scans);
    log_.scans.reserve(scans.size());
    for (auto& p : scans) {
      LaserScan& s = p.rec.scan;
      s.valid.resize(s.ranges.size());
      const auto maxr = static_cast<float>(s.max_range);
      for (std::size_t k = 0; k < s.ranges.size(); ++k) {
        const float r = s.ranges[k];
        s.valid[k] = (std::isfinite(r) && r > 0.0f && r < maxr) ? 1 : 0;
      }
      log_.scans.push_back(std::move(p.rec));
    }
    checkTimestamps();

    for (const auto& [type, line] : unknown_)
      log_.warnings.push_back("unknown message type '" + excerpt(type) + "' (" +
                              std::to_string(log_.skipped_messages[type]) + " lines from line " +
                              std::to_string(line) + ") skipped: it has the form of a CARMEN message (`" +
                              excerpt(type) + " ... ipc_timestamp host logger_timestamp`)");
    if (log_.odometry.empty() &&
        std::any_of(log_.scans.begin(), log_.scans.end(), [](const ScanRecord& r) { return r.has_odometry; }))
      log_.notes.push_back("no ODOM lines: odometry is the robot pose inside the laser lines");
  }

  const std::string& name_;
  const CarmenReadOptions& options_;
  CarmenLog& log_;
  std::size_t lineno_ = 0;
  std::vector<std::string_view> tok_;
  ParamLayout param_layout_ = ParamLayout::HostLogger;
  std::vector<PendingScan> lasers_, robot0_, raw_;
  OldLaserGeometry geometry_[2];           // front, rear
  std::size_t poseless_ = 0;               // FLASER/RLASER lines without poses
  std::map<std::string, std::size_t> unknown_;  // unknown but well-formed message type -> first line
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
