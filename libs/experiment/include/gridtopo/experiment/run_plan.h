#pragma once
// The runs of an experiment: the sweep expanded, each combination turned into the exact options of one
// gridtopo-slam run (base INI, then [slam], then the swept values), loaded through slam::SlamOptions so that a
// wrong key or value stops the experiment before anything runs, and keyed by a hash of those options and of the
// input files' contents.
#include <string>
#include <vector>

#include "gridtopo/experiment/experiment_spec.h"
#include "gridtopo/experiment/sweep.h"
#include "gridtopo/slam/slam_options.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::experiment {

struct PlannedRun {
  std::size_t index = 0;  ///< position in the expanded sweep (the --run-index of a Slurm array task)
  std::string id;         ///< 16 hex digits of sha256(options, max_scans, log and relations contents)
  std::string label;      ///< the varied values, readable ("intel_informed_particles-8_seed-1")
  std::string dir;        ///< OUTPUT/runs/<label>_<id>
  Assignment params;      ///< every swept key with its value, in sweep order (dataset first)
  std::string dataset, log, relations;
  long max_scans = -1;      ///< -1: the whole log
  int threads = 0;          ///< of the run's [slam] options (0 = all cores)
  bool slam = true;           ///< a gridtopo-slam run (the dataset has a log)
  slam::SlamOptions options;  ///< the run's filter options (base INI, [slam], swept values)
  std::string options_ini;    ///< their [slam] section, every key (slam::slamOptionsIni); the run id hashes it
  // Topology (spec.topologyRuns()): gridtopo-topology on `map`, then gridtopo-topology-compare against the plan.
  bool topology = false;
  topology::TopologyOptions topology_options;  ///< topology_ini, the fixed sections, the swept topology keys
  std::string topology_options_ini;            ///< topology::topologyOptionsIni of them (hashed into the id)
  std::string map;    ///< the topology's input: RUN/out/map.yaml after a SLAM run, else the dataset's map
  std::string model;  ///< the place model
  std::string plan, plan_labels, plan_segmentation;  ///< the dataset's labelled plan (empty: no comparison)
};

struct ExperimentPlan {
  ExperimentSpec spec;
  std::string output;                     ///< results folder
  std::vector<PlannedRun> runs;
  std::vector<std::string> slam_keys;     ///< every [slam] option key, in the order options.ini lists them
  std::vector<std::string> topology_keys; ///< with topology runs: every topology option as section.key, in order
  std::vector<std::string> varied_keys;   ///< swept keys with more than one value, dataset first
};

/// Plans every run. `output` overrides the spec's output folder (relative to the current directory); one of the
/// two must be given (InputError otherwise). Bad [slam] keys or values: InputError naming the experiment INI (or
/// the base INI), the line and "[section] key".
ExperimentPlan planExperiment(const ExperimentSpec& spec, const std::string& output = "");

/// The value of `key` in an options.ini text ("" when absent).
std::string optionValue(const std::string& options_ini, const std::string& key);

/// The run's options.ini, a RUN.ini that `gridtopo-slam RUN/options.ini` runs alone: a comment block (experiment,
/// run, the command that reproduces it), then slam::slamRunIni: [slam_run] (the log, RUN/out, max_scans; 0 = every
/// scan) and [slam] with every option.
std::string runIniText(const ExperimentPlan& plan, const PlannedRun& run, const std::string& slam_exe);

/// The gridtopo-slam arguments of a run (argv[0] = slam_exe): `gridtopo-slam RUN/options.ini -q`.
std::vector<std::string> slamCommand(const PlannedRun& run, const std::string& slam_exe);

/// The run's topology RUN.ini, RUN/topology.ini: a comment block, then topology::topologyRunIni ([topology_run] map,
/// model, output = RUN/topology; the option sections).
std::string topologyIniText(const ExperimentPlan& plan, const PlannedRun& run);

/// The processes of a run, in order; each starts when the one before exited with 0.
struct RunStage {
  std::string name;               ///< slam, topology, compare
  std::vector<std::string> argv;  ///< argv[0]: the executable
  std::string log;                ///< RUN/<name>.log
};
struct Executables {
  std::string slam, topology, compare;  ///< gridtopo-slam, gridtopo-topology, gridtopo-topology-compare
};
/// slam: `gridtopo-slam RUN/options.ini -q`; topology: `gridtopo-topology RUN/topology.ini -q`; compare (with a
/// plan): `gridtopo-topology-compare MAP RUN/topology -c RUN/topology/options.ini --reference-map PLAN
/// --reference-labels LABELS --reference-segmentation SEG -j RUN/topology/compare.json`.
std::vector<RunStage> runStages(const PlannedRun& run, const Executables& exe);

}  // namespace gridtopo::experiment
