#pragma once
// The experiment's plots, drawn by gnuplot: error vs particles (mean over seeds, std as error bars), success rate
// vs particles and wall time vs particles, one line per combination of the other varied keys (dataset, proposal,
// ...); on request (plots = neff) N_eff / particles over the processed steps, one plot per group of runs that
// differ by their seed (plots/neff/GROUP.*), one line per run. Each plot is a .gp script beside its data
// (plots/by_particles.dat, plots/neff/GROUP.dat) and its pictures (.png and .svg), so users can restyle it and run
// `gnuplot NAME.gp` again in that folder.
#include <string>
#include <vector>

#include "gridtopo/experiment/run_record.h"

namespace gridtopo::experiment {

struct PlotFiles {
  std::vector<std::string> scripts;   ///< the .gp files written
  std::vector<std::string> pictures;  ///< the .png / .svg files gnuplot made
  std::vector<std::string> notes;     ///< why a plot is missing (no gnuplot, no data, gnuplot failed)
};

/// The data file (series blocks: particles, error mean, error std, success rate, wall mean, wall std, runs).
std::string particlesTable(const ExperimentPlan& plan, const std::vector<RunRecord>& records);
/// The gnuplot script of one plot ("error", "success" or "time"), reading by_particles.dat.
std::string plotScript(const ExperimentPlan& plan, const std::vector<RunRecord>& records, const std::string& which);

/// Writes plots/ under plan.output and runs gnuplot (found on PATH) on each script of plan.spec.plots.
/// The neff plots read each ok run's RUN/out/stats.txt.
PlotFiles drawPlots(const ExperimentPlan& plan, const std::vector<RunRecord>& records);

/// The first executable `name` on PATH, or "".
std::string findOnPath(const std::string& name);

}  // namespace gridtopo::experiment
