#include "gridtopo/experiment/emitters.h"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "gridtopo/core/output_set.h"
#include "gridtopo/experiment/subprocess.h"

namespace fs = std::filesystem;

namespace gridtopo::experiment {
namespace {

std::string taskCommand(const ExperimentPlan& plan, const std::string& exe, const std::string& ini,
                        const std::string& index) {
  return shellQuote(exe) + " " + shellQuote(ini) + " -o " + shellQuote(fs::absolute(plan.output).string()) +
         " --run-index " + index;
}

}  // namespace

std::string slurmScript(const ExperimentPlan& plan, const std::string& exe, const std::string& ini) {
  int threads = 1;
  bool all_cores = false;  // threads = 0: the run takes every core of its node
  for (const auto& r : plan.runs) {
    threads = std::max(threads, r.threads);
    all_cores |= r.threads <= 0;
  }
  const std::string out = fs::absolute(plan.output).string();
  std::ostringstream o;
  o << "#!/bin/bash\n"
    << "# Slurm job array of experiment '" << plan.spec.name << "' (" << ini << "): one task per run, "
    << plan.runs.size() << " runs.\n"
    << "# Submit: sbatch " << shellQuote(out + "/slurm.sh") << "\n"
    << "# Then:   " << shellQuote(exe) << " " << shellQuote(ini) << " -o " << shellQuote(out) << " --collect\n"
    << "#SBATCH --job-name=" << plan.spec.name << "\n"
    << "#SBATCH --array=0-" << (plan.runs.empty() ? 0 : plan.runs.size() - 1) << "\n"
    << "#SBATCH --ntasks=1\n"
    << (all_cores ? std::string("#SBATCH --exclusive\n")
                  : "#SBATCH --cpus-per-task=" + std::to_string(threads) + "\n")
    << "#SBATCH --output=" << out << "/slurm-logs/%A_%a.log\n"
    << "set -euo pipefail\n"
    << "exec " << taskCommand(plan, exe, ini, "\"$SLURM_ARRAY_TASK_ID\"") << "\n";
  return o.str();
}

std::string parallelJobs(const ExperimentPlan& plan, const std::string& exe, const std::string& ini) {
  std::ostringstream o;
  for (const auto& r : plan.runs) o << taskCommand(plan, exe, ini, std::to_string(r.index)) << "\n";
  return o.str();
}

std::string emitJobs(const ExperimentPlan& plan, const std::string& kind, const std::string& exe,
                     const std::string& ini) {
  const fs::path out(plan.output);
  fs::create_directories(out);
  if (kind == "slurm") {
    fs::create_directories(out / "slurm-logs");
    const std::string path = (out / "slurm.sh").string();
    writeTextFileAtomically(path, slurmScript(plan, exe, ini));
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
    return path;
  }
  if (kind == "parallel") {
    const std::string path = (out / "parallel.jobs").string();
    writeTextFileAtomically(path, parallelJobs(plan, exe, ini));
    return path;
  }
  throw std::invalid_argument("--emit: unknown kind '" + kind + "' (expected slurm or parallel)");
}

}  // namespace gridtopo::experiment
