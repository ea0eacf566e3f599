// The region-correction rules R0-R3, each on a minimal label image, and the options' validation.
#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "gridtopo/core/error.h"
#include "gridtopo/topology/correction.h"
#include "gridtopo/topology/regions.h"

using namespace gridtopo;
using namespace gridtopo::topology;

namespace {
constexpr unsigned char R = 0, C = 1, D = 2, N = 255;  // room, corridor, doorway, no label
constexpr double kRes = 0.1;                            // 0.01 m² per cell

/// Every rule off; tests switch on the one they exercise.
CorrectionOptions rulesOff() {
  CorrectionOptions o;
  o.min_place_area = 0;
  o.min_room_area = o.min_corridor_area = o.min_doorway_area = 0;
  o.doorways_must_separate = false;
  o.max_doorway_area = 0;
  o.junctions = false;
  return o;
}

cv::Mat fill(int rows, int cols, unsigned char v) { return cv::Mat(rows, cols, CV_8U, cv::Scalar(v)); }

bool same(const cv::Mat& a, const cv::Mat& b) { return a.size() == b.size() && cv::countNonZero(a != b) == 0; }
}  // namespace

TEST(Correction, AllRulesOffChangesNothingInOnePass) {
  const cv::Mat l = (cv::Mat_<unsigned char>(2, 4) << R, C, D, N, D, R, 9, C);
  CorrectionStats st;
  const cv::Mat out = correctRegions(l, kRes, rulesOff(), &st);
  EXPECT_TRUE(same(out, l));
  EXPECT_EQ(st.passes, 1);
  EXPECT_EQ(st.patches_removed + st.small_merged + st.doorways_not_separating + st.doorways_oversized, 0);
}

TEST(Correction, R0SmallPatchesOfAnyLabelsLoseTheirLabel) {
  cv::Mat l = fill(10, 12, N);
  l(cv::Rect(0, 0, 5, 5)).setTo(R);  // 25 cells = 0.25 m²: kept
  l.at<unsigned char>(8, 1) = R;     // 2 cells, room + corridor touching diagonally: one patch of 0.02 m²
  l.at<unsigned char>(9, 2) = C;
  l(cv::Rect(8, 0, 2, 5)).setTo(C);  // corridor 2 x 5 next to a doorway 2 x 5: one patch of 0.2 m², kept
  l(cv::Rect(10, 0, 2, 5)).setTo(D);
  l.at<unsigned char>(9, 11) = D;    // a lone cell
  CorrectionOptions o = rulesOff();
  o.min_place_area = 0.1;
  CorrectionStats st;
  const cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.patches_removed, 2);
  EXPECT_EQ(out.at<unsigned char>(8, 1), N);
  EXPECT_EQ(out.at<unsigned char>(9, 2), N);
  EXPECT_EQ(out.at<unsigned char>(9, 11), N);
  EXPECT_EQ(cv::countNonZero(out == R), 25);
  EXPECT_EQ(cv::countNonZero(out == C), 10);  // the mixed patch is big enough as a whole
  EXPECT_EQ(cv::countNonZero(out == D), 10);
  // The input is not modified.
  EXPECT_EQ(l.at<unsigned char>(8, 1), R);
  // Exactly at the threshold: kept (only smaller patches go).
  o.min_place_area = 0.02;
  EXPECT_EQ(correctRegions(l, kRes, o).at<unsigned char>(8, 1), R);
}

