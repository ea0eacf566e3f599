// The local runner with a stand-in for gridtopo-slam (a shell script that reads the run's RUN.ini, as
// `gridtopo-slam RUN/options.ini -q` does, and behaves by seed): ok runs are scored
// and recorded, a failing and a crashing run are recorded with their reason without stopping the others, finished
// runs are skipped on the next call (resume) unless forced, and a stop request ends a running run by its pid and
// records nothing for it.
#include "gridtopo/experiment/run_executor.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <thread>

#include "experiment/experiment_files.h"
#include "gridtopo/core/error.h"
#include "gridtopo/experiment/results_writer.h"
#include "gridtopo/experiment/run_record.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::experiment;

namespace {

// seed 1, 4: a three-step run; 2: exits 1 with an error line; 3: SIGSEGV; 5: sleeps (for the stop request).
const char* kFakeSlam = R"(#!/bin/sh
ini=$1
log=$(sed -n 's/^input = //p' "$ini")
out=$(sed -n 's/^output = //p' "$ini")
seed=$(sed -n 's/^seed = //p' "$ini")
case $seed in
  2) echo "gridtopo-slam: error: $log:3: FLASER: malformed line" >&2; exit 1;;
  3) kill -SEGV $$;;
  5) sleep 30;;
esac
mkdir -p "$out"
printf '# step scan timestamp time_s neff resampled particles failed_matches evaluations unique_tiles map_bytes\n' > "$out/stats.txt"
printf '0 0 1 0.01 8 0 8 0 0 0 0\n1 1 2 0.01 3.5 1 8 0 0 0 0\n2 2 3 0.01 8 0 8 0 0 0 0\n' >> "$out/stats.txt"
printf '1 0 0 0\n2 1 0 0\n3 2 0 0\n' > "$out/trajectory.txt"
)";

struct Fixture {
  fs::path dir;
  std::string slam;
  ExperimentPlan plan;
};

Fixture makeExperiment(const std::string& name, const std::string& seeds) {
  Fixture f;
  f.dir = test::scratch(name);
  f.slam = (f.dir / "fake-slam").string();
  test::writeText(f.slam, kFakeSlam);
  fs::permissions(f.slam, fs::perms::owner_all);
  test::writeText(f.dir / "log.dat", "not read by the stand-in\n");
  // 1 -> 2 exactly as estimated (error 0); 2 -> 3 off by 0.1 m; 1 -> 9 beyond the trajectory: not scored.
  test::writeText(f.dir / "rel.txt", "1 2 1 0 0 0 0 0\n2 3 0.9 0 0 0 0 0\n1 9 8 0 0 0 0 0\n");
  test::writeText(f.dir / "exp.ini", "[experiment]\nname = fake\noutput = out\n[record]\nplots = none\n"
                                     "[dataset.d]\nlog = log.dat\nrelations = rel.txt\n[sweep]\nseed = " + seeds + "\n");
  f.plan = planExperiment(loadExperimentSpec((f.dir / "exp.ini").string()));
  return f;
}

ExecutionOptions options(const Fixture& f, bool force = false) {
  ExecutionOptions o;
  o.jobs = 2;
  o.force = force;
  o.exe.slam = f.slam;
  o.progress = 0;
  return o;
}

}  // namespace

