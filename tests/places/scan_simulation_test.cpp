#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "gridtopo/core/error.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/scan_simulation.h"
#include "synthetic.h"

using namespace gridtopo::places;

namespace {
// Reference: march along the ray in small steps until a non-free cell (slow, obviously right).
double castRay(const OccupancyImage& occ, cv::Point p, double th) {
  const double step = occ.resolution / 20;
  for (double d = 0;; d += step) {
    const double x = p.x + 0.5 + d / occ.resolution * std::cos(th), y = p.y + 0.5 - d / occ.resolution * std::sin(th);
    const int c = static_cast<int>(std::floor(x)), r = static_cast<int>(std::floor(y));
    if (r < 0 || c < 0 || r >= occ.rows() || c >= occ.cols() || !occ.isFree(r, c)) return d;
  }
}
}  // namespace

TEST(ScanSimulation, SquareRoomAxisAndDiagonalBeams) {
  const auto occ = test::rectangleRoom(4.0, 4.0, 0.05);  // 80 x 80 free cells
  ScanSimulationOptions o;
  const std::vector<cv::Point> s{{45, 45}};  // cell (40,40) of the room: centre at 2.025 m from the left wall
  const auto scans = simulateScans(occ, s, o);
  ASSERT_EQ(scans.size(), 1u);
  const auto* b = scans.scan(0);
  EXPECT_NEAR(b[0] * 1e-3, 4.0 - 2.025, 0.03);   // +x
  EXPECT_NEAR(b[180] * 1e-3, 2.025, 0.03);       // -x
  EXPECT_NEAR(b[90] * 1e-3, 2.025, 0.03);        // up (decreasing row)
  EXPECT_NEAR(b[270] * 1e-3, 4.0 - 2.025, 0.03); // down
  EXPECT_NEAR(b[45] * 1e-3, std::sqrt(2.0) * (4.0 - 2.025), 0.08);
}

TEST(ScanSimulation, MatchesRayCastingEverywhere) {
  // An L-shaped room with a pillar, at random cells and every 7th beam.
  auto occ = test::rectangleRoom(6.0, 4.0, 0.05);
  occ.cells(cv::Rect(60, 5, 65, 40)).setTo(kOccupied);
  occ.cells(cv::Rect(30, 50, 6, 6)).setTo(kOccupied);
  ScanSimulationOptions o;
  std::vector<cv::Point> s;
  cv::RNG rng(7);
  while (s.size() < 40) {
    cv::Point p(rng.uniform(0, occ.cols()), rng.uniform(0, occ.rows()));
    if (occ.isFree(p.y, p.x)) s.push_back(p);
  }
  const auto scans = simulateScans(occ, s, o);
  int close = 0, total = 0;
  double sum = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int k = 0; k < 360; k += 7) {
      const double ref = castRay(occ, s[i], k * M_PI / 180);
      const double err = std::abs(scans.scan(i)[k] * 1e-3 - ref);
      close += err < 0.1;
      sum += err;
      ++total;
    }
  // A digital line may graze past a wall corner that the exact ray clips (or the reverse): rare, large errors.
  EXPECT_GT(close, 0.97 * total);
  EXPECT_LT(sum / total, 0.05);
}

namespace {
// Reference for the whole-map sweeps: walk the digital line of the beam's family from the sample, one cell at a
// time, until a non-free cell or the image border (the definition in scan_simulation.h, beam by beam).
std::uint16_t walkDigitalLine(const OccupancyImage& occ, cv::Point p, int beam, int M, double max_range) {
  const int kf = beam % (M / 2);  // the family is that of direction kf < M/2 (its opposite shares the lines)
  const double th = 2.0 * M_PI * kf / M, dc = std::cos(th), dr = -std::sin(th);
  const bool shallow = std::abs(dc) >= std::abs(dr);
  const double slope = shallow ? dr / dc : dc / dr;
  const bool forward = (beam == kf) == ((shallow ? dc : dr) > 0);  // towards increasing major coordinate
  const int n_major = shallow ? occ.cols() : occ.rows(), n_minor = shallow ? occ.rows() : occ.cols();
  auto offset = [&](int k) { return static_cast<int>(std::floor(k * slope + 0.5)); };
  const int k_start = shallow ? p.x : p.y, j = (shallow ? p.y : p.x) - offset(k_start);
  int run = 0;
  for (int k = k_start + (forward ? 1 : -1); k >= 0 && k < n_major; k += forward ? 1 : -1) {
    const int m = j + offset(k);
    if (m < 0 || m >= n_minor) break;
    const unsigned char cell = shallow ? occ.cells.at<unsigned char>(m, k) : occ.cells.at<unsigned char>(k, m);
    if (cell != kFree && cell != kSeen) break;  // seen cells are free to a beam
    ++run;
  }
  const double step_mm = occ.resolution * 1000.0 * std::sqrt(1.0 + slope * slope), max_mm = max_range * 1000.0;
  return static_cast<std::uint16_t>(std::lround(std::min((run + 0.5) * step_mm, max_mm)));
}

// Every free cell of the map, row by row.
std::vector<cv::Point> freeCells(const OccupancyImage& occ) {
  std::vector<cv::Point> s;
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c)
      if (occ.isFree(r, c)) s.emplace_back(c, r);
  return s;
}