TEST(Correction, R1SmallRegionTakesTheLabelOfItsLongestBorderNeighbour) {
  // A room (cols 0-3) and a doorway (cols 5-9) with a one-cell-wide corridor between them (col 4).
  // Corridor-room border: 7 cell pairs, corridor-doorway: 5 (the doorway's bottom-left cell is missing).
  cv::Mat l = fill(3, 10, R);
  l.col(4).setTo(C);
  l.colRange(5, 10).setTo(D);
  l.at<unsigned char>(2, 5) = N;
  CorrectionOptions o = rulesOff();
  o.min_room_area = o.min_corridor_area = 0.1;  // the corridor (0.03 m²) is small, the room (0.12 m²) is not
  o.min_doorway_area = 0.01;
  CorrectionStats st;
  cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.small_merged, 1);
  EXPECT_EQ(st.passes, 2);  // one pass changes, the next finds nothing
  for (int r = 0; r < 3; ++r) EXPECT_EQ(out.at<unsigned char>(r, 4), R) << r;
  EXPECT_EQ(cv::countNonZero(out == D), 14);
  // Mirror the missing cell to the room's side: now the doorway has the longer border.
  l.at<unsigned char>(2, 5) = D;
  l.at<unsigned char>(2, 3) = N;
  out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.small_merged, 1);
  for (int r = 0; r < 3; ++r) EXPECT_EQ(out.at<unsigned char>(r, 4), D) << r;
}

TEST(Correction, R1UsesEachLabelsOwnMinimumAndKeepsIsolatedRegions) {
  cv::Mat l = fill(6, 12, N);
  l(cv::Rect(0, 0, 2, 2)).setTo(C);  // isolated small corridor: nothing to merge into
  l(cv::Rect(4, 0, 8, 6)).setTo(R);  // room of 48 cells with a doorway of 2 cells in it
  l(cv::Rect(6, 2, 1, 2)).setTo(D);
  CorrectionOptions o = rulesOff();
  o.min_corridor_area = 1.0;
  o.min_room_area = 0.1;
  o.min_doorway_area = 0.03;  // 0.02 m² is too small for a doorway
  CorrectionStats st;
  cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.small_merged, 1);
  EXPECT_EQ(out.at<unsigned char>(2, 6), R);
  EXPECT_EQ(cv::countNonZero(out == C), 4);  // isolated: kept
  o.min_doorway_area = 0.02;                 // exactly its area: kept
  out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.small_merged, 0);
  EXPECT_EQ(out.at<unsigned char>(2, 6), D);
}

TEST(Correction, R1TwoSmallNeighboursMergeIntoTheLargerOnesLabel) {
  // A room of 4 cells next to a corridor of 2, nothing else around: both are small. The smaller merges into the
  // larger (which waits that pass), then the whole is one isolated region and is kept.
  cv::Mat l = fill(4, 5, N);
  l(cv::Rect(0, 0, 2, 2)).setTo(R);
  l(cv::Rect(2, 0, 1, 2)).setTo(C);
  CorrectionOptions o = rulesOff();
  o.min_room_area = o.min_corridor_area = 1.0;
  CorrectionStats st;
  const cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(cv::countNonZero(out == R), 6);
  EXPECT_EQ(cv::countNonZero(out == C), 0);
  EXPECT_EQ(st.small_merged, 1);
  EXPECT_EQ(st.passes, 2);
}

TEST(Correction, R1TwoSmallNeighboursOfEqualSizeMergeInsteadOfSwapping) {
  // A room of 4 cells next to a corridor of 4, isolated: each is the other's only (and longest-border)
  // neighbour. They must end as one label; swapping labels every pass never settles.
  cv::Mat l = fill(4, 6, N);
  l(cv::Rect(0, 0, 2, 2)).setTo(R);
  l(cv::Rect(2, 0, 2, 2)).setTo(C);
  CorrectionOptions o = rulesOff();
  o.min_room_area = o.min_corridor_area = 1.0;
  CorrectionStats st;
  const cv::Mat out = correctRegions(l, kRes, o, &st);
  const int rooms = cv::countNonZero(out == R), corridors = cv::countNonZero(out == C);
  EXPECT_TRUE((rooms == 8 && corridors == 0) || (rooms == 0 && corridors == 8)) << rooms << " " << corridors;
  EXPECT_EQ(st.small_merged, 1);
  EXPECT_EQ(st.passes, 2);
}

