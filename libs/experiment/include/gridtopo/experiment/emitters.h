#pragma once
// Beyond one machine, on an existing scheduler: a Slurm job-array script (one array task per run, each running
// `gridtopo-experiment EXP.ini -o OUT --run-index $SLURM_ARRAY_TASK_ID`) and a GNU parallel job list (one such
// command per line; `parallel --sshloginfile` spreads it over hosts sharing the folder). Results are merged
// afterwards by `gridtopo-experiment EXP.ini -o OUT --collect`.
#include <string>

#include "gridtopo/experiment/run_plan.h"

namespace gridtopo::experiment {

/// `experiment_exe` and `experiment_ini` should be absolute (the jobs may start elsewhere). Each task asks for the
/// runs' largest `threads` as --cpus-per-task, or a whole node (--exclusive) when a run has threads = 0 (all cores).
std::string slurmScript(const ExperimentPlan& plan, const std::string& experiment_exe,
                        const std::string& experiment_ini);
std::string parallelJobs(const ExperimentPlan& plan, const std::string& experiment_exe,
                         const std::string& experiment_ini);

/// Writes OUT/slurm.sh (executable; OUT/slurm-logs/ for the tasks' output) or OUT/parallel.jobs; returns its path.
std::string emitJobs(const ExperimentPlan& plan, const std::string& kind, const std::string& experiment_exe,
                     const std::string& experiment_ini);

}  // namespace gridtopo::experiment
