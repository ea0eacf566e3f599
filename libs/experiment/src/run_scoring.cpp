#include "gridtopo/experiment/run_scoring.h"

#include <algorithm>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <sstream>

#include "gridtopo/core/error.h"
#include "gridtopo/io/carmen_log.h"

namespace gridtopo::experiment {

StepSummary summarizeSteps(const std::string& stats_text, const std::string& name) {
  StepSummary s;
  std::istringstream in(stats_text);
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream f(line);
    double step, scan, t, time_s, neff;
    int resampled;
    if (!(f >> step >> scan >> t >> time_s >> neff >> resampled))
      throw InputError(name, n, "neff/resampled", "expected the columns of gridtopo-slam's stats.txt");
    ++s.steps;
    s.resamplings += resampled != 0;
    s.neff.push_back(neff);
  }
  return s;
}

std::vector<eval::Relation> relationsWithin(const std::vector<eval::Relation>& relations,
                                            const std::vector<TimedPose>& trajectory) {
  if (trajectory.empty()) return {};
  double first = trajectory.front().timestamp, last = first;
  for (const auto& p : trajectory) {
    first = std::min(first, p.timestamp);
    last = std::max(last, p.timestamp);
  }
  std::vector<eval::Relation> out;
  for (const auto& r : relations)
    if (std::min(r.t1, r.t2) >= first && std::max(r.t1, r.t2) <= last) out.push_back(r);
  return out;
}

ErrorScores RunScorer::score(const std::vector<TimedPose>& trajectory, const std::string& log,
                             const std::string& relations) {
  ErrorScores s;
  if (relations.empty() || trajectory.empty()) return s;
  auto& ref = cache_[relations + "\n" + log];
  if (!ref) {
    ref = std::make_shared<Reference>();
    ref->relations = eval::readRelations(relations);
    // Gap correction by the log's odometry when it is a CARMEN log (as gridtopo-eval --log); none otherwise.
    const bool carmen = log.find(".clf") != std::string::npos || log.find(".log") != std::string::npos;
    if (carmen) {
      const io::CarmenLog l = io::readCarmenLog(log);
      ref->odometry = eval::OdometryTrack::fromScans(l.scans, l.odometry, eval::OdometrySource::Auto);
    }
#if defined(__GLIBC__)
    // Give the parsed log's pages back: a run forked later starts with this process's resident pages, and its
    // peak RSS (wait4) is at least that.
    malloc_trim(0);
#endif
  }
  const auto within = relationsWithin(ref->relations, trajectory);
  if (within.empty()) return s;
  const auto r = eval::evaluateRelations(trajectory, within, ref->odometry.empty() ? nullptr : &ref->odometry);
  s.relations = within.size();
  s.translational = r.translational;
  s.rotational = r.rotational;
  s.local = r.local;
  s.revisit = r.revisit;
  return s;
}

}  // namespace gridtopo::experiment