struct WalkComparison {
  int mismatches = 0;  ///< beams whose simulated range differs from the walk along their digital line
  int saturated = 0;   ///< beams whose walk reaches max_range
};

// simulateScans at the samples s, beam by beam against walkDigitalLine.
WalkComparison compareWithWalks(const OccupancyImage& occ, const std::vector<cv::Point>& s,
                                const ScanSimulationOptions& o) {
  const auto scans = simulateScans(occ, s, o);
  const auto max_mm = static_cast<std::uint16_t>(std::lround(o.max_range * 1000.0));
  WalkComparison w;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int b = 0; b < o.num_beams; ++b) {
      const std::uint16_t ref = walkDigitalLine(occ, s[i], b, o.num_beams, o.max_range);
      w.mismatches += scans.scan(i)[b] != ref;
      w.saturated += ref == max_mm;
    }
  return w;
}
}  // namespace

TEST(ScanSimulation, SweepsEqualWalkingEachDigitalLine) {
  // Random clutter (30 % of the cells blocked, plus a wall), every free cell a sample, every beam compared
  // exactly; max range short enough that some beams saturate.
  OccupancyImage occ;
  occ.resolution = 0.05;
  occ.cells = cv::Mat(47, 61, CV_8U, cv::Scalar(kFree));
  cv::RNG rng(11);
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c)
      if (rng.uniform(0.0, 1.0) < 0.3) occ.cells.at<unsigned char>(r, c) = kOccupied;
  occ.cells(cv::Rect(0, 20, 40, 1)).setTo(kOccupied);
  occ.cells(cv::Rect(10, 30, 45, 3)).setTo(kFree);  // a long free strip: runs beyond max range
  const std::vector<cv::Point> s = freeCells(occ);
  ScanSimulationOptions o;
  o.num_beams = 72;
  o.max_range = 1.5;
  o.threads = 2;
  const WalkComparison w = compareWithWalks(occ, s, o);
  EXPECT_EQ(w.mismatches, 0);
  EXPECT_GT(w.saturated, 100);
}

TEST(ScanSimulation, SweepsOverFreeSpansEqualWalkingEachDigitalLine) {
  // The default options (unknown cells and the border stop a beam) sweep only the spans of free cells of each
  // column and those of the previous column: a SLAM-like map, mostly unknown, with rooms touching all four
  // borders, rooms farther apart than the span gap (64 cells), one-cell free streaks in the unknown, seen
  // cells (free to a beam) and clutter. Every beam of every free cell equals the walk along its digital line.
  OccupancyImage occ;
  occ.resolution = 0.05;
  occ.cells = cv::Mat(150, 260, CV_8U, cv::Scalar(kUnknown));
  occ.cells(cv::Rect(0, 0, 50, 40)).setTo(kFree);      // top-left corner
  occ.cells(cv::Rect(190, 100, 70, 50)).setTo(kFree);  // bottom-right corner, > 64 columns from the next room
  occ.cells(cv::Rect(60, 110, 40, 40)).setTo(kFree);   // on the bottom border
  occ.cells(cv::Rect(230, 0, 30, 30)).setTo(kFree);    // top-right corner
  occ.cells(cv::Rect(0, 70, 20, 30)).setTo(kFree);     // on the left border
  cv::RNG rng(23);
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c) {
      unsigned char& cell = occ.cells.at<unsigned char>(r, c);
      if (cell != kFree) continue;
      const double u = rng.uniform(0.0, 1.0);
      if (u < 0.08) cell = kOccupied;
      else if (u < 0.11) cell = kSeen;
      else if (u < 0.13) cell = kUnknown;
    }
  for (int k = 0; k < 120; ++k) occ.cells.at<unsigned char>(20 + k / 2, 40 + k) = kFree;  // a streak out of a room
  for (int k = 0; k < 90; ++k) occ.cells.at<unsigned char>(5 + k, 150) = kFree;            // a lone free line
  const std::vector<cv::Point> s = freeCells(occ);
  ScanSimulationOptions o;
  o.num_beams = 72;
  o.max_range = 3.0;
  o.threads = 2;
  ASSERT_EQ(o.unknown_cells, BeamStop::kObstacle);
  ASSERT_EQ(o.map_border, BeamStop::kObstacle);
  const WalkComparison w = compareWithWalks(occ, s, o);
  int at_border = 0;
  for (std::size_t i = 0; i < s.size(); ++i) at_border += s[i].x == 0 || s[i].y == 0 || s[i].x == 259 || s[i].y == 149;
  EXPECT_EQ(w.mismatches, 0);
  EXPECT_GT(w.saturated, 100);
  EXPECT_GT(at_border, 100);
  EXPECT_GT(s.size(), 7000u);
}

