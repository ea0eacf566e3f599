// gridtopo-experiment: runs an experiment INI (config-ini/experiments/) as gridtopo-slam subprocesses, in parallel,
// resumable, and writes results.csv, results.jsonl, summary.md and gnuplot plots; or emits Slurm / GNU parallel jobs.
#include <tclap/CmdLine.h>

#include <filesystem>
#include <iostream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/data_dir.h"
#include "gridtopo/experiment/emitters.h"
#include "gridtopo/experiment/results_writer.h"
#include "gridtopo/experiment/run_executor.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::experiment;

int main(int argc, char** argv) {
  return runApp("gridtopo-experiment", [&]() -> int {
    TCLAP::CmdLine cmd("Runs an experiment INI: every combination of its sweep is one run (gridtopo-slam; with topology, "
                       "then gridtopo-topology and gridtopo-topology-compare) with its own folder and RUN.ini files; "
                       "finished runs are skipped when run again. See doc/experiments.md.",
                       ' ', "0.1");
    TCLAP::UnlabeledValueArg<std::string> ini("experiment", "experiment INI", true, "", "EXPERIMENT.ini", cmd);
    TCLAP::ValueArg<std::string> output("o", "output", "results folder (overrides [experiment] output)", false, "",
                                        "dir", cmd);
    TCLAP::ValueArg<int> jobs("j", "jobs", "parallel runs (default: cores / threads per run)", false, 0, "n", cmd);
    TCLAP::SwitchArg force("", "force", "rerun runs already done", cmd);
    TCLAP::ValueArg<long> run_index("", "run-index", "run only this run (0-based; a Slurm array task), no tables",
                                    false, -1, "n", cmd);
    TCLAP::SwitchArg collect("", "collect", "run nothing: merge the recorded runs into the tables and plots", cmd);
    TCLAP::ValueArg<std::string> emit("", "emit", "write jobs instead of running: slurm (OUT/slurm.sh) or parallel "
                                      "(OUT/parallel.jobs)", false, "", "slurm|parallel", cmd);
    TCLAP::SwitchArg list("", "list", "print the planned runs and exit", cmd);
    TCLAP::SwitchArg quiet("q", "quiet", "no progress bar and no line per run", cmd);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);
    if (collect.getValue() + emit.isSet() + run_index.isSet() + list.getValue() > 1)
      throw UsageError("--collect, --emit, --run-index and --list exclude each other");

    const ExperimentPlan plan = planExperiment(loadExperimentSpec(ini.getValue()), output.getValue());
    const std::string self = executablePath();
    if (list.getValue()) {
      for (const auto& r : plan.runs) std::cout << r.index << ' ' << r.id << ' ' << r.label << ' ' << r.dir << "\n";
      return 0;
    }
    if (emit.isSet()) {
      if (emit.getValue() != "slurm" && emit.getValue() != "parallel") throw UsageError("--emit must be slurm or parallel");
      std::cout << emitJobs(plan, emit.getValue(), self, fs::absolute(ini.getValue()).string()) << "\n";
      return 0;
    }
    if (!collect.getValue()) {
      if (run_index.isSet() && (run_index.getValue() < 0 || static_cast<std::size_t>(run_index.getValue()) >= plan.runs.size()))
        throw UsageError("--run-index must be in 0.." + std::to_string(plan.runs.size() - 1));
      ExecutionOptions eo;  // gridtopo-slam, gridtopo-topology, gridtopo-topology-compare: the ones beside this program
      eo.jobs = jobs.isSet() ? jobs.getValue() : defaultJobs(plan);
      if (eo.jobs < 1) throw UsageError("--jobs must be >= 1");
      eo.force = force.getValue();
      const fs::path bin = fs::path(self).parent_path();
      eo.exe = {(bin / "gridtopo-slam").string(), (bin / "gridtopo-topology").string(),
                (bin / "gridtopo-topology-compare").string()};
      eo.progress = quiet.getValue() ? 0 : -1;
      eo.verbose = !quiet.getValue();
      for (const auto& exe : {eo.exe.slam, eo.exe.topology, eo.exe.compare})
        if (!fs::exists(exe)) throw InputError(exe, "not found beside gridtopo-experiment");
      installStopHandlers();
      std::vector<std::size_t> indices;
      if (run_index.isSet()) indices.push_back(static_cast<std::size_t>(run_index.getValue()));
      const ExecutionSummary sum = executeRuns(plan, indices, eo, std::cerr);
      if (sum.stopped) {
        std::cerr << "gridtopo-experiment: stopped: " << sum.ok + sum.failed << " runs recorded, " << sum.interrupted
                  << " not; run the same command again to resume\n";
        return 130;
      }
      if (run_index.isSet()) return sum.failed ? 1 : 0;
    }
    return writeTablesAndPlots(plan, std::cerr) ? 0 : 1;
  });
}
