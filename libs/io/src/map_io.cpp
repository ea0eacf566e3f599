#include "gridtopo/io/map_io.h"

#include <mrpt/containers/yaml.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/serialization/CArchive.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "gridtopo/core/error.h"
#include "isolated_parse.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/io/image_write.h"
#include "gridtopo/io/trajectory_io.h"

namespace fs = std::filesystem;
using mrpt::maps::COccupancyGridMap2D;

namespace gridtopo::io {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// Shortest text that reads back to the same float (origins and resolutions are floats in MRPT grids).
std::string formatFloat(float v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, res.ptr);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

// Whether `path` is a regular file, never throwing: std::filesystem's throwing overload fails on a name longer
// than the system allows ("File name too long", found by map_fuzzer). `why` gets the system's reason when the
// path cannot be looked at at all.
bool isRegularFile(const std::string& path, std::string* why = nullptr) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return S_ISREG(st.st_mode);
  if (why && errno != ENOENT && errno != ENOTDIR) *why = std::strerror(errno);
  return false;
}

// MRPT's COccupancyGridMap2D::setSize() rounds the grid's limits to whole multiples of the resolution. Maps
// whose origin is not such a multiple (ROS maps often sit half a cell off) get their exact limits back through
// this accessor of the protected members.
struct GridLimits : COccupancyGridMap2D {
  static void set(COccupancyGridMap2D& g, float x_min, float y_min) {
    const float res = g.getResolution();
    g.*(&GridLimits::m_xMin) = x_min;
    g.*(&GridLimits::m_yMin) = y_min;
    g.*(&GridLimits::m_xMax) = x_min + static_cast<float>(g.getSizeX()) * res;
    g.*(&GridLimits::m_yMax) = y_min + static_cast<float>(g.getSizeY()) * res;
  }
};

/// A grid of `width` x `height` cells of `resolution` m whose lower-left corner is (x_min, y_min), exactly.
/// InputError(path, field, ...) when MRPT's float limits cannot hold it: a resolution that is not a normal positive
/// float (3.3e126 m became inf and gave a grid of no cells, into which the image was written: a null-pointer store
/// found by map_fuzzer), or limits that overflow.
COccupancyGridMap2D::Ptr makeGrid(const std::string& path, int width, int height, double resolution, double x_min,
                                  double y_min) {
  const float res = static_cast<float>(resolution), x0 = static_cast<float>(x_min), y0 = static_cast<float>(y_min);
  const auto describe = [&] {
    return std::to_string(width) + " x " + std::to_string(height) + " cells of " + formatDouble(resolution) +
           " m at (" + formatDouble(x_min) + ", " + formatDouble(y_min) + ")";
  };
  if (!(res >= std::numeric_limits<float>::min()) || !std::isfinite(static_cast<float>(width) * res) ||
      !std::isfinite(static_cast<float>(height) * res))
    throw InputError(path, 0, "resolution", describe() + ": the resolution is out of the range a grid can hold");
  if (!std::isfinite(x0 + static_cast<float>(width) * res) || !std::isfinite(y0 + static_cast<float>(height) * res))
    throw InputError(path, 0, "origin", describe() + ": the map's limits are out of the range a grid can hold");
  // The cell count from limits that start at 0 (from the origin's, rounding could change it), then the exact origin.
  auto g = COccupancyGridMap2D::Create();
  g->setSize(0.0f, static_cast<float>(width) * res, 0.0f, static_cast<float>(height) * res, res, 0.5f);
  if (g->getSizeX() != static_cast<unsigned>(width) || g->getSizeY() != static_cast<unsigned>(height))
    throw InputError(path, 0, "resolution", describe() + ": a grid of " + std::to_string(g->getSizeX()) + " x " +
                                                std::to_string(g->getSizeY()) + " cells came out");
  GridLimits::set(*g, x0, y0);
  return g;
}

/// Fills the grid from a grey image (row 0 = top = largest y) through a per-grey-level table of raw cells.
void fillFromImage(COccupancyGridMap2D& g, const cv::Mat& img,
                   const std::array<COccupancyGridMap2D::cellType, 256>& lut) {
  const int h = img.rows, w = img.cols;
  for (int r = 0; r < h; ++r) {
    const uint8_t* row = img.ptr<uint8_t>(r);
    COccupancyGridMap2D::cellType* cells = g.getRow(h - 1 - r);
    for (int c = 0; c < w; ++c) cells[c] = lut[row[c]];
  }
}