TEST(ScanSimulation, ThreadsDoNotChangeResults) {
  auto occ = test::rectangleRoom(5.0, 3.0, 0.05);
  occ.cells(cv::Rect(40, 20, 10, 30)).setTo(kOccupied);
  const auto lat = buildLattice(occ, 0.1);
  ScanSimulationOptions o1, o2;
  o1.threads = 1, o2.threads = 3;
  EXPECT_EQ(simulateScans(occ, lat.samples, o1).ranges_mm, simulateScans(occ, lat.samples, o2).ranges_mm);
}

TEST(ScanSimulation, LatticeCoversEveryFreeCell) {
  const auto occ = test::rectangleRoom(2.0, 1.0, 0.05);
  const auto lat = buildLattice(occ, 0.1);
  EXPECT_EQ(lat.stride, 2);
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c)
      if (occ.isFree(r, c)) {
        const int i = lat.sampleOfPixel(r, c);
        ASSERT_GE(i, 0);
        EXPECT_LE(std::abs(lat.samples[static_cast<std::size_t>(i)].x - c), 1);
      }
  EXPECT_EQ(lat.samples.size(), 21u * 11u);  // the room starts at an odd cell: 21 x 11 blocks
}

TEST(ScanSimulation, RejectsBadOptions) {
  ScanSimulationOptions o;
  o.num_beams = 7;
  EXPECT_THROW(o.validate(), gridtopo::InputError);
  o = ScanSimulationOptions();
  o.max_range = -1;
  EXPECT_THROW(o.validate(), gridtopo::InputError);
}

TEST(ScanSimulation, UnknownCellsAndBorderActAsChosen) {
  // One free row of 100 cells (5 m) in an image 1 row high: cells 0..39 free, 40..49 unknown, 50..99 free;
  // the image border closes both ends. Sample at cell 20: +x meets the unknown block 19.5 cells ahead, -x the
  // border 20.5 cells behind. Max range 30 m.
  OccupancyImage occ;
  occ.resolution = 0.05;
  occ.cells = cv::Mat(1, 100, CV_8U, cv::Scalar(kFree));
  occ.cells.colRange(40, 50).setTo(kUnknown);
  const std::vector<cv::Point> s{{20, 0}, {70, 0}};
  auto ranges = [&](BeamStop unknown, BeamStop border) {
    ScanSimulationOptions o;
    o.num_beams = 8;
    o.unknown_cells = unknown;
    o.map_border = border;
    const auto sc = simulateScans(occ, s, o);
    // beam 0 = +x (columns increasing), beam 4 = -x
    return std::array<double, 4>{sc.scan(0)[0] * 1e-3, sc.scan(0)[4] * 1e-3, sc.scan(1)[0] * 1e-3,
                                 sc.scan(1)[4] * 1e-3};
  };
  auto r = ranges(BeamStop::kObstacle, BeamStop::kObstacle);  // the behaviour before issue 15
  EXPECT_NEAR(r[0], 19.5 * 0.05, 1e-3);   // stops at the unknown block
  EXPECT_NEAR(r[1], 20.5 * 0.05, 1e-3);   // stops at the border
  EXPECT_NEAR(r[2], 29.5 * 0.05, 1e-3);   // cell 70: border ahead
  EXPECT_NEAR(r[3], 20.5 * 0.05, 1e-3);   // cell 70: unknown block behind (cells 49..50)
  r = ranges(BeamStop::kMaxRange, BeamStop::kObstacle);
  EXPECT_NEAR(r[0], 30.0, 1e-3);
  EXPECT_NEAR(r[1], 20.5 * 0.05, 1e-3);
  EXPECT_NEAR(r[3], 30.0, 1e-3);
  r = ranges(BeamStop::kPass, BeamStop::kObstacle);
  EXPECT_NEAR(r[0], 79.5 * 0.05, 1e-3);   // through the unknown block to the far border
  EXPECT_NEAR(r[3], 70.5 * 0.05, 1e-3);
  r = ranges(BeamStop::kObstacle, BeamStop::kMaxRange);
  EXPECT_NEAR(r[0], 19.5 * 0.05, 1e-3);
  EXPECT_NEAR(r[1], 30.0, 1e-3);
  EXPECT_NEAR(r[2], 30.0, 1e-3);
  r = ranges(BeamStop::kPass, BeamStop::kMaxRange);
  EXPECT_NEAR(r[0], 30.0, 1e-3);          // through the unknown, then off the map
  // An occupied cell still stops every beam: wall at cell 10.
  occ.cells.at<unsigned char>(0, 10) = kOccupied;
  r = ranges(BeamStop::kMaxRange, BeamStop::kMaxRange);
  EXPECT_NEAR(r[1], 9.5 * 0.05, 1e-3);
}

