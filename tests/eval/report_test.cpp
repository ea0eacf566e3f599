// The text, JSON and per-relation outputs of a relations-metric result, character for character.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "gridtopo/eval/report.h"

using namespace gridtopo::eval;

namespace {
ErrorStats stats(std::size_t n, double mean, double sd, double mn, double mx) {
  ErrorStats s;
  s.count = n, s.mean = mean, s.std = sd, s.min = mn, s.max = mx;
  return s;
}

RelationsResult result() {
  RelationsResult r;
  r.translational = stats(3, 0.1234567, 0.01, 0.1, 0.15);
  r.translational_squared = stats(3, 0.0153, 0.00004, 0.01, 0.0225);
  r.rotational = stats(3, 1.23456, 0.5, 0.25, 2.0);
  r.rotational_squared = stats(3, 1.75, 0.125, 0.0625, 4.0);
  r.endpoints_direct = 5;
  r.endpoints_corrected = 1;
  r.max_gap = 0.25;
  r.local.translational = stats(2, 0.016, 0.001, 0.015, 0.017);
  r.local.rotational = stats(2, 0.554, 0.1, 0.5, 0.6);
  r.revisit.translational = stats(1, 0.02204, 0, 0.02204, 0.02204);
  r.revisit.rotational = stats(1, 0.7, 0, 0.7, 0.7);
  return r;
}
}  // namespace

TEST(Report, SummaryLinesAndEndpointCounts) {
  const RelationsResult r = result();
  EXPECT_EQ(formatSummary(r),
            "translational error:   0.1235 ± 0.0100 m   (min 0.1000, max 0.1500, n = 3)\n"
            "translational squared: 0.0153 ± 0.0000 m²   (min 0.0100, max 0.0225, n = 3)\n"
            "rotational error:      1.235 ± 0.500 deg   (min 0.250, max 2.000, n = 3)\n"
            "rotational squared:    1.750 ± 0.125 deg²   (min 0.062, max 4.000, n = 3)\n"
            "relation endpoints: 5 with an estimate in reach, 1 corrected by odometry; largest time gap 0.250 s\n"
            "local (|t2-t1| <= 50 s): 0.0160 m (n=2), 0.55 deg; revisits (> 50 s): 0.0220 m (n=1), 0.70 deg\n");
}

TEST(Report, SummarySplitLineNamesTheSpanAndAnEmptySide) {
  RelationsResult r = result();
  r.revisit_span = 12.5;
  r.revisit = {};
  std::string s = formatSummary(r);
  EXPECT_NE(s.find("\nlocal (|t2-t1| <= 12.5 s): 0.0160 m (n=2), 0.55 deg; revisits (> 12.5 s): none (n=0)\n"),
            std::string::npos)
      << s;
  const std::string j = formatJson(r, {});
  EXPECT_NE(j.find("  \"revisit_span_s\": 12.5,\n"), std::string::npos) << j;
  EXPECT_NE(j.find("  \"revisit\": {\"count\": 0, \"translational_m\": {\"mean\": null, \"std\": null, \"min\": null, "
                   "\"max\": null, \"count\": 0}, \"rotational_deg\": {\"mean\": null, \"std\": null, \"min\": null, "
                   "\"max\": null, \"count\": 0}},\n"),
            std::string::npos)
      << j;
  r.local = {};
  s = formatSummary(r);
  EXPECT_NE(s.find("\nlocal (|t2-t1| <= 12.5 s): none (n=0); revisits (> 12.5 s): none (n=0)\n"), std::string::npos)
      << s;
}

TEST(Report, SummaryNamesInterpolatedAndUncorrectedEndpointsOnlyWhenThereAreAny) {
  RelationsResult r = result();
  r.endpoints_interpolated = 2;
  std::string s = formatSummary(r);
  EXPECT_NE(s.find("1 corrected by odometry, 2 interpolated between estimates; largest"), std::string::npos) << s;
  EXPECT_EQ(s.find("UNCORRECTED"), std::string::npos);
  r.endpoints_uncorrected = 3;
  s = formatSummary(r);
  EXPECT_NE(s.find(", 2 interpolated between estimates, 3 UNCORRECTED (no odometry); largest time gap 0.250 s\n"),
            std::string::npos)
      << s;
  r.endpoints_interpolated = 0;
  s = formatSummary(r);
  EXPECT_NE(s.find("1 corrected by odometry, 3 UNCORRECTED (no odometry); largest"), std::string::npos) << s;
  EXPECT_EQ(s.find("interpolated"), std::string::npos);
}