// The first line of a library's message that says what went wrong: without MRPT's banner, source location and
// call stack, or OpenCV's "OpenCV(4.x) file:line: error: (-215:...) ... in function ..." frame.
std::string shortReason(const std::string& what) {
  if (what.find("Message:") != std::string::npos) return innermostMrptMessage(what);
  std::istringstream in(what);
  std::string line, best;
  while (std::getline(in, line)) {
    const auto a = line.find_first_not_of(" \t");
    if (a == std::string::npos || line.compare(a, 4, "====") == 0 || line.find("Call stack") != std::string::npos ||
        std::isdigit(static_cast<unsigned char>(line[a])) || line[a] == '[')
      continue;
    best = line.substr(a);
    break;
  }
  if (best.empty()) best = what.substr(0, what.find('\n'));
  // "file.cpp:123: [func] message" / "OpenCV(4.6.0) file:1: error: (-215:Assertion failed) x in function 'f'"
  if (const auto p = best.find("] "); p != std::string::npos && best.find(": [") != std::string::npos && p < 200)
    best = best.substr(p + 2);
  if (const auto p = best.find(") error: "); p != std::string::npos) best = best.substr(p + 9);
  if (const auto p = best.find(" in function "); p != std::string::npos) best = best.substr(0, p);
  if (best.size() > 200) best = best.substr(0, 200) + "...";
  return best;
}

// The width and height that an image file's header claims, read without decoding the image: PNG (IHDR) and the
// PNM family (P1..P6, PGM among them). Nothing for other formats.
std::optional<std::pair<unsigned long long, unsigned long long>> imageHeaderSize(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::string head(4096, '\0');
  f.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(f.gcount()));
  const auto u8 = [&](std::size_t i) { return static_cast<unsigned long long>(static_cast<unsigned char>(head[i])); };
  if (head.size() >= 24 && head.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 && head.compare(12, 4, "IHDR") == 0)
    return std::make_pair((u8(16) << 24) | (u8(17) << 16) | (u8(18) << 8) | u8(19),
                          (u8(20) << 24) | (u8(21) << 16) | (u8(22) << 8) | u8(23));
  if (head.size() >= 2 && head[0] == 'P' && head[1] >= '1' && head[1] <= '6') {
    std::size_t i = 2;
    unsigned long long v[2] = {0, 0};
    for (auto& x : v) {
      for (;;) {  // white space and comments
        while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
        if (i < head.size() && head[i] == '#')
          while (i < head.size() && head[i] != '\n') ++i;
        else
          break;
      }
      if (i >= head.size() || !std::isdigit(static_cast<unsigned char>(head[i]))) return std::nullopt;
      while (i < head.size() && std::isdigit(static_cast<unsigned char>(head[i])) && x < (1ULL << 40))
        x = x * 10 + static_cast<unsigned long long>(head[i++] - '0');
    }
    return std::make_pair(v[0], v[1]);
  }
  return std::nullopt;
}

cv::Mat loadGrey(const std::string& path, std::size_t max_cells) {
  if (std::string why; !isRegularFile(path, &why))
    throw InputError(path, why.empty() ? "no such image file" : "cannot open the image file: " + why);
  if (::access(path.c_str(), R_OK) != 0) throw InputError(path, std::string("cannot read the image: ") + std::strerror(errno));
  // The header's size against the cell budget before anything is allocated.
  if (const auto size = imageHeaderSize(path)) {
    const auto [w, h] = *size;
    if (w == 0 || h == 0) throw InputError(path, 0, "size", "the image header says " + std::to_string(w) + " x " +
                                                                std::to_string(h) + " pixels: no cells");
    if (w > max_cells || h > max_cells || w * h > max_cells)
      throw InputError(path, 0, "size",
                       "the image header says " + std::to_string(w) + " x " + std::to_string(h) +
                           " pixels, more than the budget of " + std::to_string(max_cells) +
                           " cells (MapReadOptions::max_cells)");
  }
  cv::Mat img;
  try {
    img = cv::imread(path, cv::IMREAD_GRAYSCALE);
  } catch (const std::exception& e) {
    throw InputError(path, "cannot decode the image: " + shortReason(e.what()));
  }
  if (img.empty()) throw InputError(path, "cannot decode the image (not a PNG/PGM/JPG/BMP file?)");
  if (static_cast<std::size_t>(img.total()) > max_cells)
    throw InputError(path, 0, "size",
                     std::to_string(img.cols) + " x " + std::to_string(img.rows) + " pixels, more than the budget of " +
                         std::to_string(max_cells) + " cells (MapReadOptions::max_cells)");
  return img;
}

