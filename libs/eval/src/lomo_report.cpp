#include "gridtopo/eval/lomo_report.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "gridtopo/eval/report.h"

namespace gridtopo::eval {

std::string percent(double v) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(1) << 100.0 * v;
  return o.str();
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}

double sampleStd(const std::vector<double>& v) {
  if (v.size() < 2) return 0;
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

namespace {

constexpr int kDoorway = 2;

std::string mapJson(const MapLabelScores& s, bool vote, bool blob) {
  std::ostringstream o;
  o << "    {\"map\": " << jsonString(s.map) << ", \"order\": " << jsonString(s.order)
    << ", \"relaxation_iterations\": " << s.relaxation_iterations
    << ", \"accuracy_before\": " << s.before.accuracy() << ", \"accuracy_after\": " << s.after.accuracy()
    << ", \"accuracy_corrected\": " << s.corrected.accuracy()
    << (vote ? ", \"accuracy_segment_vote\": " + std::to_string(s.segment_vote.accuracy()) : std::string())
    << (blob ? ", \"accuracy_blob_vote\": " + std::to_string(s.blob_vote.accuracy()) : std::string())
    << ", \"oracle_region_vote_accuracy\": " << s.oracle_region_vote.accuracy()
    << ", \"oracle_region_vote_keep_doorways_accuracy\": " << s.oracle_region_vote_keep_doorways.accuracy()
    << ", \"blob_oracle_accuracy\": " << s.blob_oracle.accuracy()
    << ", \"doorway_recall_before\": " << s.before.recall(kDoorway)
    << ", \"doorway_recall_after\": " << s.after.recall(kDoorway) << ", \"after_relaxation\": " << s.after.toJson(6)
    << "}";
  return o.str();
}

// Mean / std over the benchmark maps of one score.
template <class F>
std::vector<double> column(const std::vector<BenchmarkRun>& runs, F f) {
  std::vector<double> v;
  for (const auto& x : runs) v.push_back(f(x));
  return v;
}
std::vector<double> precisions(const std::vector<BenchmarkRun>& r) {
  return column(r, [](const BenchmarkRun& x) { return x.score.precision; });
}
std::vector<double> recalls(const std::vector<BenchmarkRun>& r) {
  return column(r, [](const BenchmarkRun& x) { return x.score.recall; });
}
std::vector<double> seconds(const std::vector<BenchmarkRun>& r) {
  return column(r, [](const BenchmarkRun& x) { return x.seconds; });
}
std::vector<double> precisionsWeighted(const std::vector<BenchmarkRun>& r) {
  return column(r, [](const BenchmarkRun& x) { return x.score.precision_weighted; });
}
std::vector<double> recallsWeighted(const std::vector<BenchmarkRun>& r) {
  return column(r, [](const BenchmarkRun& x) { return x.score.recall_weighted; });
}

std::string benchmarkJson(const char* name, const std::vector<BenchmarkRun>& runs) {
  std::ostringstream o;
  const auto p = precisions(runs), r = recalls(runs);
  o << ",\n  \"" << name << "\": {\"precision_mean\": " << mean(p) << ", \"precision_std\": " << sampleStd(p)
    << ", \"recall_mean\": " << mean(r) << ", \"recall_std\": " << sampleStd(r)
    << ", \"seconds_mean\": " << mean(seconds(runs)) << ", \"maps\": [";
  for (std::size_t k = 0; k < runs.size(); ++k)
    o << (k ? ", " : "") << "\n      {\"map\": " << jsonString(runs[k].map) << ", \"score\": " << runs[k].score.toJson()
      << ", \"seconds\": " << runs[k].seconds << "}";
  o << "]}";
  return o.str();
}

// "mean ± std / mean ± std" of recall and precision.
std::string recallPrecision(const std::vector<double>& r, const std::vector<double>& p) {
  return percent(mean(r)) + " ± " + percent(sampleStd(r)) + " / " + percent(mean(p)) + " ± " + percent(sampleStd(p));
}

}  // namespace

std::string mapScoreLine(const MapLabelScores& s, bool vote, bool blob) {
  std::ostringstream o;
  o << s.map << ": order " << s.order << " acc before " << percent(s.before.accuracy()) << " after "
    << percent(s.after.accuracy()) << " corrected " << percent(s.corrected.accuracy())
    << (vote ? " vote " + percent(s.segment_vote.accuracy()) : std::string())
    << (blob ? " blob vote " + percent(s.blob_vote.accuracy()) : std::string()) << " oracle region vote "
    << percent(s.oracle_region_vote.accuracy()) << " (keeping doorways "
    << percent(s.oracle_region_vote_keep_doorways.accuracy()) << ") blob oracle " << percent(s.blob_oracle.accuracy())
    << " door recall " << percent(s.before.recall(kDoorway)) << "/" << percent(s.after.recall(kDoorway));
  return o.str();
}

std::string lomoJson(const LomoResult& r) {
  const MapLabelScores& t = r.pooled;
  std::ostringstream js;
  js << "{\n  \"mode\": " << jsonString(r.mode) << ",\n"
     << "  \"labels\": {\n    \"before_relaxation\": " << t.before.toJson(4)
     << ",\n    \"after_relaxation\": " << t.after.toJson(4) << ",\n    \"after_correction\": "
     << t.corrected.toJson(4)
     << (r.segment_vote ? ",\n    \"after_segment_vote\": " + t.segment_vote.toJson(4) : std::string())
     << (r.blob_vote ? ",\n    \"after_blob_vote\": " + t.blob_vote.toJson(4) : std::string())
     << ",\n    \"oracle_region_vote_accuracy\": " << t.oracle_region_vote.accuracy()
     << ",\n    \"oracle_region_vote\": " << t.oracle_region_vote.toJson(4)
     << ",\n    \"oracle_region_vote_keep_doorways_accuracy\": " << t.oracle_region_vote_keep_doorways.accuracy()
     << ",\n    \"blob_oracle_accuracy\": " << t.blob_oracle.accuracy() << ",\n    \"per_map\": [\n";
  for (std::size_t i = 0; i < r.maps.size(); ++i)
    js << (i ? ",\n" : "") << mapJson(r.maps[i], r.segment_vote, r.blob_vote);
  js << "\n    ]\n  }";
  if (r.segmentation)
    js << benchmarkJson("segmentation_plain", r.plain) << benchmarkJson("segmentation_furnitures", r.furnished);
  js << "\n}\n";
  return js.str();
}

std::string lomoMarkdown(const LomoResult& r) {
  const MapLabelScores& t = r.pooled;
  std::vector<double> after;
  for (const auto& m : r.maps) after.push_back(m.after.accuracy());
  std::ostringstream md;
  md << "| measure | value |\n|---|---|\n"
     << "| cell accuracy before relaxation (pooled over maps) | " << percent(t.before.accuracy()) << " % |\n"
     << "| cell accuracy after relaxation (pooled) | " << percent(t.after.accuracy()) << " % |\n"
     << (r.blob_vote ? "| cell accuracy after blob vote, before correction (pooled) | " +
                           percent(t.blob_vote.accuracy()) + " % |\n"
                     : std::string())
     << "| cell accuracy after region correction (pooled) | " << percent(t.corrected.accuracy()) << " % |\n"
     << (r.segment_vote ? "| cell accuracy after region correction and segment vote (pooled) | " +
                              percent(t.segment_vote.accuracy()) + " % |\n"
                        : std::string())
     << "| diagnostic: oracle region vote (ground-truth regions, relaxed probabilities; pooled) | "
     << percent(t.oracle_region_vote.accuracy())
     << " % (predicted doorways kept: " << percent(t.oracle_region_vote_keep_doorways.accuracy()) << " %) |\n"
     << "| diagnostic: blob oracle (geometric blobs voted with their true majority; pooled) | "
     << percent(t.blob_oracle.accuracy()) << " % |\n"
     << "| cell accuracy after relaxation, mean ± std over maps | " << percent(mean(after)) << " ± "
     << percent(sampleStd(after)) << " % |\n"
     << "| recall room / corridor / doorway (after relaxation) | " << percent(t.after.recall(0)) << " / "
     << percent(t.after.recall(1)) << " / " << percent(t.after.recall(2)) << " % |\n"
     << "| precision room / corridor / doorway (after relaxation) | " << percent(t.after.precision(0)) << " / "
     << percent(t.after.precision(1)) << " / " << percent(t.after.precision(2)) << " % |\n"
     << "| doorway recall before → after relaxation | " << percent(t.before.recall(kDoorway)) << " → "
     << percent(t.after.recall(kDoorway)) << " % |\n";
  if (r.segmentation) {
    int segments = 0, rooms = 0, segments_furnished = 0;
    for (const auto& x : r.plain) segments += x.score.segments, rooms += x.score.rooms;
    for (const auto& x : r.furnished) segments_furnished += x.score.segments;
    md << "| segmentation unfurnished: recall / precision (mean ± std over maps) | "
       << recallPrecision(recalls(r.plain), precisions(r.plain)) << " % |\n"
       << "| segmentation furnished: recall / precision | "
       << recallPrecision(recalls(r.furnished), precisions(r.furnished)) << " % |\n"
       << "| segmentation unfurnished, pixel-weighted: recall / precision | "
       << recallPrecision(recallsWeighted(r.plain), precisionsWeighted(r.plain)) << " % |\n"
       << "| segmentation furnished, pixel-weighted: recall / precision | "
       << recallPrecision(recallsWeighted(r.furnished), precisionsWeighted(r.furnished)) << " % |\n"
       << "| segments / ground-truth rooms (sum over maps), unfurnished; furnished | " << segments << " / " << rooms
       << "; " << segments_furnished << " / " << rooms << " |\n"
       << "| seconds per benchmark map (labelling + topology, " << r.threads << " threads) | "
       << std::setprecision(3) << mean(seconds(r.plain)) << " (plain), " << mean(seconds(r.furnished))
       << " (furnished) |\n";
  }
  return md.str();
}

}  // namespace gridtopo::eval
