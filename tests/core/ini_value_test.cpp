#include "gridtopo/core/ini_value.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <string>

using namespace gridtopo;

namespace {
// The two calls readIniValue makes on an MRPT config, over a map.
struct FakeConfig {
  std::map<std::string, std::string> values;  // "section/key" -> raw text
  bool keyExists(const std::string& s, const std::string& k) const { return values.count(s + "/" + k) > 0; }
  std::string read_string(const std::string& s, const std::string& k, const std::string& def, bool) const {
    const auto it = values.find(s + "/" + k);
    return it == values.end() ? def : it->second;
  }
};
}  // namespace

TEST(IniValue, TrailingCommentsAndWhiteSpaceAreNotPartOfTheValue) {
  EXPECT_EQ(iniValueText("  30 ; particles"), "30");
  EXPECT_EQ(iniValueText("0.05 // metres"), "0.05");
  EXPECT_EQ(iniValueText("true # on\t"), "true");
  EXPECT_EQ(iniValueText("auto   ; auto | odom | laser"), "auto");
  EXPECT_EQ(iniValueText("a;b"), "a;b");  // not after white space: part of the value
  EXPECT_EQ(iniValueText("http://x"), "http://x");
  EXPECT_EQ(iniValueText("; only a comment"), "");
}

TEST(IniValue, NumbersAreParsedStrictly) {
  int i = 7;
  EXPECT_FALSE(parseIniValue("-12", i));
  EXPECT_EQ(i, -12);
  EXPECT_EQ(*parseIniValue("abc", i), "an integer");  // MRPT's read_int gives 0
  EXPECT_EQ(*parseIniValue("2.5", i), "an integer");  // MRPT's read_int gives 2
  EXPECT_EQ(*parseIniValue("12abc", i), "an integer");
  EXPECT_EQ(*parseIniValue("", i), "an integer");
  EXPECT_EQ(*parseIniValue("99999999999", i), "an integer");  // does not fit
  unsigned u = 0;
  EXPECT_EQ(*parseIniValue("-1", u), "a non-negative integer");
  std::uint64_t big = 0;
  EXPECT_FALSE(parseIniValue("18446744073709551615", big));
  EXPECT_EQ(big, 18446744073709551615ULL);
  double d = 0;
  EXPECT_FALSE(parseIniValue("1e-3", d));
  EXPECT_EQ(d, 1e-3);
  EXPECT_EQ(*parseIniValue("nan", d), "a finite number");
  EXPECT_EQ(*parseIniValue("inf", d), "a finite number");
  EXPECT_EQ(*parseIniValue("0.5m", d), "a finite number");
  float f = 0;
  EXPECT_EQ(*parseIniValue("1e300", f), "a finite number");
  bool b = false;
  EXPECT_FALSE(parseIniValue("Yes", b));
  EXPECT_TRUE(b);
  EXPECT_FALSE(parseIniValue("off", b));
  EXPECT_FALSE(b);
  EXPECT_EQ(*parseIniValue("maybe", b), "a boolean (true/false)");
}

TEST(IniValue, ReaderKeepsDefaultsAndNamesSectionAndKeyOnErrors) {
  FakeConfig cfg;
  cfg.values["relaxation/max_iterations"] = "30 ; bounded";
  cfg.values["relaxation/tolerance"] = "abc";
  int iterations = 5, radius = 1;
  readIniValue(cfg, "relaxation", "max_iterations", iterations);
  EXPECT_EQ(iterations, 30);
  readIniValue(cfg, "relaxation", "neighbourhood_radius", radius);  // absent: unchanged
  EXPECT_EQ(radius, 1);
  EXPECT_EQ(readIni(cfg, "relaxation", "missing", 0.25), 0.25);
  double tolerance = 0.001;
  try {
    readIniValue(cfg, "relaxation", "tolerance", tolerance);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "[relaxation]");
    EXPECT_EQ(e.field(), "tolerance");
    EXPECT_EQ(e.message(), "cannot parse 'abc' as a finite number");
  }
  EXPECT_EQ(tolerance, 0.001);  // unchanged after an error
}
