// gridtopo-import: CARMEN log (or MRPT rawlog) -> MRPT rawlog in the action/sensory-frame or observation-only
// layout, with a summary of what the log holds.
#include <tclap/CmdLine.h>

#include <iostream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/output_set.h"
#include "gridtopo/core/run_args.h"
#include "gridtopo/io/log_import_args.h"
#include "gridtopo/io/log_summary.h"
#include "gridtopo/sim/import_source.h"

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
    io::LogImportArgs import_args(cmd);  // --layout ... --rear-laser: the reader's and the writer's options
    TCLAP::SwitchArg quiet_arg("q", "quiet", "no summary, no progress bar", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    const io::LogImportOptions io_opt = import_args.options();
    const io::LogReadOptions ropt = io::logReadOptions(io_opt);
    const io::RawlogWriteOptions wopt = io::rawlogWriteOptions(io_opt);

    const bool quiet = quiet_arg.getValue();
    // The outputs writable before the log is read (not after it).
    if (!out_arg.getValue().empty()) checkOutputFile(out_arg.getValue());
    if (!gt_arg.getValue().empty()) checkOutputFile(gt_arg.getValue());
    OutputSet outputs;  // the rawlog and the ground truth appear together or not at all
    const sim::ImportSource source =
        sim::readImportSource(given(in_arg), given(sim_arg), seed_arg.getValue(), given(gt_arg), ropt, outputs);
    if (!quiet)
      io::printLogSummary(std::cout, source.name, source.info, io::summarizeScans(source.scans),
                          source.scans.empty() ? LaserScan{} : source.scans.front().scan);

    if (!out_arg.getValue().empty()) {
      const std::string line = io::stageRawlog(outputs, out_arg.getValue(), source.scans, wopt, quiet, in_arg.getValue());
      if (!quiet) std::cout << line;
    }
    outputs.commit();
    return 0;
  });
}
