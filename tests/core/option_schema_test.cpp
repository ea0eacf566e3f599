// OptionSchema on a small struct with a nested member: load (strict parsing, ranges, words, rules, the file and key in
// errors), save (loadable, 17 digits, table order), dump, keys, describe and the help text.
#include <gtest/gtest.h>

#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/scratch.h"
#include "gridtopo/core/option_schema.h"

using namespace gridtopo;
namespace fs = std::filesystem;

namespace {
enum class Mode { Fast, Exact };
struct Inner {
  float gain = 0.85f;
};
struct Demo {
  int particles = 30;
  double spread = 0.15;
  bool enabled = true;
  std::string name = "demo";
  unsigned long seed = 1;
  Mode mode = Mode::Fast;
  Inner inner;
  double lo = -1, hi = 1;
};

const OptionSchema<Demo>& schema() {
  using R = OptionRange;
  static const OptionSchema<Demo> s =
      OptionSchema<Demo>("Demo")
          .add("particles", &Demo::particles, R::closed(1, 100000), "", "number of particles")
          .add("spread", &Demo::spread, R::leftOpen(0, 10), "m", "spread")
          .add("enabled", &Demo::enabled, R::any(), "", "on or off")
          .add("name", &Demo::name, R::any(), "", "a name")
          .add("seed", &Demo::seed, R::any(), "", "random seed")
          .addWords("mode", &Demo::mode, {{"fast", Mode::Fast}, {"exact", Mode::Exact}}, "how")
          .add("inner_gain", field(&Demo::inner, &Inner::gain), R::above(0), "", "nested")
          .add("lo", &Demo::lo, R::below(0), "", "lower")
          .add("hi", &Demo::hi, R::atLeast(0), "", "upper")
          .rule("hi", [](const Demo& d) -> std::optional<std::string> {
            if (d.hi > -d.lo) return std::string("must not exceed -lo");
            return std::nullopt;
          });
  return s;
}

std::string loadError(const std::string& body) {
  mrpt::config::CConfigFileMemory cfg;
  cfg.setContent("[d]\n" + body + "\n");
  Demo d;
  try {
    schema().load(d, cfg, "d");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(OptionRange, ContainsAndText) {
  EXPECT_EQ(OptionRange::closed(1, 100000).text(), "[1, 100000]");
  EXPECT_EQ(OptionRange::leftOpen(0, 10).text(), "(0, 10]");
  EXPECT_EQ(OptionRange::rightOpen(0, 1.5).text(), "[0, 1.5)");
  EXPECT_EQ(OptionRange::atLeast(0).text(), ">= 0");
  EXPECT_EQ(OptionRange::above(0).text(), "> 0");
  EXPECT_EQ(OptionRange::below(0).text(), "< 0");
  EXPECT_EQ(OptionRange::any().text(), "");
  EXPECT_TRUE(OptionRange::leftOpen(0, 10).contains(10));
  EXPECT_FALSE(OptionRange::leftOpen(0, 10).contains(0));
  EXPECT_FALSE(OptionRange::rightOpen(0, 1.5).contains(1.5));
  EXPECT_TRUE(OptionRange::rightOpen(0, 1.5).contains(0));
  EXPECT_FALSE(OptionRange::any().contains(std::nan("")));
  EXPECT_FALSE(OptionRange::atLeast(0).contains(HUGE_VAL));
  EXPECT_EQ(shortestText(0.15), "0.15");
  EXPECT_EQ(shortestText(100000.0), "100000");
  EXPECT_EQ(shortestText(0.0349066), "0.0349066");
  EXPECT_EQ(shortestText(1e-20), "1e-20");
  EXPECT_EQ(shortestText(0.85f), "0.85");
}

TEST(OptionSchema, LoadsEveryKeyOfItsSectionAndKeepsTheOthers) {
  mrpt::config::CConfigFileMemory cfg;
  cfg.setContent(std::string("[d]\nparticles = 8   ; comment\nspread = 2.5\nenabled = false\nname = x y\n"
                             "seed = 123456789012\nmode = exact\ninner_gain = 0.5\n[other]\nlo = -7\n"));
  Demo d;
  schema().load(d, cfg, "d");
  EXPECT_EQ(d.particles, 8);
  EXPECT_EQ(d.spread, 2.5);
  EXPECT_FALSE(d.enabled);
  EXPECT_EQ(d.name, "x y");
  EXPECT_EQ(d.seed, 123456789012UL);
  EXPECT_EQ(d.mode, Mode::Exact);
  EXPECT_EQ(d.inner.gain, 0.5f);
  EXPECT_EQ(d.lo, -1);  // [other] is not [d]
}

TEST(OptionSchema, BadValuesNameTheFileSectionKeyAndRange) {
  EXPECT_EQ(loadError("particles = 0"), "<ini>: [d] particles: must be in [1, 100000], got 0");
  EXPECT_EQ(loadError("particles = 2.5"), "<ini>: [d] particles: cannot parse '2.5' as an integer");
  EXPECT_EQ(loadError("spread = 0"), "<ini>: [d] spread: must be in (0, 10], got 0");
  EXPECT_EQ(loadError("spread = nan"), "<ini>: [d] spread: cannot parse 'nan' as a finite number");
  EXPECT_EQ(loadError("enabled = maybe"), "<ini>: [d] enabled: cannot parse 'maybe' as a boolean (true/false)");
  EXPECT_EQ(loadError("seed = -3"), "<ini>: [d] seed: cannot parse '-3' as a non-negative integer");
  EXPECT_EQ(loadError("mode = slow"), "<ini>: [d] mode: must be fast or exact");
  EXPECT_EQ(loadError("inner_gain = 0"), "<ini>: [d] inner_gain: must be > 0, got 0");
  EXPECT_EQ(loadError("lo = 0"), "<ini>: [d] lo: must be < 0, got 0");
  EXPECT_EQ(loadError("hi = 2"), "<ini>: [d] hi: must not exceed -lo");  // the rule between keys
  EXPECT_EQ(loadError("hi = 2\nlo = -2"), "");
  // A file-backed config names its file.
  const fs::path p = test::scratch("option_schema") / "bad.ini";
  std::ofstream(p) << "[d]\nparticles = -1\n";
  Demo d;
  try {
    schema().load(d, mrpt::config::CConfigFile(p.string()), "d");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), p.string());
    EXPECT_EQ(e.field(), "[d] particles");
  }
}

TEST(OptionSchema, SavesEveryKeyInTableOrderAndLoadsBackExactly) {
  Demo d;
  d.particles = 7;
  d.spread = 0.1 + 0.2;  // not a short decimal
  d.enabled = false;
  d.name = "n";
  d.seed = 18446744073709551615UL;
  d.mode = Mode::Exact;
  d.inner.gain = 0.3f;
  d.lo = -5;
  d.hi = 4;
  const std::string ini = schema().ini(d, "d");
  EXPECT_EQ(ini,
            "[d]\nparticles = 7\nspread = 0.30000000000000004\nenabled = false\nname = n\n"
            "seed = 18446744073709551615\nmode = exact\ninner_gain = 0.30000001192092896\nlo = -5\nhi = 4\n");
  mrpt::config::CConfigFileMemory cfg;
  cfg.setContent(ini);
  Demo back;
  schema().load(back, cfg, "d");
  EXPECT_EQ(schema().ini(back, "d"), ini);
  EXPECT_EQ(back.spread, d.spread);
  EXPECT_EQ(back.inner.gain, d.inner.gain);
  EXPECT_EQ(back.seed, d.seed);
  EXPECT_EQ(schema().keys(),
            (std::vector<std::string>{"particles", "spread", "enabled", "name", "seed", "mode", "inner_gain", "lo", "hi"}));
}

TEST(OptionSchema, DumpDescribeAndHelp) {
  Demo d;
  d.particles = 8;
  std::ostringstream dump;
  schema().dump(d, dump);
  EXPECT_EQ(dump.str().substr(0, dump.str().find('\n')), "----------- [Demo] ------------");
  EXPECT_NE(dump.str().find("\nparticles  = 8\n"), std::string::npos) << dump.str();
  EXPECT_NE(dump.str().find("\nmode       = fast\n"), std::string::npos) << dump.str();

  const auto desc = schema().describe(d);
  ASSERT_EQ(desc.size(), 9u);
  EXPECT_EQ(desc[0].key, "particles");
  EXPECT_EQ(desc[0].type, OptionType::Int);
  EXPECT_EQ(desc[0].value, "8");
  EXPECT_EQ(desc[0].default_value, "30");
  EXPECT_EQ(desc[0].range, "[1, 100000]");
  EXPECT_EQ(desc[1].type, OptionType::Real);
  EXPECT_EQ(desc[1].unit, "m");
  EXPECT_EQ(desc[2].type, OptionType::Bool);
  EXPECT_EQ(desc[3].type, OptionType::Text);
  EXPECT_EQ(desc[5].type, OptionType::Word);
  EXPECT_EQ(desc[5].words, (std::vector<std::string>{"fast", "exact"}));

  const std::string help = schema().help("d");
  EXPECT_EQ(help.substr(0, help.find('\n')), "[d]");
  // One line per key: "key = default" (reals in their shortest text) padded to one column, then type, range, unit, help.
  EXPECT_NE(help.find("\n  particles = 30     (int [1, 100000]) number of particles\n"), std::string::npos) << help;
  EXPECT_NE(help.find("\n  spread = 0.15      (real (0, 10] m) spread\n"), std::string::npos) << help;
  EXPECT_NE(help.find("\n  mode = fast        (fast | exact) how\n"), std::string::npos) << help;
  EXPECT_NE(help.find("\n  inner_gain = 0.85  (real > 0) nested\n"), std::string::npos) << help;
  EXPECT_EQ(desc[6].default_value, "0.85000002384185791");  // what save() writes: loads back to the same float
  EXPECT_EQ(desc[6].default_shown, "0.85");
}
