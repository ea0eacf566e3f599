// OptionTable from key tables (OptionSchema::describe): entries with values, defaults, types, ranges, units, help and
// words; edits; the INI text; loading back through the struct's own loading and validation. No display needed.
#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <string>

#include "gridtopo/core/error.h"
#include "gridtopo/core/option_schema.h"
#include "gridtopo/session/option_table.h"

using namespace gridtopo;
using session::OptionEntry;
using session::OptionTable;

namespace {
/// Keys of every type, plus one key in a second section ("<section>.io").
struct DemoOptions : public mrpt::config::CLoadableOptions {
  int particles = 30;
  double resolution = 0.05;
  bool enabled = true;
  std::string mode = "informed";
  std::string label = "x";
  int buffer = 8;  // in [<section>.io]

  static const OptionSchema<DemoOptions>& main() {
    static const OptionSchema<DemoOptions> s =
        OptionSchema<DemoOptions>("DemoOptions")
            .add("particles", &DemoOptions::particles, OptionRange::atLeast(1), "", "number of particles")
            .add("resolution", &DemoOptions::resolution, OptionRange::above(0), "m", "cell size")
            .add("enabled", &DemoOptions::enabled, OptionRange::any(), "", "on")
            .addWords<std::string>("mode", field(&DemoOptions::mode), {{"informed", "informed"}, {"odometry", "odometry"}},
                                   "proposal")
            .add("label", &DemoOptions::label, OptionRange::any(), "", "");
    return s;
  }
  static const OptionSchema<DemoOptions>& io() {
    static const OptionSchema<DemoOptions> s = OptionSchema<DemoOptions>("DemoOptions io").add(
        "buffer", &DemoOptions::buffer, OptionRange::closed(1, 64), "", "buffer size");
    return s;
  }
  static std::vector<OptionSection> describe(const DemoOptions& o) {
    return {{"demo", main().describe(o)}, {"demo.io", io().describe(o)}};
  }
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s) override {
    main().load(*this, c, s);
    io().load(*this, c, s + ".io");
  }
};

DemoOptions changed() {
  DemoOptions o;
  o.particles = 12;
  o.mode = "odometry";
  o.resolution = 0.1;
  return o;
}
}  // namespace

TEST(OptionTable, EntriesHoldValuesDefaultsTypesRangesAndHelp) {
  const OptionTable t = OptionTable::fromSections(DemoOptions::describe(changed()));
  ASSERT_EQ(t.entries().size(), 6u);
  const auto* p = t.find("demo", "particles");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->value, "12");
  EXPECT_EQ(p->default_value, "30");
  EXPECT_EQ(p->type, OptionEntry::Type::Int);
  EXPECT_EQ(p->help, "number of particles");
  EXPECT_EQ(p->range, ">= 1");
  const auto* r = t.find("demo", "resolution");
  EXPECT_EQ(r->type, OptionEntry::Type::Double);
  EXPECT_EQ(r->value, "0.10000000000000001");  // exact: loads back to the same double
  EXPECT_EQ(r->unit, "m");
  EXPECT_EQ(t.find("demo", "enabled")->type, OptionEntry::Type::Bool);
  EXPECT_EQ(t.find("demo", "enabled")->value, "true");
  const auto* m = t.find("demo", "mode");
  EXPECT_EQ(m->type, OptionEntry::Type::Choice);
  EXPECT_EQ(m->value, "odometry");
  EXPECT_EQ(m->default_value, "informed");
  EXPECT_EQ(m->words, (std::vector<std::string>{"informed", "odometry"}));
  EXPECT_EQ(t.find("demo", "label")->type, OptionEntry::Type::String);
  const auto* b = t.find("demo.io", "buffer");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->type, OptionEntry::Type::Int);
  EXPECT_EQ(b->value, "8");
  EXPECT_EQ(b->range, "[1, 64]");
  // Unknown keys and keys of another section are not found.
  EXPECT_EQ(t.find("demo", "buffer"), nullptr);
  EXPECT_EQ(t.find("demo.io", "particles"), nullptr);
  EXPECT_EQ(t.find("other", "particles"), nullptr);
}

TEST(OptionTable, SetTrimsAndRefusesUnknownKeys) {
  OptionTable t = OptionTable::fromSections(DemoOptions::describe(DemoOptions{}));
  EXPECT_TRUE(t.set("demo", "particles", "  7 \t"));
  EXPECT_EQ(t.find("demo", "particles")->value, "7");
  EXPECT_EQ(t.find("demo", "particles")->default_value, "30");  // defaults stay
  EXPECT_FALSE(t.set("demo", "nope", "1"));
  EXPECT_FALSE(t.set("demo.io", "particles", "1"));
  EXPECT_EQ(t.entries().size(), 6u);  // set never adds
}

TEST(OptionTable, ApplyToLoadsThroughTheStructAndItsValidation) {
  OptionTable t = OptionTable::fromSections(DemoOptions::describe(DemoOptions{}));
  ASSERT_TRUE(t.set("demo", "particles", "5"));
  ASSERT_TRUE(t.set("demo", "enabled", "false"));
  ASSERT_TRUE(t.set("demo", "mode", "odometry"));
  ASSERT_TRUE(t.set("demo.io", "buffer", "64"));
  DemoOptions o;
  t.applyTo(o, "demo");
  EXPECT_EQ(o.particles, 5);
  EXPECT_FALSE(o.enabled);
  EXPECT_EQ(o.mode, "odometry");
  EXPECT_EQ(o.buffer, 64);
  EXPECT_DOUBLE_EQ(o.resolution, 0.05);

  // A malformed value: the struct's InputError naming section and key.
  t.set("demo", "particles", "2.5");
  try {
    t.applyTo(o, "demo");
    FAIL() << "2.5 accepted as an integer";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "[demo] particles");
    EXPECT_EQ(std::string(e.what()), "<ini>: [demo] particles: cannot parse '2.5' as an integer");
  }
  // Well-formed values out of range, and a word not in the list.
  t.set("demo", "particles", "0");
  try {
    t.applyTo(o, "demo");
    FAIL() << "0 particles accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "<ini>: [demo] particles: must be >= 1, got 0");
  }
  t.set("demo", "particles", "3");
  t.set("demo.io", "buffer", "65");
  EXPECT_THROW(t.applyTo(o, "demo"), InputError);
  t.set("demo.io", "buffer", "4");
  t.set("demo", "mode", "greedy");
  EXPECT_THROW(t.applyTo(o, "demo"), InputError);
}

TEST(OptionTable, ToIniWritesSectionsHelpAndValuesAndReadsBack) {
  const OptionTable t = OptionTable::fromSections(DemoOptions::describe(changed()));
  const std::string ini = t.toIni();
  EXPECT_EQ(ini,
            "# written by gridtopo-gui\n"
            "\n[demo]\n"
            "# number of particles\n"
            "particles = 12\n"
            "# cell size\n"
            "resolution = 0.10000000000000001\n"
            "# on\n"
            "enabled = true\n"
            "# proposal\n"
            "mode = odometry\n"
            "label = x\n"
            "\n[demo.io]\n"
            "# buffer size\n"
            "buffer = 8\n")
      << ini;
  // The text loads back into the struct with the same values.
  DemoOptions o;
  mrpt::config::CConfigFileMemory cfg;
  cfg.setContent(ini);
  o.loadFromConfigFile(cfg, "demo");
  EXPECT_EQ(o.particles, 12);
  EXPECT_EQ(o.mode, "odometry");
  EXPECT_EQ(o.resolution, 0.1);
}
