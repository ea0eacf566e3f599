// The tables of an experiment: the CSV's schema (column names and order), one row per record with its values,
// the success flag against the threshold, JSON lines, and the summary's grouping over seeds with its statistics.
#include "gridtopo/experiment/results_writer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "experiment/experiment_files.h"
#include "gridtopo/experiment/run_statistics.h"

namespace fs = std::filesystem;
using namespace gridtopo;
using namespace gridtopo::experiment;

namespace {

ExperimentPlan plan() {
  const fs::path dir = test::scratch("plan");
  test::writeText(dir / "exp.ini", "[experiment]\nname = tables\noutput = out\n[record]\nsuccess_threshold = 0.05\n"
                                   "[dataset.intel]\nlog = " + std::string(GRIDTOPO_DATA_DIR) +
                                       "/slam/intel.clf.gz\n[sweep]\nproposal = informed odometry\nseed = 1..3\n");
  return planExperiment(loadExperimentSpec((dir / "exp.ini").string()));
}

RunRecord record(const ExperimentPlan& p, std::size_t i, double trans_mean, const std::string& status = "ok") {
  RunRecord r = recordOf(p.runs[i]);
  r.status = status;
  r.relations_scored = status == "ok" ? 10 : 0;
  r.trans_mean = status == "ok" ? trans_mean : NAN;
  r.trans_std = r.trans_max = r.rot_mean = r.rot_std = r.rot_max = status == "ok" ? 0.5 : NAN;
  r.trans_local_mean = status == "ok" ? 0.25 : NAN;
  r.trans_revisit_mean = NAN;  // no revisit relations
  r.steps = 100;
  r.resamplings = 7;
  r.wall_s = 2.0 + static_cast<double>(i);
  r.cpu_s = 1.5;
  r.peak_rss_mb = 100.0 + static_cast<double>(i);
  r.commit = "abc";
  r.host = "h";
  r.start_time = "2026-01-01T00:00:00Z";
  if (status != "ok") r.error = "exit code 1: bad \"line\", see log";
  return r;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cur += '"', ++i;
      else if (c == '"') quoted = false;
      else cur += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.push_back(cur), cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

}  // namespace

TEST(ResultsWriter, CsvSchema) {
  const ExperimentPlan p = plan();
  const auto cols = resultsColumns(p);
  const std::vector<std::string> head = {"index", "id", "label", "status", "dataset", "log", "relations", "max_scans"};
  const std::vector<std::string> tail = {"relations_scored", "trans_mean_m", "trans_std_m", "trans_max_m",
                                         "rot_mean_deg", "rot_std_deg", "rot_max_deg", "trans_local_mean_m",
                                         "trans_revisit_mean_m", "success", "steps",
                                         "resamplings", "wall_s", "cpu_s", "peak_rss_mb", "commit", "host",
                                         "start_time", "error", "dir"};
  ASSERT_EQ(cols.size(), head.size() + p.slam_keys.size() + tail.size());
  EXPECT_EQ(std::vector<std::string>(cols.begin(), cols.begin() + 8), head);
  EXPECT_EQ(std::vector<std::string>(cols.end() - static_cast<long>(tail.size()), cols.end()), tail);
  // Every [slam] option is a column, in options.ini's order, starting with the filter's keys.
  EXPECT_GE(p.slam_keys.size(), 60u);
  EXPECT_EQ(cols[8], "particles");
  EXPECT_EQ(cols[9], "seed");
  EXPECT_EQ(cols[10], "threads");
  EXPECT_NE(std::find(cols.begin(), cols.end(), "proposal"), cols.end());

  std::vector<RunRecord> recs = {record(p, 0, 0.04), record(p, 1, 0.06), record(p, 2, 0, "failed")};
  const std::string csv = resultsCsv(p, recs);
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(split(line), cols);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) rows.push_back(split(line));
  ASSERT_EQ(rows.size(), 3u);
  auto at = [&](std::size_t row, const std::string& col) {
    return rows[row][static_cast<std::size_t>(std::find(cols.begin(), cols.end(), col) - cols.begin())];
  };
  for (const auto& r : rows) EXPECT_EQ(r.size(), cols.size());
  EXPECT_EQ(at(0, "index"), "0");
  EXPECT_EQ(at(0, "proposal"), "informed");
  EXPECT_EQ(at(1, "seed"), "2");
  EXPECT_EQ(at(0, "trans_mean_m"), "0.04");
  EXPECT_EQ(at(0, "success"), "1");  // 0.04 <= 0.05
  EXPECT_EQ(at(1, "success"), "0");  // 0.06 > 0.05
  EXPECT_EQ(at(2, "success"), "0");  // failed
  EXPECT_EQ(at(2, "trans_mean_m"), "");
  EXPECT_EQ(at(0, "trans_local_mean_m"), "0.25");
  EXPECT_EQ(at(0, "trans_revisit_mean_m"), "");
  EXPECT_EQ(at(2, "trans_local_mean_m"), "");
  EXPECT_EQ(at(2, "status"), "failed");
  EXPECT_EQ(at(2, "error"), "exit code 1: bad \"line\", see log");
  EXPECT_EQ(at(1, "peak_rss_mb"), "101");
  EXPECT_EQ(at(1, "resamplings"), "7");
  EXPECT_EQ(at(0, "max_scans"), "");

