// gridtopo-slam: RBPF grid SLAM with the informed proposal on a CARMEN log or an MRPT rawlog.
#include <tclap/CmdLine.h>

#include <iostream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/run_args.h"
#include "gridtopo/slam/slam_log_run.h"

using namespace gridtopo;

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-slam", [&]() -> int {
    TCLAP::CmdLine cmd(
        "RBPF grid SLAM with the informed proposal (Grisetti, Stachniss, Burgard 2007). Reads a CARMEN log "
        "(.clf/.log, optionally .gz) or an MRPT rawlog (either layout) and writes the map (PNG, PGM+YAML, "
        ".gridmap.gz), a .simplemap, the trajectory of every scan, per-step statistics and the run's INI to the "
        "output directory. The run comes from a RUN.ini ([slam_run] input, output, max_scans; [slam] options; see "
        "config-ini/run-slam.ini) or from -i/-o; flags override the RUN.ini.",
        ' ', "0.1");
    TCLAP::UnlabeledValueArg<std::string> run_ini("run", "RUN.ini naming input, output and options", false, "",
                                                  "RUN.ini", cmd);
    TCLAP::ValueArg<std::string> input("i", "input", "input log (.clf, .log, .gz, .rawlog)", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> output("o", "output", "output directory", false, "", "dir", cmd);
    TCLAP::ValueArg<std::string> config("c", "config", "INI file with the options (see config-ini/slam.ini)",
                                        false, "", "file", cmd);
    TCLAP::ValueArg<std::string> section("", "section", "INI section of the options", false, "slam", "name", cmd);
    TCLAP::ValueArg<int> particles("p", "particles", "number of particles (overrides the INI)", false, 0, "n", cmd);
    TCLAP::ValueArg<long long> seed("s", "seed", "random seed (overrides the INI)", false, -1, "n", cmd);
    TCLAP::ValueArg<int> threads("t", "threads", "threads, 0 = all cores (overrides the INI)", false, -1, "n", cmd);
    TCLAP::ValueArg<std::string> proposal("", "proposal", "informed | mode-only | hahnel | odometry (overrides the INI)",
                                          false, "", "name", cmd);
    TCLAP::ValueArg<long> max_scans("", "max-scans", "process only the first n scans (0 or less: all)", false, 0,
                                    "n", cmd);
    HelpOptionsArg help_options(cmd, slam::slamOptionsHelp);
    TCLAP::SwitchArg quiet("q", "quiet", "no progress bar", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    const slam::SlamRunSpec spec = slam::slamRunOfCommandLine(
        positionalArgument(run_ini), given(config), section.getValue(),
        {given(input), given(output), given(max_scans)}, {given(particles), given(seed), given(threads), given(proposal)});
    const slam::SlamLogRunSummary summary = slam::runSlamOnLog(spec, quiet.getValue(), std::cerr);
    std::cerr << slam::slamLogRunSummaryLine(summary, spec.output);
    return 0;
  });
}