TEST(Correction, R2DoorwaysThatJoinNothingTakeTheirNeighboursLabel) {
  // Rooms A (cols 0-3) and B (cols 5-8) joined by doorway D1 (col 4, rows 1-3); doorway D2 (col 9, rows 1-3) is a
  // stub on B's far side.
  cv::Mat l = fill(5, 11, N);
  l.colRange(0, 4).setTo(R);
  l.colRange(5, 9).setTo(R);
  l(cv::Rect(4, 1, 1, 3)).setTo(D);
  l(cv::Rect(9, 1, 1, 3)).setTo(D);
  l.at<unsigned char>(2, 10) = D;  // part of D2
  CorrectionOptions o = rulesOff();
  o.doorways_must_separate = true;
  CorrectionStats st;
  cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.doorways_not_separating, 1);
  EXPECT_EQ(st.small_merged, 0);
  EXPECT_EQ(st.passes, 2);
  for (int r = 1; r <= 3; ++r) {
    EXPECT_EQ(out.at<unsigned char>(r, 4), D) << r;  // separates A and B
    EXPECT_EQ(out.at<unsigned char>(r, 9), R) << r;  // joins nothing
  }
  EXPECT_EQ(out.at<unsigned char>(2, 10), R);
  // Off: the stub stays.
  o.doorways_must_separate = false;
  out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.doorways_not_separating, 0);
  EXPECT_EQ(out.at<unsigned char>(2, 9), D);
  // A doorway touching no region at all has no label to take: kept.
  o.doorways_must_separate = true;
  cv::Mat lone = fill(3, 3, N);
  lone.at<unsigned char>(1, 1) = D;
  EXPECT_TRUE(same(correctRegions(lone, kRes, o, &st), lone));
  EXPECT_EQ(st.doorways_not_separating, 0);
}

TEST(Correction, R2WaitsForR1AndAStubNextToACorridorTakesTheCorridorsLabel) {
  // A doorway stub on a corridor that also touches a small room: R1 first merges the small room into the doorway
  // (4 border pairs against 2 diagonal ones with the corridor), then the doorway, touching only the corridor,
  // becomes corridor.
  cv::Mat l = fill(6, 8, C);
  l(cv::Rect(3, 3, 2, 1)).setTo(D);  // doorway at rows 3, cols 3-4
  l(cv::Rect(3, 4, 2, 2)).setTo(R);  // room below it (4 cells), walled off from the corridor
  l(cv::Rect(2, 4, 1, 2)).setTo(N);
  l(cv::Rect(5, 4, 1, 2)).setTo(N);
  CorrectionOptions o = rulesOff();
  o.min_room_area = 0.1;
  o.doorways_must_separate = true;
  CorrectionStats st;
  const cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.small_merged, 1);
  EXPECT_EQ(st.doorways_not_separating, 1);
  EXPECT_EQ(st.passes, 3);
  EXPECT_EQ(cv::countNonZero(out == C), 6 * 8 - 4);  // everything but the four wall cells
}

TEST(Correction, R3OversizedDoorwaysAreNotDoors) {
  // Rooms A and B joined by a doorway of 3 cells (0.03 m²).
  cv::Mat l = fill(5, 9, N);
  l.colRange(0, 4).setTo(R);
  l.colRange(5, 9).setTo(R);
  l(cv::Rect(4, 1, 1, 3)).setTo(D);
  CorrectionOptions o = rulesOff();
  o.doorways_must_separate = true;
  o.max_doorway_area = 0.035;  // larger than its area: a door
  CorrectionStats st;
  cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.doorways_oversized, 0);
  EXPECT_EQ(cv::countNonZero(out == D), 3);
  o.max_doorway_area = 0.025;
  out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.doorways_oversized, 1);
  EXPECT_EQ(st.doorways_not_separating, 0);
  EXPECT_EQ(cv::countNonZero(out == D), 0);
  EXPECT_EQ(cv::countNonZero(out == R), 5 * 8 + 3);
  o.max_doorway_area = 0;  // 0 = off
  out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.doorways_oversized, 0);
  EXPECT_EQ(cv::countNonZero(out == D), 3);
}