struct RosMapYaml {
  std::string image;
  double resolution = 0;
  double origin[3] = {0, 0, 0};
  bool negate = false;
  double occupied_thresh = 0.65, free_thresh = 0.196;
  std::string mode = "trinary";
};

RosMapYaml parseRosYamlUnchecked(const std::string& path);

// Every failure of the YAML library (a malformed document, a key of the wrong kind) as "file: what is wrong",
// never the library's banner and call stack.
RosMapYaml parseRosYaml(const std::string& path) {
  if (std::string why; !isRegularFile(path, &why))
    throw InputError(path, why.empty() ? "no such YAML file" : "cannot open the YAML file: " + why);
  if (::access(path.c_str(), R_OK) != 0) throw InputError(path, std::string("cannot read: ") + std::strerror(errno));
  // YAML allows no control bytes but tab, LF and CR (and the parser can loop forever on a NUL: found by
  // map_fuzzer); a map's YAML is a few lines.
  {
    // Read in 64 KiB blocks up to 1 MiB (a zero-filled 1 MiB buffer per read made map_fuzzer page-fault bound).
    std::ifstream f(path, std::ios::binary);
    std::string text;
    char block[1 << 16];
    while (f.read(block, sizeof block), f.gcount() > 0) {
      text.append(block, static_cast<std::size_t>(f.gcount()));
      if (text.size() > (1 << 20)) throw InputError(path, "not a ROS map_server YAML file (larger than 1 MiB)");
    }
    for (std::size_t i = 0; i < text.size(); ++i) {
      const auto c = static_cast<unsigned char>(text[i]);
      if (c >= 0x80) {  // UTF-8: a lead byte and its continuation bytes (the parser also loops on broken ones)
        const std::size_t n = c >= 0xF0 && c < 0xF5 ? 3 : c >= 0xE0 ? (c < 0xF0 ? 2 : 0) : c >= 0xC2 ? 1 : 0;
        bool ok = n > 0 && i + n < text.size() + 0;
        for (std::size_t k = 1; ok && k <= n; ++k) ok = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
        if (!ok) throw InputError(path, "not a UTF-8 text YAML file (byte " + std::to_string(i) + ")");
        i += n;
        continue;
      }
      if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02X", c);
        throw InputError(path, "not a text YAML file (byte " + std::to_string(i) + " is " + hex + ")");
      }
    }
  }
  try {
    return parseRosYamlUnchecked(path);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, "not a ROS map_server YAML file: " + shortReason(e.what()));
  }
}

// The YAML parser (rapidyaml inside MRPT) prints its diagnosis ("<memory-@0x...>:2:13: error: invalid multiline
// plain key" and the lines around it) to stderr and then fails an assertion that says nothing: its stderr is
// captured while it parses, and the diagnosis becomes the error's line and message.
mrpt::containers::yaml parseYamlFile(const std::string& path) {
  std::fflush(stderr);
  std::FILE* capture = std::tmpfile();
  const int saved = capture ? ::dup(2) : -1;
  if (saved >= 0) ::dup2(::fileno(capture), 2);
  std::string failure;
  mrpt::containers::yaml y;
  try {
    y = mrpt::containers::yaml::FromFile(path);
  } catch (const std::exception& e) {
    failure = shortReason(e.what());
  }
  std::string said;
  if (saved >= 0) {
    std::fflush(stderr);
    ::dup2(saved, 2);
    ::close(saved);
    std::rewind(capture);
    char buf[512];
    if (std::fgets(buf, sizeof buf, capture)) said = buf;
  }
  if (capture) std::fclose(capture);
  if (failure.empty()) return y;
  // "<memory-@0x...>:2:13: error: invalid multiline plain key"
  const auto err = said.find(": error: ");
  if (err != std::string::npos) {
    const std::string where = said.substr(0, err);
    std::size_t line = 0;
    if (const auto c1 = where.find(">:"); c1 != std::string::npos) line = std::strtoul(where.c_str() + c1 + 2, nullptr, 10);
    std::string what = said.substr(err + 9);
    while (!what.empty() && (what.back() == '\n' || what.back() == '\r')) what.pop_back();
    throw InputError(path, line, "", "cannot parse YAML: " + what);
  }
  throw InputError(path, 0, "", "cannot parse YAML: " + failure);
}

