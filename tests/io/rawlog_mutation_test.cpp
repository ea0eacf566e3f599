// Truncated rawlogs (the usual damage: an interrupted copy or recording) must give a clean gridtopo::InputError
// naming the file, never a crash or a hang, plain or gzip, both layouts.
// Corrupted (byte-flipped) rawlogs: MRPT 2.5.8's own deserialiser can crash on them (e.g. a segfault in
// CActionRobotMovement2D::serializeFrom); readRawlog parses in a child process first and turns such a crash into
// an InputError naming the entry.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "gridtopo/core/error.h"
#include "gridtopo/io/rawlog_io.h"
#include "gridtopo/sim/simulator.h"

namespace fs = std::filesystem;
using namespace gridtopo::io;

namespace {
// A short simulated log (6 scans of 30 beams) and a fresh scratch folder for the mutated files.
struct Scratch {
  gridtopo::sim::SimLog sim;
  fs::path dir;
  explicit Scratch(const std::string& name) {
    auto so = gridtopo::sim::pillarRoomOptions();
    so.beams = 30;
    sim = gridtopo::sim::simulatePillarRoom(6, so);
    dir = fs::temp_directory_path() / ("gridtopo_rawlog_" + name + "_" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  ~Scratch() { fs::remove_all(dir); }
};
}  // namespace

TEST(RawlogTruncation, EveryCutGivesAnInputErrorOrTheScansBeforeIt) {
  const Scratch scratch("cut");
  const auto& sim = scratch.sim;
  const fs::path& dir = scratch.dir;
  std::size_t complete = 0, errors = 0;
  for (const auto layout : {RawlogLayout::ActionSensoryFrame, RawlogLayout::ObservationOnly}) {
    for (const bool gz : {false, true}) {
      const fs::path clean = dir / (gz ? "clean.rawlog.gz" : "clean.rawlog");
      RawlogWriteOptions w;
      w.layout = layout;
      writeRawlog(clean.string(), sim.records, w);
      std::ifstream f(clean, std::ios::binary);
      const std::string bytes{std::istreambuf_iterator<char>(f), {}};
      std::mt19937 rng(12345);
      for (int trial = 0; trial < 100; ++trial) {
        const std::size_t cut = rng() % bytes.size();
        const fs::path p = dir / (gz ? "cut.rawlog.gz" : "cut.rawlog");
        std::ofstream(p, std::ios::binary) << bytes.substr(0, cut);
        try {
          const auto c = readRawlog(p.string());
          // Only possible when the cut falls exactly between objects (or before the first one).
          ++complete;
          EXPECT_LT(c.scans.size(), sim.records.size());
        } catch (const gridtopo::InputError& e) {
          ++errors;
          EXPECT_EQ(e.file(), p.string());
        }
      }
    }
  }
  EXPECT_EQ(complete + errors, 400u);
  EXPECT_GT(errors, 300u);
}

TEST(RawlogCorruption, EveryByteFlipGivesAnInputErrorOrAResultNeverACrash) {
  const Scratch scratch("flip");
  const auto& sim = scratch.sim;
  const fs::path& dir = scratch.dir;
  std::size_t complete = 0, errors = 0, crashes = 0;
  for (const auto layout : {RawlogLayout::ActionSensoryFrame, RawlogLayout::ObservationOnly}) {
    const fs::path clean = dir / "clean.rawlog";
    RawlogWriteOptions w;
    w.layout = layout;
    writeRawlog(clean.string(), sim.records, w);
    std::ifstream f(clean, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(f), {}};
    std::mt19937 rng(layout == RawlogLayout::ActionSensoryFrame ? 777 : 778);
    for (int trial = 0; trial < 150; ++trial) {
      std::string mutated = bytes;
      const int flips = 1 + static_cast<int>(rng() % 4);
      for (int k = 0; k < flips; ++k) mutated[rng() % mutated.size()] ^= static_cast<char>(1 + rng() % 255);
      const fs::path p = dir / "flipped.rawlog";
      std::ofstream(p, std::ios::binary) << mutated;
      try {
        readRawlog(p.string());
        ++complete;  // a flip inside a range or a timestamp still parses
      } catch (const gridtopo::InputError& e) {
        ++errors;
        EXPECT_EQ(e.file(), p.string());
        if (std::string(e.what()).find("crashed") != std::string::npos) ++crashes;
      }
    }
  }
  EXPECT_EQ(complete + errors, 300u);
  EXPECT_GT(errors, 50u);
  // The isolation is exercised: some flips make MRPT's deserialiser crash (a segfault before the guard).
  EXPECT_GT(crashes, 0u);
  std::printf("byte flips: %zu parsed, %zu InputError (%zu of them MRPT crashes)\n", complete, errors, crashes);
}