TEST(Correction, R3OversizedDoorwayTakesTheLongestBorderNeighboursLabel) {
  // A doorway (col 4) between a room (cols 0-3) and a corridor (cols 5-8) whose border is shorter (a wall cell).
  cv::Mat l = fill(5, 9, R);
  l.col(4).setTo(D);
  l.colRange(5, 9).setTo(C);
  l.at<unsigned char>(0, 5) = N;
  CorrectionOptions o = rulesOff();
  o.doorways_must_separate = true;
  o.max_doorway_area = 0.01;
  CorrectionStats st;
  const cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.doorways_oversized, 1);
  for (int r = 0; r < 5; ++r) EXPECT_EQ(out.at<unsigned char>(r, 4), R) << r;
}

// R4: a corridor 1 m wide runs west and east of a junction that reads as room together with the office that opens
// onto it (one room region). The corridor runs on through the junction; the office stays room.
TEST(Correction, R4CorridorsRunOnThroughAJunctionReadAsRoom) {
  cv::Mat l = fill(40, 100, N);
  l(cv::Rect(0, 25, 40, 10)).setTo(C);   // west corridor, rows 25..34
  l(cv::Rect(60, 25, 40, 10)).setTo(C);  // east corridor
  l(cv::Rect(40, 25, 20, 10)).setTo(R);  // the junction, read as room
  l(cv::Rect(42, 2, 16, 23)).setTo(R);   // the office above it, 1.6 m x 2.3 m, open onto the junction
  CorrectionOptions o = rulesOff();
  o.junctions = true;
  CorrectionStats st;
  const cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.junctions, 1);
  // The junction's cells in line with the corridor are corridor; the office's upper part stays room.
  const int junction_corridor = cv::countNonZero(out(cv::Rect(40, 25, 20, 10)) == C);
  EXPECT_GE(junction_corridor, 180) << junction_corridor << " of 200";
  EXPECT_EQ(cv::countNonZero(out(cv::Rect(42, 2, 16, 15)) == R), 16 * 15);
  // West and east are one corridor region now.
  const RegionMap rm = extractRegions(out, kRes);
  EXPECT_EQ(rm.ids.at<int>(30, 0), rm.ids.at<int>(30, 99));
  // Nothing else changed: every cell that was not room keeps its label.
  EXPECT_EQ(cv::countNonZero((l != R) & (out != l)), 0);

  // A passage wider than junction_max_half_width (here 0.3 m against the corridor's 0.5 m) stays room.
  o.junction_max_half_width = 0.3;
  EXPECT_TRUE(same(correctRegions(l, kRes, o, &st), l));
  EXPECT_EQ(st.junctions, 0);
  // On by default.
  EXPECT_TRUE(CorrectionOptions().junctions);
  // A room region that touches one corridor region only is left alone.
  cv::Mat one = l.clone();
  one(cv::Rect(60, 25, 40, 10)).setTo(N);
  o.junction_max_half_width = 1.25;
  EXPECT_TRUE(same(correctRegions(one, kRes, o, &st), one));
}

TEST(Correction, DisabledOrNoPassesLimitTheWork) {
  cv::Mat l = fill(3, 10, R);
  l.col(4).setTo(C);
  l.at<unsigned char>(0, 9) = N;
  l.at<unsigned char>(2, 9) = D;  // a one-cell doorway in the room
  CorrectionOptions o;            // defaults: every rule on
  o.enabled = false;
  CorrectionStats st;
  st.passes = 99;
  EXPECT_TRUE(same(correctRegions(l, kRes, o, &st), l));
  EXPECT_EQ(st.passes, 0);
  EXPECT_EQ(st.patches_removed, 0);
  // max_passes = 0: only R0 runs (the whole image, 0.29 m², is below the default 0.5 m²).
  o.enabled = true;
  o.max_passes = 0;
  const cv::Mat out = correctRegions(l, kRes, o, &st);
  EXPECT_EQ(st.passes, 0);
  EXPECT_EQ(st.patches_removed, 1);
  EXPECT_EQ(cv::countNonZero(out == N), 30);
  // Stats are optional.
  EXPECT_NO_THROW(correctRegions(l, kRes, o));
}