TEST(RunExecutor, RecordsOkFailedAndCrashedRunsAndResumes) {
  const Fixture f = makeExperiment("mixed", "1..4");
  std::ostringstream log;
  ExecutionSummary s = executeRuns(f.plan, {}, options(f), log);
  EXPECT_EQ(s.selected, 4u);
  EXPECT_EQ(s.ok, 2u);
  EXPECT_EQ(s.failed, 2u);
  EXPECT_EQ(s.skipped, 0u);
  EXPECT_FALSE(s.stopped);

  const auto records = collectRecords(f.plan);
  ASSERT_EQ(records.size(), 4u);
  const RunRecord& ok = records[0];
  EXPECT_EQ(ok.status, "ok");
  EXPECT_EQ(ok.relations_scored, 2u);
  EXPECT_NEAR(ok.trans_mean, 0.05, 1e-12);
  EXPECT_NEAR(ok.trans_max, 0.1, 1e-12);
  EXPECT_NEAR(ok.trans_std, std::sqrt(0.005), 1e-12);
  EXPECT_NEAR(ok.rot_mean, 0.0, 1e-12);
  EXPECT_NEAR(ok.trans_local_mean, 0.05, 1e-12);  // both scored relations are 1 s long: local
  EXPECT_TRUE(std::isnan(ok.trans_revisit_mean));  // no revisit among them
  EXPECT_EQ(ok.steps, 3u);
  EXPECT_EQ(ok.resamplings, 1u);
  EXPECT_GT(ok.wall_s, 0.0);
  EXPECT_GT(ok.peak_rss_mb, 0.0);
  EXPECT_FALSE(ok.start_time.empty());
  EXPECT_EQ(records[1].status, "failed");
  EXPECT_EQ(records[1].exit_code, 1);
  EXPECT_EQ(records[1].error, "exit code 1: gridtopo-slam: error: " + f.plan.runs[1].log + ":3: FLASER: malformed line");
  EXPECT_EQ(records[2].status, "crashed");
  EXPECT_EQ(records[2].signal, 11);
  EXPECT_EQ(records[2].error.rfind("killed by signal 11 (Segmentation fault)", 0), 0u) << records[2].error;
  EXPECT_EQ(records[3].status, "ok");
  // Every run folder holds the options.ini the run was started with.
  for (const auto& run : f.plan.runs) EXPECT_TRUE(fs::exists(fs::path(run.dir) / "options.ini")) << run.dir;

  // Again: the two ok runs are skipped, the failed and crashed ones run again.
  const auto first_start = fs::last_write_time(fs::path(f.plan.runs[0].dir) / "result.json");
  s = executeRuns(f.plan, {}, options(f), log);
  EXPECT_EQ(s.skipped, 2u);
  EXPECT_EQ(s.failed, 2u);
  EXPECT_EQ(fs::last_write_time(fs::path(f.plan.runs[0].dir) / "result.json"), first_start);
  EXPECT_NE(log.str().find("2 of 4 runs already done"), std::string::npos) << log.str();
  // --force: everything runs.
  s = executeRuns(f.plan, {}, options(f, true), log);
  EXPECT_EQ(s.skipped, 0u);
  EXPECT_EQ(s.ok + s.failed, 4u);
  // One run by index (a Slurm array task).
  s = executeRuns(f.plan, {3}, options(f, true), log);
  EXPECT_EQ(s.selected, 1u);
  EXPECT_EQ(s.ok, 1u);
}

TEST(RunExecutor, AStopRequestEndsTheRunningRunAndRecordsNothingForIt) {
  const Fixture f = makeExperiment("stop", "1 5 4");
  std::ostringstream log;
  ExecutionOptions o = options(f);
  o.jobs = 1;
  clearStopRequest();
  // Stop once seed 5 has started (with one job, seed 1 has then finished): its options.ini is written at launch.
  const fs::path sleeping = fs::path(f.plan.runs[1].dir) / "options.ini";
  std::thread stopper([&] {
    for (int i = 0; i < 3000 && !fs::exists(sleeping); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    requestStop();
  });
  const auto t0 = std::chrono::steady_clock::now();
  const ExecutionSummary s = executeRuns(f.plan, {}, o, log);
  stopper.join();
  clearStopRequest();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10.0);  // not 30 s
  EXPECT_TRUE(s.stopped);
  EXPECT_EQ(s.ok, 1u);           // seed 1 finished before the request
  EXPECT_EQ(s.interrupted, 2u);  // seed 5 stopped, seed 4 never started
  EXPECT_TRUE(fs::exists(fs::path(f.plan.runs[0].dir) / "result.json"));
  EXPECT_FALSE(fs::exists(fs::path(f.plan.runs[1].dir) / "result.json"));
  EXPECT_FALSE(fs::exists(fs::path(f.plan.runs[2].dir)));
  EXPECT_EQ(collectRecords(f.plan).size(), 1u);
}

TEST(RunExecutor, OneRunnerPerResultsFolder) {
  const Fixture f = makeExperiment("lock", "1 5");
  std::ostringstream log;
  ExecutionOptions o = options(f);
  clearStopRequest();
  std::thread first([&] {
    std::ostringstream first_log;
    try {
      executeRuns(f.plan, {}, o, first_log);  // seed 5 sleeps until the stop request
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }
  });
  const fs::path sleeping = fs::path(f.plan.runs[1].dir) / "options.ini";
  for (int i = 0; i < 3000 && !fs::exists(sleeping); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (!fs::exists(sleeping)) {
    requestStop();
    first.join();
    clearStopRequest();
    FAIL() << "the first runner did not start";
  }
  try {
    executeRuns(f.plan, {}, o, log);
    ADD_FAILURE() << "a second runner started";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), f.plan.output + ": another gridtopo-experiment is running in this results folder");
  }
  requestStop();
  first.join();
  clearStopRequest();
}

TEST(RunExecutor, DefaultJobsAreCoresOverThreads) {
  Fixture f = makeExperiment("jobs", "1");
  const long cores = std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN));
  f.plan.runs[0].threads = 1;
  EXPECT_EQ(defaultJobs(f.plan), cores);
  f.plan.runs[0].threads = 0;  // all cores
  EXPECT_EQ(defaultJobs(f.plan), 1);
  f.plan.runs[0].threads = static_cast<int>(cores) * 4;
  EXPECT_EQ(defaultJobs(f.plan), 1);
}

