// gridtopo-map: log -> SLAM -> semantic and topological map in one process, through the two MRPT map builders
// (mapping::CMetricMapBuilderTopology over slam::CMetricMapBuilderGridRbpf).
#include <tclap/CmdLine.h>

#include <cstdio>
#include <iostream>
#include <optional>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/error.h"
#include "gridtopo/core/process_memory.h"
#include "gridtopo/core/progress.h"
#include "gridtopo/mapping/map_run.h"
#include "gridtopo/slam/slam_run_ini.h"

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
    TCLAP::ValueArg<std::string> model("m", "model", "place model from gridtopo-train", false, "", "file", cmd);
    TCLAP::ValueArg<int> particles("p", "particles", "number of particles (overrides the INI)", false, 0, "n", cmd);
    TCLAP::ValueArg<long long> seed("s", "seed", "random seed (overrides the INI)", false, -1, "n", cmd);
    TCLAP::ValueArg<int> threads("t", "threads", "SLAM threads, 0 = all cores (overrides the INI)", false, -1, "n", cmd);
    TCLAP::ValueArg<long> max_scans("", "max-scans", "process only the first n scans (0: all)", false, 0, "n", cmd);
    HelpOptionsArg help_options(cmd, mapping::mapRunOptionsHelp);
    TCLAP::SwitchArg quiet("q", "quiet", "no progress bar and no topology updates on stderr", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    // TCLAP hands an unknown flag to the optional positional argument.
    if (run_ini.getValue().rfind('-', 0) == 0) throw UsageError(run_ini.getValue() + ": unknown argument");
    const bool has_run_ini = !run_ini.getValue().empty();
    if (!has_run_ini && (!input.isSet() || !output.isSet()))
      throw UsageError("name the log (-i) and the output directory (-o), or give a RUN.ini");
    mapping::MapRunSpec spec = has_run_ini ? mapping::loadMapRunIni(run_ini.getValue()) : mapping::MapRunSpec{};
    const auto given = [](auto& arg) { return arg.isSet() ? std::optional(arg.getValue()) : std::nullopt; };
    mapping::overrideRun(spec, {given(input), given(output), given(model), given(max_scans)});
    slam::overrideOptions(spec.slam, {given(particles), given(seed), given(threads), std::nullopt});

    const bool loud = !quiet.getValue();
    std::optional<ProgressBar> bar;  // the total is known once the log is read
    std::string last_topology;
    mapping::MapRunHooks hooks;
    hooks.warning = [&](const std::string& w) { std::cerr << "gridtopo-map: warning: " << spec.input << ": " << w << "\n"; };
    if (loud) {
      hooks.note = [&](const std::string& n) { std::cerr << "gridtopo-map: note: " << spec.input << ": " << n << "\n"; };
      hooks.progress = [&](std::size_t fed, std::size_t total) {
        if (!bar) bar.emplace(total, "map", "scans");
        bar->update(fed, last_topology);
      };
      hooks.topologyUpdated = [&](const mapping::MapTopology& t) {
        int counts[3] = {0, 0, 0};
        for (const auto& n : t.graph().nodes) counts[n.label]++;
        last_topology = std::to_string(counts[0]) + " rooms, " + std::to_string(counts[1]) + " corridors, " +
                        std::to_string(counts[2]) + " doorways, " + std::to_string(t.graph().edges.size()) + " edges";
        if (!bar || !bar->enabled())
          std::cerr << "gridtopo-map: topology at " << t.map_size << " processed scans: " << last_topology << "\n";
      };
    }
    const auto s = mapping::runMapping(spec, hooks);
    if (bar) bar->finish();
    std::fprintf(stderr,
                 "gridtopo-map: %zu scans, %zu processed, %zu topology updates, read %.2f s, mapping %.2f s, total "
                 "%.2f s, peak RSS %zu MB, output in %s\n",
                 s.scans, s.steps, s.topology_updates, s.seconds_read, s.seconds_mapping, s.seconds_total,
                 processMemory().peak_kb / 1024, spec.output.c_str());
    return 0;
  });
}