// A value from the file as it may appear in a one-line message: control bytes escaped (a quoted YAML scalar may
// hold "\n"), at most `max` bytes.
std::string printable(const std::string& v, std::size_t max = 40) {
  std::string out;
  for (const char ch : v.substr(0, max)) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c != 0x7F) {
      out += ch;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
  }
  return v.size() > max ? out + "..." : out;
}

// A YAML scalar as a number, parsed here: MRPT's as<double>() falls through to its integer conversion when the
// text is no decimal number ("0x1G", "1e999") and there casts DBL_MAX to long long (undefined behaviour, found by
// map_fuzzer under UBSan). The whole text must be the number; nullopt if it is not one (a map, a list, a word).
std::optional<double> yamlNumber(const mrpt::containers::yaml& node) {
  if (!node.isScalar()) return std::nullopt;
  std::string text;
  try {
    text = node.as<std::string>();
  } catch (const std::exception&) {
    return std::nullopt;
  }
  const char* begin = text.c_str();
  while (*begin == ' ' || *begin == '\t') ++begin;
  if (*begin == '\0') return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin) return std::nullopt;
  while (*end == ' ' || *end == '\t') ++end;
  if (*end != '\0') return std::nullopt;
  return v;
}

RosMapYaml parseRosYamlUnchecked(const std::string& path) {
  const mrpt::containers::yaml y = parseYamlFile(path);
  if (!y.isMap()) throw InputError(path, "not a ROS map_server YAML file (expected key: value pairs)");
  RosMapYaml m;
  auto number = [&](const char* key, bool required, double def) {
    if (!y.has(key)) {
      if (required) throw InputError(path, 0, key, "missing");
      return def;
    }
    const auto n = yamlNumber(y[key]);
    if (!n) throw InputError(path, 0, key, "expected a number");
    const double v = *n;
    if (!std::isfinite(v)) throw InputError(path, 0, key, "expected a finite number");
    return v;
  };
  if (!y.has("image")) throw InputError(path, 0, "image", "missing");
  try {
    m.image = y["image"].as<std::string>();
  } catch (const std::exception&) {
    throw InputError(path, 0, "image", "expected a file name");
  }
  if (m.image.empty()) throw InputError(path, 0, "image", "empty image file name");
  m.resolution = number("resolution", true, 0);
  if (!(m.resolution > 0)) throw InputError(path, 0, "resolution", "must be positive");
  if (!y.has("origin")) throw InputError(path, 0, "origin", "missing");
  {
    const auto& o = y["origin"];
    if (!o.isSequence() || o.asSequence().size() != 3) throw InputError(path, 0, "origin", "expected [x, y, yaw]");
    for (int i = 0; i < 3; ++i) {
      const auto n = yamlNumber(o.asSequence()[i]);
      if (!n) throw InputError(path, 0, "origin", "expected three numbers [x, y, yaw]");
      m.origin[i] = *n;
      if (!std::isfinite(m.origin[i])) throw InputError(path, 0, "origin", "expected finite numbers");
    }
    if (std::abs(m.origin[2]) > 1e-9)
      throw InputError(path, 0, "origin", "a rotated map (non-zero yaw) cannot be held by an MRPT grid");
  }
  m.negate = number("negate", false, 0) != 0.0;
  m.occupied_thresh = number("occupied_thresh", false, 0.65);
  m.free_thresh = number("free_thresh", false, 0.196);
  if (!(m.free_thresh >= 0 && m.free_thresh < m.occupied_thresh && m.occupied_thresh <= 1))
    throw InputError(path, 0, "free_thresh", "need 0 <= free_thresh < occupied_thresh <= 1");
  if (y.has("mode")) try {
      m.mode = y["mode"].as<std::string>();
    } catch (const std::exception&) {
      throw InputError(path, 0, "mode", "expected trinary, scale or raw");
    }
  if (m.mode != "trinary" && m.mode != "scale" && m.mode != "raw")
    throw InputError(path, 0, "mode", "expected trinary, scale or raw, not '" + printable(m.mode) + "'");
  return m;
}

