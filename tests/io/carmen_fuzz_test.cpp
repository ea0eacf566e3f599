// Deterministic random-mutation fuzzing of the CARMEN parser on a slice of the real Intel log: thousands of
// mutated, truncated and (re)compressed variants must either parse into a consistent CarmenLog or throw
// gridtopo::InputError; anything else (crash, hang, other exception) fails the test.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/io/carmen_log.h"

namespace fs = std::filesystem;
using namespace gridtopo::io;

namespace {

/// The first `max_lines` lines of the bundled Intel log, plus a ROBOTLASER1 and PARAM lines so every parser
/// path is exercised.
std::string realSlice(std::size_t max_lines) {
  gzFile g = gzopen((std::string(GRIDTOPO_DATA_DIR) + "/slam/intel.clf.gz").c_str(), "rb");
  EXPECT_NE(g, nullptr);
  std::string out;
  char buf[1 << 14];
  std::size_t lines = 0;
  while (lines < max_lines && gzgets(g, buf, sizeof buf)) {
    out += buf;
    ++lines;
  }
  gzclose(g);
  out += "PARAM laser_front_laser_resolution 1.0 nohost 0\nPARAM robot_front_laser_max 40 nohost 0\n";
  out += "ROBOTLASER1 0 -1.5708 3.14159 0.0174533 81.9 0.01 0 5 1 2 3 81.9 nan 2 0.1 0.2 0.1 0.2 0.3 0 0 0 0.1 0 "
         "0.5 0.3 0 976052857.4 host 0.1\n";
  out += "RAWLASER1 0 -1.5708 3.14159 0.0174533 81.9 0.01 0 3 1 2 3 0 976052857.4 host 0.1\n";
  return out;
}

std::string gzipString(const std::string& s) {
  std::string out(compressBound(static_cast<uLong>(s.size())) + 64, '\0');
  z_stream zs{};
  deflateInit2(&zs, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(s.data()));
  zs.avail_in = static_cast<uInt>(s.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

const char* kTokens[] = {"nan", "-nan", "inf", "-inf", "1e999", "-1e999", "1e-999", "0", "-0", "-1", "+1",
                         "18446744073709551616", "99999999", "180", "181", "0x10", "", " ", "\t", "\r", "#",
                         "FLASER", "ODOM", "PARAM", "ROBOTLASER1", "RLASER", "\n", "1.0.0", "--1", "e5", ".",
                         "\xff\xfe", "\x01"};  // NUL bytes come from the byte flips

std::string mutate(std::string s, std::mt19937& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? std::size_t(0) : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const int edits = 1 + static_cast<int>(pick(4));
  for (int e = 0; e < edits && !s.empty(); ++e) {
    switch (pick(7)) {
      case 0:  // flip a byte
        s[pick(s.size())] = static_cast<char>(pick(256));
        break;
      case 1: {  // delete a span
        const std::size_t b = pick(s.size());
        s.erase(b, 1 + pick(std::min<std::size_t>(200, s.size() - b)));
        break;
      }
      case 2: {  // insert a nasty token at a token boundary
        std::size_t b = pick(s.size());
        while (b < s.size() && s[b] != ' ') ++b;
        s.insert(b, std::string(" ") + kTokens[pick(sizeof kTokens / sizeof *kTokens)]);
        break;
      }
      case 3: {  // replace a token by a nasty one
        std::size_t b = pick(s.size());
        while (b > 0 && s[b - 1] != ' ') --b;
        std::size_t end = b;
        while (end < s.size() && s[end] != ' ' && s[end] != '\n') ++end;
        s.replace(b, end - b, kTokens[pick(sizeof kTokens / sizeof *kTokens)]);
        break;
      }
      case 4:  // truncate
        s.resize(pick(s.size()));
        break;
      case 5: {  // duplicate a span
        const std::size_t b = pick(s.size());
        const std::size_t len = 1 + pick(std::min<std::size_t>(500, s.size() - b));
        s.insert(pick(s.size()), s.substr(b, len));
        break;
      }
      default: {  // swap two lines' order by moving a chunk
        const std::size_t b = pick(s.size());
        const std::size_t len = 1 + pick(std::min<std::size_t>(300, s.size() - b));
        const std::string chunk = s.substr(b, len);
        s.erase(b, len);
        s.insert(pick(s.size() + 1), chunk);
        break;
      }
    }
  }
  return s;
}

void checkConsistent(const CarmenLog& log) {
  for (const auto& r : log.scans) {
    ASSERT_GT(r.scan.size(), 0u);
    ASSERT_EQ(r.scan.valid.size(), r.scan.ranges.size());
    ASSERT_TRUE(std::isfinite(r.scan.timestamp));
    ASSERT_TRUE(std::isfinite(r.scan.start_angle));
    ASSERT_TRUE(std::isfinite(r.scan.angle_increment));
    ASSERT_TRUE(r.scan.max_range > 0);
    ASSERT_TRUE(std::isfinite(r.odometry.x) && std::isfinite(r.odometry.y) && std::isfinite(r.odometry.phi));
    ASSERT_TRUE(std::isfinite(r.scan.sensor_pose.x) && std::isfinite(r.scan.sensor_pose.phi));
    for (std::size_t k = 0; k < r.scan.size(); ++k) {
      if (r.scan.valid[k]) {
        ASSERT_TRUE(r.scan.ranges[k] > 0 && r.scan.ranges[k] < r.scan.max_range);
      }
    }
    ASSERT_GT(r.source_index, 0u);
  }
  for (const auto& o : log.odometry) ASSERT_TRUE(std::isfinite(o.pose.phi) && std::isfinite(o.timestamp));
}

}  // namespace

TEST(CarmenFuzz, MutatedRealLogNeverCrashes) {
  const std::string base = realSlice(24);
  {
    std::istringstream in(base);
    const CarmenLog log = parseCarmenLog(in, "slice.clf");
    ASSERT_GE(log.scans.size(), 5u);  // the slice itself is valid
  }
  std::mt19937 rng(20091027);
  std::size_t parsed = 0, rejected = 0, skipped_lines = 0;
  const int kVariants = 4000;
  for (int i = 0; i < kVariants; ++i) {
    std::string text = mutate(base, rng);
    const int mode = i % 4;
    if (mode == 3) {
      // Mutate the compressed bytes instead (truncated / corrupt gzip).
      std::string gz = gzipString(base);
      gz = mutate(gz, rng);
      if (gz.size() < 2 || i % 8 == 3) gz = gzipString(base).substr(0, std::uniform_int_distribution<std::size_t>(0, gz.size())(rng));
      text = gz;
    } else if (mode == 2) {
      text = gzipString(text);
    }
    CarmenReadOptions o;
    o.skip_bad_lines = (i % 2 == 1);
    o.read_rear_laser = (i % 3 == 0);
    try {
      std::istringstream in(text);
      const CarmenLog log = parseCarmenLog(in, "fuzz.clf", o);
      checkConsistent(log);
      skipped_lines += log.skipped_lines;
      ++parsed;
    } catch (const gridtopo::InputError& e) {
      ASSERT_NE(std::string(e.what()).find("fuzz.clf"), std::string::npos);
      ++rejected;
    }
  }
  std::cout << "fuzz: " << parsed << " parsed, " << rejected << " rejected, " << skipped_lines
            << " lines skipped\n";
  EXPECT_EQ(parsed + rejected, static_cast<std::size_t>(kVariants));
  EXPECT_GT(parsed, 100u);    // the mutations do not all break the log...
  EXPECT_GT(rejected, 100u);  // ...and many are caught
  EXPECT_GT(skipped_lines, 100u);
}