TEST(Correction, OptionsAreValidatedWithTheKeyName) {
  CorrectionOptions o;
  EXPECT_NO_THROW(o.validate());
  o.min_room_area = -1;
  try {
    o.validate();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "<options>: [correction] min_room_area: must be >= 0, got -1");
    EXPECT_EQ(e.field(), "[correction] min_room_area");
  }
  // correctRegions refuses bad options too.
  EXPECT_THROW(correctRegions(fill(2, 2, R), kRes, o), InputError);
  o = CorrectionOptions{};
  o.max_doorway_area = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(o.validate(), InputError);
  o = CorrectionOptions{};
  o.min_place_area = std::numeric_limits<double>::infinity();
  EXPECT_THROW(o.validate(), InputError);
  o = CorrectionOptions{};
  o.max_passes = 1001;
  try {
    o.validate("x.ini", "x");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "x.ini: [x] max_passes: must be in [0, 1000], got 1001");
  }
  o.max_passes = 1000;
  EXPECT_NO_THROW(o.validate());
  o.max_passes = -1;
  EXPECT_THROW(o.validate(), InputError);
}

TEST(Correction, LoadFromConfigReadsEveryKeyAndNamesBadOnes) {
  mrpt::config::CConfigFileMemory cfg;
  cfg.setContent(std::string("[corr]\n"
                             "enabled = false\n"
                             "min_place_area = 0.25\n"
                             "min_room_area = 3\n"
                             "min_corridor_area = 2.5\n"
                             "min_doorway_area = 0.2\n"
                             "doorways_must_separate = false\n"
                             "max_doorway_area = 0\n"
                             "max_passes = 7\n"));
  CorrectionOptions o;
  o.loadFromConfigFile(cfg, "corr");
  EXPECT_FALSE(o.enabled);
  EXPECT_DOUBLE_EQ(o.min_place_area, 0.25);
  EXPECT_DOUBLE_EQ(o.min_room_area, 3);
  EXPECT_DOUBLE_EQ(o.min_corridor_area, 2.5);
  EXPECT_DOUBLE_EQ(o.min_doorway_area, 0.2);
  EXPECT_FALSE(o.doorways_must_separate);
  EXPECT_DOUBLE_EQ(o.max_doorway_area, 0);
  EXPECT_EQ(o.max_passes, 7);
  std::ostringstream dump;
  o.dumpToTextStream(dump);
  EXPECT_NE(dump.str().find("max_passes              = 7\n"), std::string::npos) << dump.str();

  // Missing keys keep their values.
  CorrectionOptions d;
  d.loadFromConfigFile(cfg, "other");
  EXPECT_TRUE(d.enabled);
  EXPECT_EQ(d.max_passes, 20);

  mrpt::config::CConfigFileMemory bad;
  bad.setContent(std::string("[corr]\nmax_passes = 2.5\n"));
  try {
    CorrectionOptions b;
    b.loadFromConfigFile(bad, "corr");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "<ini>: [corr] max_passes: cannot parse '2.5' as an integer");
  }
  mrpt::config::CConfigFileMemory negative;
  negative.setContent(std::string("[corr]\nmin_doorway_area = -0.1\n"));
  try {
    CorrectionOptions b;
    b.loadFromConfigFile(negative, "corr");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "<ini>: [corr] min_doorway_area: must be >= 0, got -0.1");
  }
}
