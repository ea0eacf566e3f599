// OptionTable on a small hand-written options struct: entries, types, defaults, help from a documented INI,
// edits, the INI text and loading back through the struct's own validation. No display needed.
#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <fstream>
#include <iterator>
#include <string>

#include "gridtopo/core/error.h"
#include "gridtopo/core/ini_value.h"
#include "gridtopo/session/option_table.h"
#include "test_helpers.h"

using namespace gridtopo;
using session::OptionEntry;
using session::OptionTable;

namespace {
/// Keys of every type, plus one key in a sub-section ("<section>.io").
struct DemoOptions : public mrpt::config::CLoadableOptions {
  int particles = 30;
  double resolution = 0.05;
  bool enabled = true;
  std::string mode = "informed";
  double gain = 2;  // written "2" by default: an Int by its default, a Double once it holds a fraction
  int buffer = 8;   // in [<section>.io]

  void loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s) override {
    readIniValue(c, s, "particles", particles);
    readIniValue(c, s, "resolution", resolution);
    readIniValue(c, s, "enabled", enabled);
    readIniValue(c, s, "mode", mode);
    readIniValue(c, s, "gain", gain);
    readIniValue(c, s + ".io", "buffer", buffer);
    if (particles < 1) throw InputError("[" + s + "]", 0, "particles", "must be >= 1");
  }
  void saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const override {
    c.write(s, "particles", std::to_string(particles));
    c.write(s, "resolution", resolution == 0.05 ? std::string("0.05") : std::to_string(resolution));
    c.write(s, "enabled", std::string(enabled ? "true" : "false"));
    c.write(s, "mode", mode);
    c.write(s, "gain", gain == 2 ? std::string("2") : std::string("2.5"));
    c.write(s + ".io", "buffer", std::to_string(buffer));
  }
};

DemoOptions changed() {
  DemoOptions o;
  o.particles = 12;
  o.mode = "odometry";
  o.gain = 2.5;
  return o;
}
}  // namespace

TEST(OptionTable, EntriesHoldValuesDefaultsAndTypes) {
  const OptionTable t = OptionTable::fromOptions(changed(), DemoOptions{}, "demo");
  ASSERT_EQ(t.entries().size(), 6u);
  const auto* p = t.find("demo", "particles");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->value, "12");
  EXPECT_EQ(p->default_value, "30");
  EXPECT_EQ(p->type, OptionEntry::Type::Int);
  EXPECT_EQ(p->help, "");
  EXPECT_EQ(t.find("demo", "resolution")->type, OptionEntry::Type::Double);
  EXPECT_EQ(t.find("demo", "enabled")->type, OptionEntry::Type::Bool);
  EXPECT_EQ(t.find("demo", "enabled")->value, "true");
  EXPECT_EQ(t.find("demo", "mode")->type, OptionEntry::Type::String);
  EXPECT_EQ(t.find("demo", "mode")->value, "odometry");
  EXPECT_EQ(t.find("demo", "mode")->default_value, "informed");
  // Default "2" reads as an integer, the current "2.5" makes it a Double.
  EXPECT_EQ(t.find("demo", "gain")->type, OptionEntry::Type::Double);
  EXPECT_EQ(t.find("demo", "gain")->value, "2.5");
  const auto* b = t.find("demo.io", "buffer");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->type, OptionEntry::Type::Int);
  EXPECT_EQ(b->value, "8");
  // Unknown keys and keys of another section are not found.
  EXPECT_EQ(t.find("demo", "buffer"), nullptr);
  EXPECT_EQ(t.find("demo.io", "particles"), nullptr);
  EXPECT_EQ(t.find("other", "particles"), nullptr);
  // With equal defaults an integer stays an integer.
  EXPECT_EQ(OptionTable::fromOptions(DemoOptions{}, DemoOptions{}, "demo").find("demo", "gain")->type,
            OptionEntry::Type::Int);
}

TEST(OptionTable, SetTrimsAndRefusesUnknownKeys) {
  OptionTable t = OptionTable::fromOptions(DemoOptions{}, DemoOptions{}, "demo");
  EXPECT_TRUE(t.set("demo", "particles", "  7 \t"));
  EXPECT_EQ(t.find("demo", "particles")->value, "7");
  EXPECT_EQ(t.find("demo", "particles")->default_value, "30");  // defaults stay
  EXPECT_FALSE(t.set("demo", "nope", "1"));
  EXPECT_FALSE(t.set("demo.io", "particles", "1"));
  EXPECT_EQ(t.entries().size(), 6u);  // set never adds
}