// A topology run's processes one after the other (stand-ins for gridtopo-topology and gridtopo-topology-compare):
// the second starts only when the first exited with 0, the record holds compare.json's and topology.json's numbers
// and both processes' CPU time; a failing gridtopo-topology ends the run with its error, and nothing is compared.
TEST(RunExecutor, TopologyRunsChainTheirProcesses) {
  const fs::path dir = test::scratch("topology");
  const std::string topo = (dir / "fake-topology").string(), compare = (dir / "fake-compare").string();
  test::writeText(topo, R"(#!/bin/sh
out=$(sed -n 's/^output = //p' "$1")
if grep -q '^segmentation = doorways' "$1"; then echo "gridtopo-topology: error: $1: boom" >&2; exit 1; fi
mkdir -p "$out"
printf '{"nodes": [{"id": 1}, {"id": 2}, {"id": 3}], "edges": [{"from": 1, "to": 2}]}\n' > "$out/topology.json"
i=0; while [ $i -lt 200000 ]; do i=$((i+1)); done
)");
  test::writeText(compare, R"(#!/bin/sh
while [ $# -gt 0 ]; do case $1 in -j) json=$2; shift 2;; *) shift;; esac; done
printf '{"labels": {"accuracy": 0.75, "recall": [0.5, 0.25, 0.125]}, "segmentation": {"recall": 0.9, "precision": 0.8}, "graph": {"attached_fraction": 0.6, "loops_closed": 1, "plan_loops": 2}}\n' > "$json"
)");
  for (const auto& p : {topo, compare}) fs::permissions(p, fs::perms::owner_all);
  test::writeText(dir / "map.png", "not read by the stand-ins\n");
  test::writeText(dir / "exp.ini", "[experiment]\noutput = out\nplaces_model = map.png\n[record]\nplots = none\n"
                                   "[dataset.d]\nmap = map.png\nplan = map.png\nplan_labels = map.png\n"
                                   "plan_segmentation = map.png\n[topology]\nthreads = 1\n"
                                   "[sweep]\ntopology.segmentation = regions doorways\n");
  const ExperimentPlan plan = planExperiment(loadExperimentSpec((dir / "exp.ini").string()));
  ExecutionOptions o;
  o.jobs = 2;
  o.exe = {"/nonexistent/gridtopo-slam", topo, compare};
  o.progress = 0;
  std::ostringstream log;
  const ExecutionSummary s = executeRuns(plan, {}, o, log);
  EXPECT_EQ(s.ok, 1u);
  EXPECT_EQ(s.failed, 1u);
  const auto records = collectRecords(plan);
  ASSERT_EQ(records.size(), 2u);
  const RunRecord& ok = records[0];
  ASSERT_EQ(ok.status, "ok") << ok.error;
  EXPECT_TRUE(ok.topology);
  EXPECT_EQ(ok.graph_nodes, 3u);
  EXPECT_EQ(ok.graph_edges, 1u);
  EXPECT_EQ(ok.label_accuracy, 0.75);
  EXPECT_EQ(ok.recall_room, 0.5);
  EXPECT_EQ(ok.recall_corridor, 0.25);
  EXPECT_EQ(ok.recall_doorway, 0.125);
  EXPECT_EQ(ok.seg_recall, 0.9);
  EXPECT_EQ(ok.seg_precision, 0.8);
  EXPECT_EQ(ok.graph_attached, 0.6);
  EXPECT_EQ(ok.graph_loops_closed, 1.0);
  EXPECT_EQ(ok.graph_plan_loops, 2.0);
  EXPECT_EQ(ok.relations_scored, 0u);
  EXPECT_GT(ok.cpu_s, 0.05);  // the busy loop of the first process counts
  EXPECT_TRUE(fs::is_regular_file(fs::path(ok.dir) / "compare.log"));
  EXPECT_FALSE(fs::exists(fs::path(ok.dir) / "options.ini"));  // no SLAM run, no SLAM RUN.ini
  const RunRecord& failed = records[1];
  EXPECT_EQ(failed.status, "failed");
  EXPECT_EQ(failed.error, "topology: exit code 1: gridtopo-topology: error: " + plan.runs[1].dir + "/topology.ini: boom");
  EXPECT_FALSE(fs::exists(fs::path(failed.dir) / "compare.log"));
  // The CSV has the topology columns; the failed run's are empty.
  const std::string csv = resultsCsv(plan, records);
  EXPECT_NE(csv.find(",resamplings,graph_nodes,graph_edges,label_accuracy,recall_room,recall_corridor,recall_doorway,"
                     "seg_recall,seg_precision,graph_attached,graph_loops_closed,graph_plan_loops,wall_s,"),
            std::string::npos);
  EXPECT_NE(csv.find(",,0,0,3,1,0.75,0.5,0.25,0.125,0.9,0.8,0.6,1,2,"),
            std::string::npos)
      << csv;
}
