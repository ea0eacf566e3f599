// gridtopo-slam: RBPF grid SLAM with the informed proposal on a CARMEN log or an MRPT rawlog.
#include <tclap/CmdLine.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/io/log_reader.h"
#include "gridtopo/slam/slam_run.h"
#include "gridtopo/slam/slam_run_ini.h"

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

    // TCLAP hands an unknown flag to the optional positional argument.
    if (run_ini.getValue().rfind('-', 0) == 0) throw UsageError(run_ini.getValue() + ": unknown argument");
    const bool has_run_ini = !run_ini.getValue().empty();
    if (has_run_ini && config.isSet()) throw UsageError("give the options either in RUN.ini or with -c, not both");
    if (!has_run_ini && (!input.isSet() || !output.isSet()))
      throw UsageError("name the log (-i) and the output directory (-o), or give a RUN.ini");
    slam::SlamRunSpec spec = has_run_ini ? slam::loadSlamRunIni(run_ini.getValue(), section.getValue())
                                         : slam::SlamRunSpec{};
    if (config.isSet()) spec.options = slam::loadSlamOptionsIni(config.getValue(), section.getValue());
    if (input.isSet()) {
      spec.input = input.getValue();
      spec.input_from_ini = false;
    }
    if (output.isSet()) {
      spec.output = output.getValue();
      spec.output_from_ini = false;
    }
    if (max_scans.isSet()) spec.max_scans = static_cast<std::size_t>(std::max(0L, max_scans.getValue()));
    const auto given = [](auto& arg) { return arg.isSet() ? std::optional(arg.getValue()) : std::nullopt; };
    slam::overrideOptions(spec.options, {given(particles), given(seed), given(threads), given(proposal)});
    slam::checkSlamRunSpec(spec);
    if (!quiet.getValue()) spec.options.dumpToTextStream(std::cerr);

    const auto t0 = std::chrono::steady_clock::now();
    io::ScanLogInfo info;
    auto records = std::make_shared<std::vector<ScanRecord>>(io::readScanLog(spec.input, {}, info));
    // What the reader decided against the log's word is always said; which variant it read, unless quiet.
    for (const auto& w : info.warnings) std::cerr << "gridtopo-slam: warning: " << spec.input << ": " << w << "\n";
    if (!quiet.getValue())
      for (const auto& n : info.notes) std::cerr << "gridtopo-slam: note: " << spec.input << ": " << n << "\n";
    if (spec.max_scans > 0 && spec.max_scans < records->size()) records->resize(spec.max_scans);
    if (records->empty()) throw InputError(spec.input, "the log holds no laser scans");
    const double t_read = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    slam::SlamRun run(std::move(records), spec.options);
    ProgressBar bar(run.scanLimit(), "slam", "scans", quiet.getValue() ? 0 : -1);
    run.runToEnd([&](std::size_t fed, std::size_t) { bar.update(fed); });
    bar.finish();
    const std::size_t scans = run.scansFed(), steps = run.filter().stepsProcessed();
    const double t_slam = run.filterSeconds();
    run.finishAndWrite(spec.output, {"gridtopo-slam " + spec.input, "one pose per laser scan, best particle"},
                       slam::slamRunIni(spec));
    const double t_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr,
                 "gridtopo-slam: %zu scans, %zu processed, read %.2f s, slam %.2f s, total %.2f s, peak RSS %zu MB, "
                 "output in %s\n",
                 scans, steps, t_read, t_slam, t_total, processMemory().peak_kb / 1024, spec.output.c_str());
    return 0;
  });
}