/// map_server semantics: grey v -> occupancy p = (255 - v) / 255 (v / 255 if negate); p > occupied_thresh is
/// occupied, p < free_thresh free, otherwise unknown (trinary) or p rescaled between the thresholds (scale).
/// raw: v is the occupancy in percent (0..100), anything else unknown.
std::array<COccupancyGridMap2D::cellType, 256> rosLut(const RosMapYaml& m) {
  std::array<COccupancyGridMap2D::cellType, 256> lut{};
  for (int v = 0; v < 256; ++v) {
    double p_free = 0.5;  // unknown
    if (m.mode == "raw") {
      const int occ = m.negate ? 255 - v : v;
      if (occ <= 100) p_free = 1.0 - occ / 100.0;
    } else {
      const double occ = m.negate ? v / 255.0 : (255 - v) / 255.0;
      if (occ > m.occupied_thresh)
        p_free = 0.0;
      else if (occ < m.free_thresh)
        p_free = 1.0;
      else if (m.mode == "scale")
        p_free = 1.0 - (occ - m.free_thresh) / (m.occupied_thresh - m.free_thresh);
    }
    lut[v] = COccupancyGridMap2D::p2l(static_cast<float>(p_free));
  }
  return lut;
}

COccupancyGridMap2D::Ptr readRosMap(const std::string& yaml_path, std::size_t max_cells,
                                    const std::string& image_override = "") {
  const RosMapYaml m = parseRosYaml(yaml_path);
  std::string image = image_override;
  if (image.empty()) {
    const fs::path ip(m.image);
    image = ip.is_absolute() ? ip.string() : (fs::path(yaml_path).parent_path() / ip).string();
    // The YAML names the image: a missing one is the YAML's error (an absolute path elsewhere would otherwise be
    // reported without the file that names it: found by map_fuzzer).
    if (std::string why; !isRegularFile(image, &why))
      throw InputError(yaml_path, 0, "image",
                       (why.empty() ? "no such image file: " : "cannot open the image file (" + why + "): ") +
                           printable(image, 300));
  }
  const cv::Mat img = loadGrey(image, max_cells);
  auto g = makeGrid(yaml_path, img.cols, img.rows, m.resolution, m.origin[0], m.origin[1]);
  fillFromImage(*g, img, rosLut(m));
  return g;
}

// MRPT's deserialiser passes the stored limits through setSize(), which moves an origin that is not a whole
// number of cells by up to half a cell. The stored limits follow the object header as
// [uint8 bits per cell][uint32 size_x][uint32 size_y][float x_min, x_max, y_min, y_max, resolution]
// (little endian, COccupancyGridMap2D serialisation version 6): find that record in the first bytes of the
// file and, if it matches the loaded grid, give the grid its exact stored origin back.
void restoreExactLimits(const std::string& path, COccupancyGridMap2D& g) {
  mrpt::io::CFileGZInputStream in;
  if (!in.open(path)) return;
  std::array<uint8_t, 256> head{};
  const std::size_t n = in.Read(head.data(), head.size());
  auto u32 = [&](std::size_t i) {
    return static_cast<uint32_t>(head[i]) | static_cast<uint32_t>(head[i + 1]) << 8 |
           static_cast<uint32_t>(head[i + 2]) << 16 | static_cast<uint32_t>(head[i + 3]) << 24;
  };
  auto f32 = [&](std::size_t i) {
    const uint32_t bits = u32(i);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  };
  for (std::size_t i = 0; i + 29 <= n; ++i) {
    if ((head[i] != 8 && head[i] != 16) || u32(i + 1) != g.getSizeX() || u32(i + 5) != g.getSizeY()) continue;
    const float x_min = f32(i + 9), x_max = f32(i + 13), y_min = f32(i + 17), y_max = f32(i + 21), res = f32(i + 25);
    const float tol = 0.5f * res + 1e-4f;
    if (res != g.getResolution() || !(std::abs(x_min - g.getXMin()) <= tol) ||
        !(std::abs(y_min - g.getYMin()) <= tol) || !(std::abs(x_max - g.getXMax()) <= tol) ||
        !(std::abs(y_max - g.getYMax()) <= tol))
      continue;
    GridLimits::set(g, x_min, y_min);
    return;
  }
}