TEST(Report, JsonHasInfoStatsAndCounts) {
  RelationsResult r = result();
  r.endpoints_interpolated = 2;
  r.endpoints_uncorrected = 4;
  EXPECT_EQ(formatJson(r, {{"estimate", "run.txt"}, {"relations", "ref.relations"}}),
            "{\n"
            "  \"estimate\": \"run.txt\",\n"
            "  \"relations\": \"ref.relations\",\n"
            "  \"translational_m\": {\"mean\": 0.1234567, \"std\": 0.01, \"min\": 0.1, \"max\": 0.15, \"count\": 3},\n"
            "  \"translational_squared_m2\": {\"mean\": 0.0153, \"std\": 4e-05, \"min\": 0.01, \"max\": 0.0225, "
            "\"count\": 3},\n"
            "  \"rotational_deg\": {\"mean\": 1.23456, \"std\": 0.5, \"min\": 0.25, \"max\": 2, \"count\": 3},\n"
            "  \"rotational_squared_deg2\": {\"mean\": 1.75, \"std\": 0.125, \"min\": 0.0625, \"max\": 4, \"count\": 3},\n"
            "  \"endpoints_direct\": 5,\n"
            "  \"endpoints_corrected\": 1,\n"
            "  \"endpoints_interpolated\": 2,\n"
            "  \"endpoints_uncorrected\": 4,\n"
            "  \"revisit_span_s\": 50,\n"
            "  \"local\": {\"count\": 2, \"translational_m\": {\"mean\": 0.016, \"std\": 0.001, \"min\": 0.015, "
            "\"max\": 0.017, \"count\": 2}, \"rotational_deg\": {\"mean\": 0.554, \"std\": 0.1, \"min\": 0.5, "
            "\"max\": 0.6, \"count\": 2}},\n"
            "  \"revisit\": {\"count\": 1, \"translational_m\": {\"mean\": 0.02204, \"std\": null, \"min\": 0.02204, "
            "\"max\": 0.02204, \"count\": 1}, \"rotational_deg\": {\"mean\": 0.7, \"std\": null, \"min\": 0.7, "
            "\"max\": 0.7, \"count\": 1}},\n"
            "  \"largest_time_gap_s\": 0.25\n"
            "}\n");
}

TEST(Report, JsonEscapesStringsAndWritesNullForUndefinedNumbers) {
  RelationsResult r;
  r.translational = stats(1, 0.5, 0.0, 0.5, 0.5);  // one value: no sample std
  r.rotational = stats(0, std::numeric_limits<double>::quiet_NaN(), 0, 0, 0);
  r.max_gap = std::numeric_limits<double>::infinity();
  const std::string j = formatJson(r, {{"a\"b\\c", "line1\nline2\tx\x01y"}});
  EXPECT_NE(j.find("  \"a\\\"b\\\\c\": \"line1\\nline2\\tx\\u0001y\",\n"), std::string::npos) << j;
  EXPECT_NE(j.find("\"translational_m\": {\"mean\": 0.5, \"std\": null, \"min\": 0.5, \"max\": 0.5, \"count\": 1}"),
            std::string::npos)
      << j;
  EXPECT_NE(j.find("\"rotational_deg\": {\"mean\": null, \"std\": null, \"min\": 0, \"max\": 0, \"count\": 0}"),
            std::string::npos)
      << j;
  EXPECT_NE(j.find("\"largest_time_gap_s\": null\n}\n"), std::string::npos) << j;
  // No info: the object starts with the statistics.
  EXPECT_EQ(formatJson(r, {}).rfind("{\n  \"translational_m\": ", 0), 0u);
}

TEST(Report, ErrorsOneLinePerRelationInOrderWithDegrees) {
  RelationsResult r;
  RelationError a;
  a.relation.t1 = 1234.5678;
  a.relation.t2 = 1200.25;  // t2 < t1 is allowed and kept
  a.translational = 0.125;
  a.rotational = M_PI / 2;
  a.gap1 = 0;
  a.gap2 = 0.375;
  RelationError b;
  b.relation.t1 = 1.5;
  b.relation.t2 = 2.5;
  b.translational = 1e-12;
  b.rotational = 0;
  r.errors = {a, b};
  EXPECT_EQ(formatErrors(r),
            "# t1 t2 translational_error_m rotational_error_deg gap1_s gap2_s (relations file order)\n"
            "1234.5678 1200.25 0.125 90 0 0.375\n"
            "1.5 2.5 1e-12 0 0 0\n");
  EXPECT_EQ(formatErrors(RelationsResult{}),
            "# t1 t2 translational_error_m rotational_error_deg gap1_s gap2_s (relations file order)\n");
}

// issue 36 item 8: every key of eval.json once: an info or number key that repeats one is refused.
TEST(Report, JsonRefusesARepeatedKey) {
  RelationsResult r;
  EXPECT_THROW(formatJson(r, {{"a", "x"}}, {{"a", 1.0}}), std::invalid_argument);
  EXPECT_THROW(formatJson(r, {}, {{"largest_time_gap_s", 1.0}}), std::invalid_argument);
  EXPECT_NE(formatJson(r, {{"a", "x"}}, {{"n", 13631}}).find("  \"n\": 13631,\n"), std::string::npos);
}

// Yes/no options are JSON booleans (they were the strings "true" / "false"), after the info, each key once.
TEST(Report, JsonFlagsAreBooleans) {
  RelationsResult r;
  const std::string j = formatJson(r, {{"relations", "x"}}, {{"n", 2}},
                                   {{"odometry_interpolated", true}, {"estimate_interpolated", false}});
  EXPECT_EQ(j.rfind("{\n  \"relations\": \"x\",\n  \"odometry_interpolated\": true,\n"
                    "  \"estimate_interpolated\": false,\n  \"n\": 2,\n",
                    0),
            0u)
      << j;
  EXPECT_THROW(formatJson(r, {{"a", "x"}}, {}, {{"a", true}}), std::invalid_argument);
}
