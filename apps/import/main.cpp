// gridtopo-import: CARMEN log (or MRPT rawlog) -> MRPT rawlog in the action/sensory-frame or observation-only
// layout, with a summary of what the log holds.
#include <tclap/CmdLine.h>

#include <iostream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/io/log_import.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/io/log_summary.h"
#include "gridtopo/io/rawlog_io.h"
#include "gridtopo/sim/simulator.h"
#include "gridtopo/io/trajectory_io.h"

using namespace gridtopo;


int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-import", [&]() -> int {
    TCLAP::CmdLine cmd(
        "gridtopo-import: converts a CARMEN log (.clf/.log, plain or .gz) or an MRPT rawlog into an MRPT rawlog "
        "in the action/sensory-frame layout (what rbpf-slam / icp-slam read) or the observation-only layout, "
        "and prints a summary of the log. The input format is detected from the file's content.",
        ' ', "0.1");
    TCLAP::ValueArg<std::string> in_arg("i", "input", "input log: CARMEN (.clf/.log[.gz]) or MRPT rawlog", false, "",
                                        "file", cmd);
    TCLAP::ValueArg<unsigned> sim_arg("", "simulate",
                                      "instead of --input: simulate N scans of a robot looping around two pillars "
                                      "in a 12 m x 6 m room (noisy odometry, off-centre laser, no-return beams)",
                                      false, 0, "N", cmd);
    TCLAP::ValueArg<unsigned> seed_arg("", "seed", "random seed of --simulate (default 42)", false, 42, "seed", cmd);
    TCLAP::ValueArg<std::string> gt_arg("", "ground-truth",
                                        "with --simulate: write the true poses as a trajectory file "
                                        "(timestamp x y theta)",
                                        false, "", "file", cmd);
    TCLAP::ValueArg<std::string> out_arg(
        "o", "output",
        "output rawlog (.rawlog; gzip-compressed if it ends in .gz or with --gz); omit to only "
        "print the summary",
        false, "", "file", cmd);
    TCLAP::ValueArg<std::string> layout_arg("l", "layout",
                                            "rawlog layout: 'sf' (CActionCollection + CSensoryFrame pairs, "
                                            "default) or 'obs' (CObservationOdometry + CObservation2DRangeScan)",
                                            false, "sf", "sf|obs", cmd);
    TCLAP::ValueArg<std::string> odo_arg("", "odometry",
                                         "CARMEN odometry source: 'laser' (pose inside each laser line, default) "
                                         "or 'odom' (ODOM lines interpolated at the scan time)",
                                         false, "laser", "laser|odom", cmd);
    TCLAP::ValueArg<std::string> model_arg("", "motion-model",
                                           "motion model of the actions (sf layout): 'gaussian' (default) or "
                                           "'thrun' (MRPT's defaults)",
                                           false, "gaussian", "gaussian|thrun", cmd);
    TCLAP::ValueArg<int> level_arg("", "compression",
                                   "gzip level 0-9 of the output (default: 1 if the name "
                                   "ends in .gz, else 0 = plain)",
                                   false, -1, "level", cmd);
    TCLAP::SwitchArg gz_arg("", "gz", "gzip-compress the output (level 1, like MRPT's tools)", cmd);
    TCLAP::ValueArg<std::string> label_arg("", "sensor-label", "sensorLabel of the scans (default LASER)", false,
                                           "LASER", "label", cmd);
    TCLAP::ValueArg<double> maxr_arg("", "max-range", "CARMEN: laser max range (m) when no PARAM gives it (default 50)",
                                     false, 50.0, "metres", cmd);
    TCLAP::SwitchArg skip_arg("", "skip-bad-lines",
                              "CARMEN: skip malformed lines (counted and reported) "
                              "instead of stopping at the first one",
                              cmd);
    TCLAP::SwitchArg rear_arg("", "rear-laser", "CARMEN: also import RLASER (rear laser) scans", cmd);
    TCLAP::SwitchArg quiet_arg("q", "quiet", "no summary, no progress bar", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    io::LogImportOptions io_opt;
    io_opt.odometry = odo_arg.getValue(), io_opt.motion_model = model_arg.getValue();
    io_opt.layout = layout_arg.getValue(), io_opt.sensor_label = label_arg.getValue();
    io_opt.max_range = maxr_arg.getValue(), io_opt.compression = level_arg.getValue(), io_opt.gz = gz_arg.getValue();
    io_opt.skip_bad_lines = skip_arg.getValue(), io_opt.rear_laser = rear_arg.getValue();
    const io::LogReadOptions ropt = io::logReadOptions(io_opt);
    const io::RawlogWriteOptions wopt = io::rawlogWriteOptions(io_opt);

    const bool quiet = quiet_arg.getValue();
    const bool simulate = sim_arg.isSet();
    if (simulate == in_arg.isSet()) throw std::invalid_argument("give either --input or --simulate");
    if (gt_arg.isSet() && !simulate) throw std::invalid_argument("--ground-truth needs --simulate");
    io::ScanLogInfo info;
    std::vector<ScanRecord> scans;
    std::string input = in_arg.getValue();
    OutputSet outputs;  // the rawlog and the ground truth appear together or not at all
    if (simulate) {
      auto sopt = sim::pillarRoomOptions();
      sopt.seed = seed_arg.getValue();
      const std::size_t n = sim_arg.getValue();
      auto sim = sim::simulatePillarRoom(n, sopt);
      const auto truth = sim.timedTruth();
      scans = std::move(sim.records);
      info.format = io::LogFormat::Simulated;
      input = "simulated (" + std::to_string(n) + " scans, seed " + std::to_string(sopt.seed) + ")";
      if (gt_arg.isSet()) {
        const std::string header = "ground truth of gridtopo-import --simulate " + std::to_string(n) +
                                   " --seed " + std::to_string(sopt.seed);
        outputs.write(gt_arg.getValue(), [&](const std::string& tmp) { io::writeTrajectory(tmp, truth, {header}); });
      }
    } else {
      scans = io::readScanLog(input, ropt, info);
    }
    if (!quiet)
      io::printLogSummary(std::cout, input, info, io::summarizeScans(scans),
                          scans.empty() ? LaserScan{} : scans.front().scan);

    if (!out_arg.getValue().empty()) {
      const std::string line = io::stageRawlog(outputs, out_arg.getValue(), scans, wopt, quiet, in_arg.getValue());
      if (!quiet) std::cout << line;
    }
    outputs.commit();
    return 0;
  });
}
