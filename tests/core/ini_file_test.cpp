#include <gtest/gtest.h>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_file.h"

using namespace gridtopo;

namespace {
const char* kText =
    "; a comment\n"
    "[run]\n"
    "input = /data/log.clf   ; the log\n"
    "  output=out  \n"
    "# another comment\n"
    "// and another\n"
    "@define X 3\n"
    "\n"
    "[slam]\n"
    "particles = 30 // many\n"
    "seed = 1\n"
    "particles = 40\n";
}

TEST(IniFile, SectionsKeysLinesAndValues) {
  const IniFile ini = IniFile::parse(kText, "run.ini");
  EXPECT_EQ(ini.name(), "run.ini");
  EXPECT_EQ(ini.sections(), (std::vector<std::string>{"run", "slam"}));
  EXPECT_EQ(ini.keys("run"), (std::vector<std::string>{"input", "output"}));
  EXPECT_EQ(ini.keys("slam"), (std::vector<std::string>{"particles", "seed"}));
  EXPECT_EQ(ini.line("run"), 2u);
  EXPECT_EQ(ini.line("run", "output"), 4u);
  EXPECT_EQ(ini.line("slam", "seed"), 11u);
  EXPECT_EQ(ini.line("slam", "input"), 0u);
  EXPECT_EQ(ini.line("nothing"), 0u);
  EXPECT_TRUE(ini.hasSection("slam"));
  EXPECT_FALSE(ini.hasSection("X"));
  EXPECT_TRUE(ini.hasKey("run", "input"));
  EXPECT_EQ(*ini.value("run", "input"), "/data/log.clf");
  EXPECT_EQ(*ini.value("run", "output"), "out");
  EXPECT_EQ(*ini.value("slam", "particles"), "40");  // the last one wins, as in MRPT
  EXPECT_FALSE(ini.value("slam", "threads"));
}

TEST(IniFile, UnknownSectionsAndKeysNameFileLineSectionAndKey) {
  const IniFile ini = IniFile::parse(kText, "run.ini");
  EXPECT_NO_THROW(ini.requireKnownSections({"run", "slam"}));
  try {
    ini.requireKnownSections({"run"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "run.ini:9: [slam]: unknown section (expected run)");
  }
  EXPECT_NO_THROW(ini.requireKnownKeys("run", {"input", "output"}));
  try {
    ini.requireKnownKeys("run", {"input", "max_scans"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "run.ini:4: [run] output: unknown key (expected input, max_scans)");
  }
  try {
    ini.requireKnownKeys("slam", {"particles"}, "see slam.ini");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "run.ini:11: [slam] seed: unknown key (see slam.ini)");
  }
}

TEST(IniFile, LinesForErrorsOfOptionLoaders) {
  const IniFile ini = IniFile::parse(kText, "run.ini");
  EXPECT_EQ(ini.lineOrSection("slam", "seed"), 11u);
  EXPECT_EQ(ini.lineOrSection("slam", "threads"), 9u);  // absent: where it belongs
  EXPECT_EQ(ini.lineOrSection("other", "x"), 0u);
  // An options loader names "[section] key" without a line: the line of that key is added.
  EXPECT_STREQ(ini.withLine(InputError("run.ini", 0, "[slam] seed", "must be >= 0")).what(),
               "run.ini:11: [slam] seed: must be >= 0");
  EXPECT_STREQ(ini.withLine(InputError("run.ini", 0, "[slam] threads", "bad")).what(), "run.ini: [slam] threads: bad");
  EXPECT_STREQ(ini.withLine(InputError("run.ini", 3, "[slam] seed", "bad")).what(), "run.ini:3: [slam] seed: bad");
  EXPECT_STREQ(ini.withLine(InputError("run.ini", 0, "--seed", "bad")).what(), "run.ini: --seed: bad");
}

TEST(IniFile, MalformedLinesAndMissingFilesAreInputErrors) {
  auto message = [](const std::string& text) {
    try {
      IniFile::parse(text, "bad.ini");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("[run\nx = 1\n"), "bad.ini:1: [run: a section header without ']'");
  EXPECT_EQ(message("[run]\njust words\n"), "bad.ini:2: just words: expected 'key = value' or '[section]'");
  EXPECT_EQ(message("[run]\n = 3\n"), "bad.ini:2: a value without a key");
  EXPECT_EQ(message("x = 1\n"), "bad.ini:1: x: a key before the first [section]");
  EXPECT_THROW(IniFile::read("/nonexistent/run.ini"), InputError);
}

TEST(IniFile, RepeatsAreAllowedUnlessRefused) {
  const IniFile twice_key = IniFile::parse("[run]\nx = 1\n[slam]\ny = 2\n[run]\nz = 3\nx = 4\n", "r.ini");
  EXPECT_EQ(twice_key.value("run", "x"), std::optional<std::string>("4"));  // the last wins, as in MRPT
  try {
    twice_key.requireNoRepeats();
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "r.ini:5: [run]: section given twice");
  }
  const IniFile twice = IniFile::parse("[run]\nx = 1\ny = 2\nx = 3\n", "r.ini");
  try {
    twice.requireNoRepeats();
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "r.ini:4: [run] x: key given twice");
  }
  EXPECT_NO_THROW(IniFile::parse("[run]\nx = 1\n[slam]\nx = 1\n", "r.ini").requireNoRepeats());
}
