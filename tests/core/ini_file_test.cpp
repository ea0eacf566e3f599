#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

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

// Near misses get a "did you mean" (one edit, two from 8 letters on; a swap of neighbours is one edit); far ones
// only the list.
TEST(IniFile, NearMissesGetADidYouMean) {
  EXPECT_EQ(closestName("particlez", {"seed", "particles"}), "particles");
  EXPECT_EQ(closestName("slma", {"slam_run", "slam"}), "slam");
  EXPECT_EQ(closestName("slamm", {"slam_run", "slam"}), "slam");
  EXPECT_EQ(closestName("partcles", {"particles"}), "particles");
  EXPECT_EQ(closestName("prticlez", {"particles"}), "particles");  // two edits in 8 letters
  EXPECT_EQ(closestName("seeds", {"seed"}), "seed");
  EXPECT_EQ(closestName("output", {"input", "max_scans"}), "");  // two edits in 6 letters: no guess
  EXPECT_EQ(closestName("zzz", {"seed"}), "");
  const IniFile ini = IniFile::parse("[slam]\nparticlez = 3\n", "c.ini");
  try {
    ini.requireKnownKeys("slam", {"particles", "seed"}, "see config-ini/slam.ini");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "c.ini:2: [slam] particlez: unknown key (did you mean 'particles'? see config-ini/slam.ini)");
  }
}

// The checks of a -c options file: other gridtopo apps' sections pass (one INI for several apps), a typo does not,
// the section the app reads must be there, keys once.
TEST(IniFile, OptionsFileChecks) {
  IniFile::parse("[slam]\nparticles = 3\n[topology]\nx = 1\n[relations_metric]\n", "a.ini")
      .requireOptionsFile({"slam", "loop_closure"}, "slam");
  try {
    IniFile::parse("[slam]\nparticles = 3\n\n[slamm]\nparticles = 4\n", "b.ini").requireOptionsFile({"slam"}, "slam");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "b.ini:4: [slamm]: unknown section (did you mean [slam]? this app reads slam)");
  }
  try {
    IniFile::parse("[relaxation]\niterations = 3\n", "c.ini").requireOptionsFile({"topology", "relaxation"}, "topology");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "c.ini: [topology]: section not found");
  }
  EXPECT_THROW(IniFile::parse("[slam]\nseed = 1\nseed = 2\n", "d.ini").requireOptionsFile({"slam"}, "slam"),
               InputError);
}

// A binary file given as an INI is refused before parsing, naming the file and the first non-text byte; an
// unreadable one says the system's reason.
TEST(IniFile, BinaryAndUnreadableFilesAreRefusedUpFront) {
  const std::string elf = ::testing::TempDir() + "ini_file_test_binary_" + std::to_string(::getpid());
  {
    std::ofstream f(elf, std::ios::binary);
    f << "\x7f" "ELF" << '\x02' << '\x01' << std::string(3, '\0') << "[slam]\n";
  }
  try {
    IniFile::read(elf);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), elf + ": not a text INI file (byte 0 is 0x7F)");
  }
  std::remove(elf.c_str());
  try {
    IniFile::read("/nonexistent/x.ini");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/x.ini: cannot read the INI file: No such file or directory");
  }
}