COccupancyGridMap2D::Ptr parseGridmapFile(const std::string& path) {
  mrpt::io::CFileGZInputStream in;
  if (!isRegularFile(path) || !in.open(path)) throw InputError(path, "cannot open gridmap file");
  mrpt::serialization::CSerializable::Ptr obj;
  try {
    obj = mrpt::serialization::archiveFrom(in).ReadObject();
  } catch (const std::exception& e) {
    throw InputError(path, 0, "",
                     "cannot read an MRPT serialized object (corrupt or truncated?): " + innermostMrptMessage(e.what()));
  }
  auto g = std::dynamic_pointer_cast<COccupancyGridMap2D>(obj);
  if (!g)
    throw InputError(path, 0, "",
                     std::string("holds a ") + (obj ? obj->GetRuntimeClass()->className : "null") +
                         ", not an mrpt::maps::COccupancyGridMap2D");
  restoreExactLimits(path, *g);
  return g;
}

COccupancyGridMap2D::Ptr readGridmapFile(const std::string& path) {
  if (!isRegularFile(path)) throw InputError(path, "cannot open gridmap file");
  // MRPT's deserialiser may crash or allocate gigabytes on corrupted data: parse in a child process first.
  checkParsesInChild(path, [&](volatile std::uint64_t*) { parseGridmapFile(path); });
  return parseGridmapFile(path);
}

void writeGz(const std::string& tmp, const mrpt::serialization::CSerializable& obj) {
  mrpt::io::CFileGZOutputStream out;
  if (!out.open(tmp, 1)) throw std::runtime_error("cannot open " + tmp + " for writing");
  mrpt::serialization::archiveFrom(out) << obj;
  out.close();
}

}  // namespace

namespace {
// The ROS YAML with the same stem as an image, or "" if there is none.
std::string yamlBeside(const std::string& path) {
  for (const char* ext : {".yaml", ".yml"}) {
    const fs::path yaml = fs::path(path).replace_extension(ext);
    if (isRegularFile(yaml.string())) return yaml.string();
  }
  return "";
}
}  // namespace

MapKind mapFileKind(const std::string& path) {
  const std::string l = lower(path);
  if (endsWith(l, ".gridmap") || endsWith(l, ".gridmap.gz")) return MapKind::ProbabilisticGrid;
  if (endsWith(l, ".yaml") || endsWith(l, ".yml") || !yamlBeside(path).empty()) return MapKind::RosMap;
  return MapKind::PlainImage;
}

MapImage mapImageOfGrid(const mrpt::maps::COccupancyGridMap2D& grid, MapKind kind, const std::string& source) {
  MapImage m;
  m.grey = gridToImage(grid);
  m.resolution = grid.getResolution();
  m.origin = cv::Point2d(grid.getXMin(), grid.getYMin());
  m.kind = kind;
  m.source = source;
  return m;
}

MapImage readMap(const std::string& path, const MapReadOptions& options) {
  return mapImageOfGrid(*readGridMap(path, options), mapFileKind(path), path);
}

mrpt::maps::COccupancyGridMap2D::Ptr readGridMap(const std::string& path, const MapReadOptions& options) {
  const std::string l = lower(path);
  if (endsWith(l, ".yaml") || endsWith(l, ".yml")) return readRosMap(path, options.max_cells);
  if (mapFileKind(path) == MapKind::ProbabilisticGrid) return readGridmapFile(path);
  // An image: a ROS YAML with the same stem beside it gives resolution, origin and thresholds.
  if (const std::string yaml = yamlBeside(path); !yaml.empty()) return readRosMap(yaml, options.max_cells, path);
  if (!(options.resolution > 0) || !std::isfinite(options.resolution))
    throw InputError(path, 0, "resolution", "must be a positive number of metres per pixel");
  const cv::Mat img = loadGrey(path, options.max_cells);
  auto g = makeGrid(path, img.cols, img.rows, options.resolution, options.origin_x, options.origin_y);
  // Plain images: grey level = p_free * 255 (white free, black occupied), as MRPT's own image loader.
  std::array<COccupancyGridMap2D::cellType, 256> lut{};
  for (int v = 0; v < 256; ++v) lut[v] = COccupancyGridMap2D::p2l(static_cast<float>(v) / 255.0f);
  fillFromImage(*g, img, lut);
  return g;
}