TEST(ScanSimulation, BeamStopOptionsParseAndRoundTrip) {
  EXPECT_EQ(parseBeamStop("max_range", "x", "unknown_cells", true), BeamStop::kMaxRange);
  EXPECT_EQ(parseBeamStop("pass", "x", "unknown_cells", true), BeamStop::kPass);
  EXPECT_EQ(beamStopName(BeamStop::kObstacle), "obstacle");
  try {
    parseBeamStop("pass", "topology_train.ini", "map_border", false);
    FAIL() << "pass accepted for the map border";
  } catch (const gridtopo::InputError& e) {
    EXPECT_EQ(e.field(), "map_border");
  }
  EXPECT_THROW(parseBeamStop("wall", "x", "unknown_cells", true), gridtopo::InputError);
}

TEST(ScanSimulation, StripesOfSamplesReadWhatTheWholeMapReads) {
  // A map much taller than the rows a beam depends on (max range 2 m = 40 rows, margin 43): the beams of each
  // stripe of samples, swept over the stripe's rows and the margin only, equal those of the whole-map sweeps bit
  // for bit, whatever unknown cells and the border do, for every family (72 beams: steep and shallow slopes).
  OccupancyImage occ;
  occ.resolution = 0.05;
  occ.cells = cv::Mat(400, 90, CV_8U, cv::Scalar(kFree));
  cv::RNG rng(5);
  for (int r = 0; r < occ.rows(); ++r)
    for (int c = 0; c < occ.cols(); ++c) {
      const double u = rng.uniform(0.0, 1.0);
      if (u < 0.04) occ.cells.at<unsigned char>(r, c) = kOccupied;
      else if (u < 0.06) occ.cells.at<unsigned char>(r, c) = kUnknown;
      else if (u < 0.08) occ.cells.at<unsigned char>(r, c) = kSeen;
    }
  occ.cells(cv::Rect(20, 0, 3, 400)).setTo(kFree);  // long free lines: beams saturate across stripe borders
  occ.cells(cv::Rect(60, 0, 1, 400)).setTo(kFree);
  const Lattice lat = buildLattice(occ, 0.1);
  ScanSimulationOptions o;
  o.num_beams = 72;
  o.max_range = 2.0;
  o.threads = 2;
  ASSERT_EQ(scanRowMargin(occ, o), 43);
  int saturated = 0;
  for (const BeamStop unknown : {BeamStop::kObstacle, BeamStop::kMaxRange, BeamStop::kPass})
    for (const BeamStop border : {BeamStop::kObstacle, BeamStop::kMaxRange}) {
      o.unknown_cells = unknown, o.map_border = border;
      const SimulatedScans whole = simulateScans(occ, lat.samples, o);
      const auto stripes = latticeStripes(lat, 1500);
      ASSERT_GE(stripes.size(), 4u);
      int mismatches = 0;
      for (const auto& [a, b] : stripes) {
        const std::vector<cv::Point> part(lat.samples.begin() + static_cast<long>(a),
                                          lat.samples.begin() + static_cast<long>(b));
        const cv::Mat beams = simulateBeams(occ, part, o);
        ASSERT_EQ(beams.rows, o.num_beams);
        ASSERT_EQ(beams.cols, static_cast<int>(b - a));
        for (std::size_t i = a; i < b; ++i)
          for (int k = 0; k < o.num_beams; ++k) {
            const std::uint16_t v = beams.at<std::uint16_t>(k, static_cast<int>(i - a));
            mismatches += v != whole.scan(i)[k];
            saturated += v == 2000;
          }
      }
      EXPECT_EQ(mismatches, 0) << beamStopName(unknown) << " / " << beamStopName(border);
    }
  EXPECT_GT(saturated, 1000);
}
