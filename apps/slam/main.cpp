// gridtopo-slam: RBPF grid SLAM with the informed proposal on a CARMEN log or an MRPT rawlog.
#include <mrpt/config/CConfigFile.h>
#include <tclap/CmdLine.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/slam/map_export.h"
#include "gridtopo/slam/options_ini.h"
#include "gridtopo/slam/rbpf_slam.h"
#include "gridtopo/slam/slam_outputs.h"

namespace fs = std::filesystem;
using namespace gridtopo;

namespace {

long rssKb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return 0;
}

long peakRssKb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));
  return 0;
}

/// Gives the pages of freed heap memory back to the system (glibc keeps them otherwise: the particles' tiles
/// are small blocks spread over the heap, and the export's large buffers are fresh mappings).
void releaseFreedMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-slam", [&]() -> int {
    TCLAP::CmdLine cmd(
        "RBPF grid SLAM with the informed proposal (Grisetti, Stachniss, Burgard 2007). Reads a CARMEN log "
        "(.clf/.log, optionally .gz) or an MRPT rawlog (either layout) and writes the map (PNG, PGM+YAML, "
        ".gridmap.gz), a .simplemap, the trajectory of every scan and per-step statistics to --output.",
        ' ', "0.1");
    TCLAP::ValueArg<std::string> input("i", "input", "input log (.clf, .log, .gz, .rawlog)", true, "", "file", cmd);
    TCLAP::ValueArg<std::string> output("o", "output", "output directory", true, "", "dir", cmd);
    TCLAP::ValueArg<std::string> config("c", "config", "INI file with the options (see config-ini/slam.ini)",
                                        false, "", "file", cmd);
    TCLAP::ValueArg<std::string> section("", "section", "INI section", false, "slam", "name", cmd);
    TCLAP::ValueArg<int> particles("p", "particles", "number of particles (overrides the INI)", false, 0, "n", cmd);
    TCLAP::ValueArg<long long> seed("s", "seed", "random seed (overrides the INI)", false, -1, "n", cmd);
    TCLAP::ValueArg<int> threads("t", "threads", "threads, 0 = all cores (overrides the INI)", false, -1, "n", cmd);
    TCLAP::ValueArg<std::string> proposal("", "proposal", "informed | mode-only | odometry (overrides the INI)",
                                          false, "", "name", cmd);
    TCLAP::ValueArg<long> max_scans("", "max-scans", "process only the first n scans", false, -1, "n", cmd);
    TCLAP::SwitchArg quiet("q", "quiet", "no progress bar", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    slam::SlamOptions o;
    if (!config.getValue().empty()) {
      if (!fs::exists(config.getValue())) throw InputError(config.getValue(), "no such INI file");
      mrpt::config::CConfigFile ini(config.getValue());
      if (!ini.sectionExists(section.getValue()))
        throw InputError(config.getValue(), 0, "[" + section.getValue() + "]", "section not found");
      o.loadFromConfigFile(ini, section.getValue());
    }
    const std::string cli = "<command line>";
    if (particles.isSet()) o.particles = particles.getValue();
    if (seed.isSet()) {
      if (seed.getValue() < 0) throw InputError(cli, 0, "--seed", "must be >= 0");
      o.seed = static_cast<std::uint64_t>(seed.getValue());
    }
    if (threads.isSet()) o.threads = threads.getValue();
    if (proposal.isSet()) {
      try {
        o.proposal.type = slam::proposalFromString(proposal.getValue());
      } catch (const std::invalid_argument& e) {
        throw InputError(cli, 0, "--proposal", e.what());
      }
    }
    o.validate(cli, "slam");
    if (!quiet.getValue()) o.dumpToTextStream(std::cerr);

    const auto t0 = std::chrono::steady_clock::now();
    if (!fs::exists(input.getValue())) throw InputError(input.getValue(), "no such file");
    io::ScanLogInfo info;
    std::vector<io::ScanRecord> records = io::readScanLog(input.getValue(), {}, info);
    // What the reader decided against the log's word is always said; which variant it read, unless quiet.
    for (const auto& w : info.warnings) std::cerr << "gridtopo-slam: warning: " << input.getValue() << ": " << w << "\n";
    if (!quiet.getValue())
      for (const auto& n : info.notes) std::cerr << "gridtopo-slam: note: " << input.getValue() << ": " << n << "\n";
    if (max_scans.getValue() >= 0 && static_cast<std::size_t>(max_scans.getValue()) < records.size())
      records.resize(static_cast<std::size_t>(max_scans.getValue()));
    if (records.empty()) throw InputError(input.getValue(), "the log holds no laser scans");
    const double t_read = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    auto filter_owner = std::make_unique<slam::RbpfSlam>(o);
    slam::RbpfSlam& filter = *filter_owner;
    ProgressBar bar(records.size(), "slam", "scans", quiet.getValue() ? 0 : -1);
    std::ostringstream stats;
    stats << "# " << slam::kStatsColumns << " rss_kb\n";
    for (std::size_t i = 0; i < records.size(); ++i) {
      if (filter.processScan(records[i])) {
        stats << slam::statsRow(filter.stats().back()) << ' ' << rssKb() << '\n';
      }
      if ((i & 63) == 0) bar.update(i);
    }
    bar.finish();
    const double t_slam =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() - t_read;

    // Outputs: all or nothing.
    const fs::path dir(output.getValue());
    const auto traj = filter.trajectory();
    const std::size_t steps = filter.stepsProcessed();
    const slam::TrajectoryNodePtr best_node = filter.bestParticle().node;
    // The export needs only the best particle: the other particles' maps are freed before the map (and its
    // pictures, 3 bytes a cell) is built, so that the peak memory is the filter's, not filter + export.
    auto grid = [&] {
      const slam::GridMap best_map = filter.bestParticle().map;  // shares the tiles
      filter_owner.reset();
      releaseFreedMemory();
      return slam::toOccupancyGrid(best_map);
    }();
    releaseFreedMemory();
    slam::SlamOutputs outputs;
    outputs.grid = std::move(grid);
    outputs.trajectory = traj;
    outputs.trajectory_header = {"gridtopo-slam " + input.getValue(), "one pose per laser scan, best particle"};
    outputs.simplemap = slam::simpleMapOf(best_node, records);
    outputs.stats = stats.str();
    outputs.options_ini = slam::slamOptionsIni(o);
    slam::writeSlamOutputs(dir.string(), outputs);
    const double t_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr,
                 "gridtopo-slam: %zu scans, %zu processed, read %.2f s, slam %.2f s, total %.2f s, peak RSS %ld MB, "
                 "output in %s\n",
                 records.size(), steps, t_read, t_slam, t_total, peakRssKb() / 1024,
                 dir.string().c_str());
    return 0;
  });
}