TEST(OptionTable, ApplyToLoadsThroughTheStructAndItsValidation) {
  OptionTable t = OptionTable::fromOptions(DemoOptions{}, DemoOptions{}, "demo");
  ASSERT_TRUE(t.set("demo", "particles", "5"));
  ASSERT_TRUE(t.set("demo", "enabled", "false"));
  ASSERT_TRUE(t.set("demo", "mode", "mode-only"));
  ASSERT_TRUE(t.set("demo.io", "buffer", "64"));
  DemoOptions o;
  t.applyTo(o, "demo");
  EXPECT_EQ(o.particles, 5);
  EXPECT_FALSE(o.enabled);
  EXPECT_EQ(o.mode, "mode-only");
  EXPECT_EQ(o.buffer, 64);
  EXPECT_DOUBLE_EQ(o.resolution, 0.05);

  // A malformed value: the struct's InputError naming section and key.
  t.set("demo", "particles", "2.5");
  try {
    t.applyTo(o, "demo");
    FAIL() << "2.5 accepted as an integer";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "particles");
    EXPECT_EQ(std::string(e.what()), "[demo]: particles: cannot parse '2.5' as an integer");
  }
  // A well-formed value the struct's validation refuses.
  t.set("demo", "particles", "0");
  try {
    t.applyTo(o, "demo");
    FAIL() << "0 particles accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "[demo]: particles: must be >= 1");
  }
}

TEST(OptionTable, ToIniWritesSectionsHelpAndValuesAndReadsBack) {
  guitest::TempDir tmp;
  {
    std::ofstream(tmp / "demo.ini") << "[demo]\n"
                                       "# Number of particles.\n"
                                       "particles = 30\n";
  }
  OptionTable t = OptionTable::fromOptions(changed(), DemoOptions{}, "demo");
  t.addHelpFromIni(tmp / "demo.ini");
  const std::string ini = t.toIni();
  EXPECT_EQ(ini,
            "# written by gridtopo-gui\n"
            "\n[demo]\n"
            "enabled = true\n"
            "gain = 2.5\n"
            "mode = odometry\n"
            "# Number of particles.\n"
            "particles = 12\n"
            "resolution = 0.05\n"
            "\n[demo.io]\n"
            "buffer = 8\n")
      << ini;
  // The text loads back into the struct with the same values.
  { std::ofstream(tmp / "out.ini") << ini; }
  DemoOptions o;
  mrpt::config::CConfigFileMemory cfg;
  {
    std::ifstream in(tmp / "out.ini");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    cfg.setContent(text);
  }
  o.loadFromConfigFile(cfg, "demo");
  EXPECT_EQ(o.particles, 12);
  EXPECT_EQ(o.mode, "odometry");
  EXPECT_DOUBLE_EQ(o.gain, 2.5);
}

TEST(OptionTable, HelpFromCommentsAboveInlineAndSharedByABlock) {
  guitest::TempDir tmp;
  {
    std::ofstream(tmp / "demo.ini")
        << "# Header of the file, ended by a blank line.\n"
           "\n"
           "[demo]\n"
           "# ---------------------------------------------------------------- filter\n"
           "# Number of particles\n"
           "# (>= 1).\n"
           "particles = 30\n"
           "resolution = 0.05   # Cell size (m).\n"
           "# Two keys under one comment.\n"
           "enabled = true\n"
           "mode = informed\n"
           "\n"
           "gain = 2\n"
           "[demo.io]\n"
           "; Buffer size.\n"
           "buffer = 8\n"
           "[elsewhere]\n"
           "# Not this one.\n"
           "gain = 1\n";
  }
  OptionTable t = OptionTable::fromOptions(DemoOptions{}, DemoOptions{}, "demo");
  t.addHelpFromIni(tmp / "demo.ini");
  EXPECT_EQ(t.find("demo", "particles")->help, "Number of particles (>= 1).");  // lines joined, separator dropped
  EXPECT_EQ(t.find("demo", "resolution")->help, "Cell size (m).");               // inline
  EXPECT_EQ(t.find("demo", "enabled")->help, "Two keys under one comment.");
  EXPECT_EQ(t.find("demo", "mode")->help, "Two keys under one comment.");        // same block
  EXPECT_EQ(t.find("demo", "gain")->help, "");  // a blank line ends the block; [elsewhere] is not [demo]
  EXPECT_EQ(t.find("demo.io", "buffer")->help, "Buffer size.");                  // ';' comments too
  // A missing file: no help and no error.
  OptionTable u = OptionTable::fromOptions(DemoOptions{}, DemoOptions{}, "demo");
  EXPECT_NO_THROW(u.addHelpFromIni(tmp / "missing.ini"));
  for (const auto& e : u.entries()) EXPECT_EQ(e.help, "") << e.key;
}
