#include "gridtopo/experiment/sweep.h"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace gridtopo::experiment;

TEST(Sweep, ValuesAndRanges) {
  EXPECT_EQ(parseSweepValues("4 8 15"), (std::vector<std::string>{"4", "8", "15"}));
  EXPECT_EQ(parseSweepValues("1..4"), (std::vector<std::string>{"1", "2", "3", "4"}));
  EXPECT_EQ(parseSweepValues("informed  odometry"), (std::vector<std::string>{"informed", "odometry"}));
  EXPECT_EQ(parseSweepValues("-1..1 7"), (std::vector<std::string>{"-1", "0", "1", "7"}));
  EXPECT_EQ(parseSweepValues("3..3"), (std::vector<std::string>{"3"}));
  EXPECT_EQ(parseSweepValues("1..10").size(), 10u);
}

TEST(Sweep, BadValueListsSayWhy) {
  auto why = [](const std::string& text) {
    try {
      parseSweepValues(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(why(""), "no values");
  EXPECT_EQ(why("5..2"), "range '5..2' runs backwards");
  EXPECT_EQ(why("1..x"), "'1..x' is not a range of integers a..b");
  EXPECT_EQ(why("1.5..3"), "'1.5..3' is not a range of integers a..b");
  EXPECT_EQ(why("1 2 1"), "accepted");  // repeats are for zip groups; checkDistinct refuses them elsewhere
  auto distinct = [](const std::string& text) {
    try {
      checkDistinct(parseSweepValues(text));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(distinct("1 2 1"), "value '1' is listed twice");
  EXPECT_EQ(distinct("1..3 2"), "value '2' is listed twice");
  EXPECT_EQ(distinct("1..3 4"), "accepted");
}

TEST(Sweep, AZipGroupMayRepeatAValueButNotATuple) {
  // The paper's core runs: each proposal with its own particle counts.
  const std::vector<SweepKey> keys = {{"seed", {"1", "2"}},
                                      {"proposal", {"informed", "informed", "hahnel", "hahnel", "hahnel"}},
                                      {"particles", {"4", "8", "4", "8", "250"}}};
  const auto runs = expandSweep(keys, {{"proposal", "particles"}});
  ASSERT_EQ(runs.size(), 10u);
  EXPECT_EQ(runs[4], (Assignment{{"seed", "1"}, {"proposal", "hahnel"}, {"particles", "250"}}));
  EXPECT_EQ(runs[5], (Assignment{{"seed", "2"}, {"proposal", "informed"}, {"particles", "4"}}));
  const std::vector<SweepKey> twice = {{"proposal", {"informed", "hahnel", "informed"}}, {"particles", {"4", "8", "4"}}};
  try {
    expandSweep(twice, {{"proposal", "particles"}});
    FAIL() << "a repeated tuple was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "zip group: 'proposal=informed particles=4' is listed twice");
  }
  // A crossed key with a repeated value is refused by the expansion too.
  EXPECT_THROW(expandSweep({{"seed", {"1", "1"}}}), std::invalid_argument);
}

TEST(Sweep, CartesianProductFirstKeySlowest) {
  const std::vector<SweepKey> keys = {{"proposal", {"informed", "odometry"}}, {"particles", {"4", "8", "15"}},
                                      {"seed", {"1", "2"}}};
  const auto runs = expandSweep(keys);
  ASSERT_EQ(runs.size(), 12u);
  EXPECT_EQ(runs[0], (Assignment{{"proposal", "informed"}, {"particles", "4"}, {"seed", "1"}}));
  EXPECT_EQ(runs[1], (Assignment{{"proposal", "informed"}, {"particles", "4"}, {"seed", "2"}}));
  EXPECT_EQ(runs[2], (Assignment{{"proposal", "informed"}, {"particles", "8"}, {"seed", "1"}}));
  EXPECT_EQ(runs[6], (Assignment{{"proposal", "odometry"}, {"particles", "4"}, {"seed", "1"}}));
  EXPECT_EQ(runs[11], (Assignment{{"proposal", "odometry"}, {"particles", "15"}, {"seed", "2"}}));
  EXPECT_EQ(valueOf(runs[7], "seed"), "2");
  EXPECT_EQ(valueOf(runs[7], "nothing", "x"), "x");
}

TEST(Sweep, ZipGroupsAdvanceTogether) {
  // particles and threads in step, seed crossed with them: 3 x 2 runs, not 3 x 3 x 2.
  const std::vector<SweepKey> keys = {{"particles", {"4", "8", "15"}}, {"seed", {"1", "2"}},
                                      {"threads", {"1", "2", "2"}}};
  const auto runs = expandSweep(keys, {{"particles", "threads"}});
  ASSERT_EQ(runs.size(), 6u);
  // The group sits where its first key is: particles/threads slowest, seed fastest; keys keep their order.
  EXPECT_EQ(runs[0], (Assignment{{"particles", "4"}, {"seed", "1"}, {"threads", "1"}}));
  EXPECT_EQ(runs[1], (Assignment{{"particles", "4"}, {"seed", "2"}, {"threads", "1"}}));
  EXPECT_EQ(runs[2], (Assignment{{"particles", "8"}, {"seed", "1"}, {"threads", "2"}}));
  EXPECT_EQ(runs[5], (Assignment{{"particles", "15"}, {"seed", "2"}, {"threads", "2"}}));
}

TEST(Sweep, BadZipGroupsNameTheKey) {
  const std::vector<SweepKey> keys = {{"particles", {"4", "8"}}, {"seed", {"1", "2", "3"}}, {"threads", {"1", "2"}}};
  auto why = [&](const std::vector<std::vector<std::string>>& zip) {
    try {
      expandSweep(keys, zip);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(why({{"particles", "seed"}}), "zip key 'seed' has 3 values, 'particles' has 2");
  EXPECT_EQ(why({{"particles", "nope"}}), "zip key 'nope' is not a swept key");
  EXPECT_EQ(why({{"particles"}}), "a zip group needs at least two keys");
  EXPECT_EQ(why({{"particles", "threads"}, {"threads", "seed"}}),
            "key 'threads' is in two zip groups or twice in one");
  EXPECT_EQ(why({{"particles", "threads"}}), "accepted");
}

TEST(Sweep, NoKeysIsOneRun) { EXPECT_EQ(expandSweep({}).size(), 1u); }