cv::Mat gridToImage(const mrpt::maps::COccupancyGridMap2D& grid) {
  const int w = static_cast<int>(grid.getSizeX()), h = static_cast<int>(grid.getSizeY());
  cv::Mat img(h, w, CV_8UC1);
  // round(255 * p_free) per raw cell value (MRPT's l2p_255 truncates: 255 would come back as 254).
  using Cell = COccupancyGridMap2D::cellType;
  using Unsigned = COccupancyGridMap2D::cellTypeUnsigned;
  std::vector<uint8_t> lut(std::size_t{1} << (8 * sizeof(Cell)));
  for (std::size_t u = 0; u < lut.size(); ++u) {
    const Cell c = static_cast<Cell>(static_cast<Unsigned>(u));
    lut[u] = static_cast<uint8_t>(std::lround(255.0 * COccupancyGridMap2D::l2p(c)));
  }
  for (int r = 0; r < h; ++r) {
    const Cell* cells = grid.getRow(h - 1 - r);
    uint8_t* row = img.ptr<uint8_t>(r);
    for (int c = 0; c < w; ++c) row[c] = lut[static_cast<Unsigned>(cells[c])];
  }
  return img;
}

void writeMapPng(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path) {
  writePng(gridToImage(grid), path);
}

void writeRosMap(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& stem) {
  // map_saver convention: occupied (p_occ > 0.65) = 0, free (p_occ < 0.196) = 254, unknown = 205.
  const int w = static_cast<int>(grid.getSizeX()), h = static_cast<int>(grid.getSizeY());
  cv::Mat img(h, w, CV_8UC1);
  for (int r = 0; r < h; ++r) {
    uint8_t* row = img.ptr<uint8_t>(r);
    for (int c = 0; c < w; ++c) {
      const double p_occ = 1.0 - static_cast<double>(grid.getCell(c, h - 1 - r));
      row[c] = p_occ > 0.65 ? 0 : (p_occ < 0.196 ? 254 : 205);
    }
  }
  const std::string pgm = stem + ".pgm", yaml = stem + ".yaml";
  std::ostringstream y;
  y << "image: " << fs::path(pgm).filename().string() << "\n"
    << "resolution: " << formatFloat(grid.getResolution()) << "\n"
    << "origin: [" << formatFloat(grid.getXMin()) << ", " << formatFloat(grid.getYMin()) << ", 0.0]\n"
    << "negate: 0\n"
    << "occupied_thresh: 0.65\n"
    << "free_thresh: 0.196\n";
  OutputSet out;
  out.write(pgm, [&](const std::string& tmp) {
    writePgm(img, tmp);  // binary PGM (P5), what map_server's map_saver writes
  });
  out.write(yaml, [&](const std::string& tmp) {
    std::ofstream f(tmp);
    f << y.str();
    if (!f.flush()) throw std::runtime_error("cannot write " + yaml);
  });
  out.commit();
}

void writeGridmapGz(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path) {
  writeFileAtomically(path, [&](const std::string& tmp) { writeGz(tmp, grid); });
}

void writeSimplemap(const mrpt::maps::CSimpleMap& map, const std::string& path) {
  writeFileAtomically(path, [&](const std::string& tmp) { writeGz(tmp, map); });
}

void writeGridMap(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path) {
  const std::string l = lower(path);
  if (endsWith(l, ".gridmap") || endsWith(l, ".gridmap.gz")) return writeGridmapGz(grid, path);
  if (endsWith(l, ".yaml") || endsWith(l, ".pgm"))
    return writeRosMap(grid, fs::path(path).replace_extension().string());
  if (endsWith(l, ".png") || endsWith(l, ".bmp") || endsWith(l, ".jpg") || endsWith(l, ".jpeg"))
    return writeMapPng(grid, path);
  throw std::invalid_argument("unknown map format for '" + path +
                              "' (expected .png, .yaml/.pgm, .gridmap or .gridmap.gz)");
}

}  // namespace gridtopo::io
