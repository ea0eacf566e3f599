// gridtopo-map: log -> SLAM -> semantic and topological map in one process, through the two MRPT map builders
// (mapping::CMetricMapBuilderTopology over mapping::CMetricMapBuilderGridRbpf).
#include <tclap/CmdLine.h>

#include <iostream>
#include <optional>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/run_args.h"
#include "gridtopo/mapping/map_run_console.h"
#include "gridtopo/mapping/map_run_ini.h"

using namespace gridtopo;

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-map", [&]() -> int {
    TCLAP::CmdLine cmd(
        "Build the metric map of a log with the RBPF SLAM and its semantic and topological map (place labels, "
        "regions, graph) in one run, through the two MRPT map builders. Writes OUT/slam (what gridtopo-slam writes), "
        "OUT/topology (what gridtopo-topology writes on OUT/slam/map.gridmap.gz) and OUT/options.ini (this run's "
        "loadable RUN.ini), all or nothing. The run comes from a RUN.ini ([map_run] input, output, model, max_scans; "
        "[slam]; [topology], [relaxation], [correction]; [topology_builder] update_every; see config-ini/run-map.ini) "
        "or from -i/-o; flags override the RUN.ini.",
        ' ', "0.1");
    TCLAP::UnlabeledValueArg<std::string> run_ini("run", "RUN.ini naming input, output and options", false, "",
                                                  "RUN.ini", cmd);
    TCLAP::ValueArg<std::string> input("i", "input", "input log (.clf, .log, .gz, .rawlog)", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> output("o", "output", "output directory", false, "", "dir", cmd);
    TCLAP::ValueArg<std::string> model("m", "model",
                                       "place model from gridtopo-train; default: the shipped models/places_model.yml, "
                                       "from $GRIDTOPO_DATA_DIR, beside the executable or the source tree",
                                       false, "", "file", cmd);
    TCLAP::ValueArg<int> particles("p", "particles", "number of particles (overrides the INI)", false, 0, "n", cmd);
    TCLAP::ValueArg<long long> seed("s", "seed", "random seed (overrides the INI)", false, -1, "n", cmd);
    TCLAP::ValueArg<int> threads("t", "threads", "SLAM threads, 0 = all cores (overrides the INI)", false, -1, "n", cmd);
    TCLAP::ValueArg<long> max_scans("", "max-scans", "process only the first n scans (0: all)", false, 0, "n", cmd);
    HelpOptionsArg help_options(cmd, mapping::mapRunOptionsHelp);
    TCLAP::SwitchArg quiet("q", "quiet", "no progress bar and no topology updates on stderr", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    const mapping::MapRunSpec spec =
        mapping::mapRunOfCommandLine(positionalArgument(run_ini), {given(input), given(output), given(model), given(max_scans)},
                                     {given(particles), given(seed), given(threads), std::nullopt});
    mapping::MapRunConsole console(spec.input, quiet.getValue(), std::cerr);
    const mapping::MapRunSummary summary = mapping::runMapping(spec, console.hooks());
    console.finish();
    std::cerr << mapping::mapRunSummaryLine(summary, spec.output);
    return 0;
  });
}