  std::istringstream jl(resultsJsonl(p, recs));
  std::vector<nlohmann::json> js;
  while (std::getline(jl, line)) js.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(js.size(), 3u);
  EXPECT_EQ(js[0]["success"], true);
  EXPECT_EQ(js[1]["success"], false);
  EXPECT_EQ(js[2]["trans_mean_m"], nullptr);
  EXPECT_EQ(js[1]["params"]["seed"], "2");
  EXPECT_EQ(js[1]["options"]["proposal"], "informed");
  // A record survives its JSON.
  const RunRecord back = recordFromJson(toJson(recs[1]), "x");
  EXPECT_EQ(back.id, recs[1].id);
  EXPECT_EQ(back.trans_mean, 0.06);
  EXPECT_EQ(back.options, recs[1].options);
  EXPECT_TRUE(std::isnan(recordFromJson(toJson(recs[2]), "x").trans_mean));
}

TEST(ResultsWriter, SummaryGroupsBySweptKeysButSeed) {
  const ExperimentPlan p = plan();
  std::vector<RunRecord> recs = {record(p, 0, 0.01), record(p, 1, 0.02), record(p, 2, 0.06),
                                 record(p, 3, 0.10), record(p, 4, 0, "crashed"), record(p, 5, 0.30)};
  const std::string md = summaryMarkdown(p, recs);
  // informed: 0.01 0.02 0.06 -> mean 0.03, std 0.0265, median 0.02; success 2/3.
  EXPECT_NE(md.find("| intel | informed | 3 | 0 | 0.0300 | 0.0265 | 0.0200 | 0.0100 | 0.0600 | 0.500 | 2/3 | 3.0 |"),
            std::string::npos)
      << md;
  // odometry: one crashed run (counts as failed, not in the error statistics): 0.10 0.30; success 0/3.
  EXPECT_NE(md.find("| intel | odometry | 3 | 1 | 0.2000 | 0.1414 | 0.2000 | 0.1000 | 0.3000 | 0.500 | 0/3 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("## Failed runs"), std::string::npos);
  EXPECT_NE(md.find("| 4 intel_odometry_seed-2 | crashed |"), std::string::npos) << md;
}

TEST(ResultsWriter, Spread) {
  const Spread s = Spread::of({3, 1, NAN, 2, 10});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 4.0);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 10.0);
  EXPECT_NEAR(s.std, std::sqrt((9 + 1 + 4 + 36) / 3.0), 1e-12);
  EXPECT_TRUE(std::isnan(Spread::of({}).mean));
  EXPECT_EQ(Spread::of({5}).std, 0.0);
}
