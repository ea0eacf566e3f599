// The shared command-line steps of the apps whose run is an INI file (core/run_args.h).
#include <gtest/gtest.h>

#include <vector>

#include "gridtopo/core/run_args.h"

using namespace gridtopo;

namespace {
struct Line {
  // TCLAP remembers in a static that a command line has an optional positional argument; each Line is a new one.
  bool fresh = (TCLAP::OptionalUnlabeledTracker::alreadyOptional() = false);
  TCLAP::CmdLine cmd{"test", ' ', "0"};
  TCLAP::UnlabeledValueArg<std::string> run{"run", "RUN.ini", false, "", "RUN.ini", cmd};
  TCLAP::ValueArg<int> particles{"p", "particles", "n", false, 30, "n", cmd};
  TCLAP::ValueArg<std::string> output{"o", "output", "dir", false, "", "dir", cmd};

  explicit Line(std::vector<std::string> args) {
    cmd.setExceptionHandling(false);
    args.insert(args.begin(), "test");
    cmd.parse(args);
  }
};
}  // namespace

TEST(RunArgs, GivenHoldsOnlyTheFlagsTheUserGave) {
  Line a({"-p", "7"});
  EXPECT_EQ(given(a.particles), std::optional<int>(7));
  EXPECT_EQ(given(a.output), std::nullopt);  // its default "" does not override
  Line b({"-p", "30"});
  EXPECT_EQ(given(b.particles), std::optional<int>(30));  // the default's value, but given
}

TEST(RunArgs, APositionalFlagIsAnUnknownArgument) {
  Line a({"run.ini"});
  EXPECT_EQ(positionalArgument(a.run), "run.ini");
  Line b({"--nonsense"});
  try {
    positionalArgument(b.run);
    FAIL() << "an unknown flag accepted as the RUN.ini";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "--nonsense: unknown argument");
  }
}

TEST(RunArgs, ARunNeedsARunIniOrBothInputAndOutput) {
  EXPECT_NO_THROW(requireRunIniOrInputOutput("run.ini", false, false));
  EXPECT_NO_THROW(requireRunIniOrInputOutput("", true, true));
  EXPECT_THROW(requireRunIniOrInputOutput("", true, false), UsageError);
  EXPECT_THROW(requireRunIniOrInputOutput("", false, true), UsageError);
}
