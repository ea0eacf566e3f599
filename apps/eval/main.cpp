// gridtopo-eval: scores an estimated trajectory against the ground-truth relations of the Freiburg SLAM
// benchmark with the relations metric of Kümmerle et al. 2009 (see doc/evaluation.md).
#include <tclap/CmdLine.h>

#include <iostream>

#include "gridtopo/core/app_shell.h"
#include "gridtopo/core/run_args.h"
#include "gridtopo/eval/relations_run.h"

using namespace gridtopo;

int main(int argc, char** argv) {
  return gridtopo::runApp("gridtopo-eval", [&]() -> int {
    TCLAP::CmdLine cmd(
        "Scores an estimated trajectory against ground-truth relations (Kuemmerle et al. 2009, Freiburg SLAM "
        "benchmark): nearest estimated pose per relation timestamp, carried over gaps > --max-gap by odometry; "
        "translational / rotational error mean +- sample std, min, max, absolute and squared.\n"
        "Example: gridtopo-eval --relations datasets/slam/intel.relations.gz --log datasets/slam/intel.clf.gz "
        "--gfs datasets/slam/intel.gfs.log.gz --odometry laser --json out.json",
        ' ', "0.1");
    TCLAP::ValueArg<std::string> relations("r", "relations", "ground-truth relations file (plain or .gz)", true, "",
                                           "file", cmd);
    TCLAP::ValueArg<std::string> log("l", "log", "raw CARMEN log (plain or .gz): odometry for the gap correction",
                                     false, "", "file", cmd);
    TCLAP::ValueArg<std::string> trajectory("t", "trajectory", "estimated trajectory: 'timestamp x y theta' lines",
                                            false, "", "file", cmd);
    TCLAP::ValueArg<std::string> gfs("g", "gfs",
                                     "estimate as a CARMEN log with corrected poses (e.g. GMapping's .gfs.log.gz); "
                                     "needs --log",
                                     false, "", "file", cmd);
    TCLAP::SwitchArg baseline("", "baseline-odometry",
                              "estimate = the raw log's odometry (laser lines): the no-SLAM baseline", cmd);
    TCLAP::ValueArg<std::string> gfs_match("", "gfs-match",
                                           "how --gfs timestamps find the raw laser lines: auto (ipc if all match "
                                           "exactly, else logger), ipc, logger (nearest logger timestamp, the "
                                           "reference convention), ranges (logger + identical ranges)",
                                           false, "auto", "auto|ipc|logger|ranges", cmd);
    TCLAP::ValueArg<std::string> gfs_pose("", "gfs-pose", "which pose of the --gfs laser lines: robot or laser",
                                          false, "robot", "robot|laser", cmd);
    TCLAP::ValueArg<std::string> odometry("o", "odometry",
                                          "odometry for the gap correction: odom (ODOM lines), laser (odometry inside "
                                          "the laser lines), auto (odom if the log has ODOM lines) [default from "
                                          "--config, else auto]",
                                          false, "auto", "auto|odom|laser", cmd);
    TCLAP::SwitchArg interpolate("i", "interpolate",
                                 "interpolate the odometry between readings instead of taking the nearest reading",
                                 cmd);
    TCLAP::SwitchArg interpolate_estimate(
        "", "interpolate-estimate",
        "beyond --max-gap, blend the poses carried over from the estimates before and after the relation time "
        "(a variant, not the benchmark's definition)",
        cmd);
    TCLAP::ValueArg<double> max_gap("", "max-gap", "seconds: nearer estimated poses are used as they are [0.1]",
                                    false, 0.1, "s", cmd);
    TCLAP::ValueArg<double> revisit_span("", "revisit-span", "seconds: relations with |t2 - t1| over this are "
                                         "revisits, the others local (errors of each) [50]", false, 50.0, "s", cmd);
    TCLAP::ValueArg<std::string> config("c", "config", "INI file with a [relations_metric] section (config-ini/eval.ini)",
                                        false, "", "file", cmd);
    TCLAP::ValueArg<std::string> json("j", "json", "write the result as JSON to this file", false, "", "file", cmd);
    TCLAP::ValueArg<std::string> errors("e", "errors", "write per-relation errors to this text file", false, "",
                                        "file", cmd);
    TCLAP::SwitchArg skip_bad("", "skip-bad-lines", "skip (and count) malformed lines of CARMEN logs", cmd);
    TCLAP::SwitchArg partial("", "partial",
                             "score the relations inside the estimate's time span even when most relations lie "
                             "outside it (a trajectory of part of the log); without it such a run is refused",
                             cmd);
    HelpOptionsArg help_options(cmd, eval::relationsMetricOptionsHelp);
    cmd.setExceptionHandling(false);
    cmd.parse(argc, argv);

    eval::RelationsRunSpec spec;
    spec.relations = relations.getValue(), spec.log = log.getValue(), spec.trajectory = trajectory.getValue();
    spec.corrected_log = gfs.getValue(), spec.baseline_odometry = baseline.getValue();
    spec.read.skip_bad_lines = skip_bad.getValue();
    spec.partial = partial.getValue();
    eval::configureRelationsRun(spec, given(config), {odometry.isSet() ? odometry.getValue() : "", gfs_match.getValue(),
                                                      gfs_pose.getValue(), interpolate.getValue(),
                                                      interpolate_estimate.getValue(), given(max_gap),
                                                      given(revisit_span)});

    for (const auto* out : {&json, &errors})  // an unusable output is said before the scoring
      if (!out->getValue().empty()) checkOutputFile(out->getValue());
    const eval::RelationsRun scored = eval::runRelations(spec, std::cerr);
    std::cout << eval::relationsRunText(scored);
    std::cerr << eval::relationsRunWarnings(scored);
    eval::writeRelationsOutputs(scored, json.getValue(), errors.getValue());
    return 0;
  });
}
