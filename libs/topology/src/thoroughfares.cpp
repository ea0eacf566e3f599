#include "gridtopo/topology/thoroughfares.h"

#include <cmath>
#include <deque>
#include <map>

#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/door_passages.h"
#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

namespace {
constexpr double kMaxDip = 0.5;   // m: a stretch this short off every place (a wall's blur) does not end a visit
constexpr int kRoomLabel = static_cast<int>(places::PlaceLabel::Room);
constexpr int kCorridorLabel = static_cast<int>(places::PlaceLabel::Corridor);

// A visit: a maximal stretch of path samples in one region.
struct Visit {
  int id = 0;
  std::size_t first = 0, last = 0;
  bool from_outside = false;  ///< the sample before it is on the path (not a start or a gap) and outside the region
  bool to_outside = false;    ///< the same after it
};

// The share of region `id`'s cells within `radius` cells (4-neighbour steps inside the region) of the path samples
// that lie in it (`at[k] == id`).
double pathCoverage(const RegionMap& rm, int id, const std::vector<cv::Point2d>& samples, const std::vector<int>& at,
                    double radius) {
  const Region& r = rm.region(id);
  const cv::Rect box = r.bbox;
  cv::Mat dist(box.size(), CV_32S, cv::Scalar(-1));
  std::deque<cv::Point> queue;
  for (std::size_t k = 0; k < at.size(); ++k) {
    if (at[k] != id) continue;
    const cv::Point c(static_cast<int>(std::floor(samples[k].x)) - box.x,
                      static_cast<int>(std::floor(samples[k].y)) - box.y);
    // A dip sample (off every region, counted in the visit) seeds nothing.
    if (!cv::Rect(cv::Point(), box.size()).contains(c) || rm.ids.at<int>(c + box.tl()) != id) continue;
    if (dist.at<int>(c) >= 0) continue;
    dist.at<int>(c) = 0;
    queue.push_back(c);
  }
  const int reach = static_cast<int>(std::floor(radius));
  long covered = 0;
  while (!queue.empty()) {
    const cv::Point c = queue.front();
    queue.pop_front();
    ++covered;
    const int d = dist.at<int>(c);
    if (d >= reach) continue;
    for (const cv::Point step : {cv::Point(1, 0), cv::Point(-1, 0), cv::Point(0, 1), cv::Point(0, -1)}) {
      const cv::Point e = c + step;
      if (e.x < 0 || e.y < 0 || e.x >= box.width || e.y >= box.height || dist.at<int>(e) >= 0) continue;
      if (rm.ids.at<int>(e + box.tl()) != id) continue;
      dist.at<int>(e) = d + 1;
      queue.push_back(e);
    }
  }
  return r.cells > 0 ? static_cast<double>(covered) / r.cells : 0.0;
}
}  // namespace

cv::Mat relabelThoroughfares(const cv::Mat& labels, const std::vector<cv::Point2d>& path, double resolution,
                             const ThoroughfareOptions& o, std::vector<Thoroughfare>* found) {
  cv::Mat out = labels.clone();
  std::vector<Thoroughfare> result;
  if (!o.enabled || path.empty()) {
    if (found) *found = result;
    return out;
  }
  const RegionMap rm = extractRegions(labels, resolution);
  // Per sample: its region, 0 off every region, -1 at a gap in the trajectory.
  PathOverRegions over = pathOverRegions(path, rm.ids, resolution);
  const std::vector<cv::Point2d>& samples = over.samples;
  std::vector<int>& at = over.region;
  // A dip of at most kMaxDip off every region between two samples of one region (a wall's blur, a gap between
  // places) does not end a visit.
  const auto max_dip = static_cast<std::size_t>(std::ceil(kMaxDip / resolution));
  for (std::size_t i = 1; i < at.size(); ++i) {
    if (at[i] != 0 || at[i - 1] <= 0) continue;
    std::size_t j = i;
    while (j < at.size() && at[j] == 0 && j - i < max_dip) ++j;
    if (j < at.size() && at[j] == at[i - 1])
      for (std::size_t k = i; k < j; ++k) at[k] = at[i - 1];
  }
  // The visits of room regions.
  std::vector<Visit> visits;
  for (std::size_t i = 0; i < at.size();) {
    std::size_t j = i;
    while (j + 1 < at.size() && at[j + 1] == at[i]) ++j;
    if (at[i] > 0 && rm.region(at[i]).label == kRoomLabel) {
      Visit v;
      v.id = at[i];
      v.first = i, v.last = j;
      v.from_outside = i > 0 && at[i - 1] >= 0;
      v.to_outside = j + 1 < at.size() && at[j + 1] >= 0;
      visits.push_back(v);
    }
    i = j + 1;
  }

  // Per room region: crossings and the openings its visits used.
  struct Use {
    int crossings = 0;
    std::vector<cv::Point2d> openings;
    cv::Point2d entered{-1, -1};  // where the first visit began
  };
  std::map<int, Use> use;
  const double span_cells = o.min_span / resolution, radius_cells = o.opening_radius / resolution;
  const auto add_opening = [&](Use& u, const cv::Point2d& p) {
    for (const auto& q : u.openings)
      if (cv::norm(p - q) < radius_cells) return;
    u.openings.push_back(p);
  };
  for (const Visit& v : visits) {
    Use& u = use[v.id];
    if (u.entered.x < 0) u.entered = samples[v.first];
    const cv::Point2d &in = samples[v.first], &out_at = samples[v.last];
    if (v.from_outside) add_opening(u, in);
    if (v.to_outside) add_opening(u, out_at);
    if (v.from_outside && v.to_outside && cv::norm(out_at - in) >= span_cells) ++u.crossings;
  }

  std::vector<char> relabel(rm.regions.size() + 1, 0);
  bool any = false;
  for (const auto& [id, u] : use) {
    const Region& r = rm.region(id);
    if (r.area_m2 < o.min_area || u.crossings < o.min_crossings ||
        static_cast<int>(u.openings.size()) < o.min_openings)
      continue;
    const double coverage = pathCoverage(rm, id, samples, at, o.cover_radius / resolution);
    if (coverage < o.min_coverage) continue;
    relabel[static_cast<std::size_t>(id)] = 1;
    any = true;
    Thoroughfare t;
    t.crossings = u.crossings;
    t.openings = static_cast<int>(u.openings.size());
    t.area_m2 = r.area_m2;
    t.coverage = coverage;
    t.at = cv::Point(static_cast<int>(std::floor(r.centroid.x)), static_cast<int>(std::floor(r.centroid.y)));
    if (!r.bbox.contains(t.at) || rm.ids.at<int>(t.at) != id)
      t.at = cv::Point(static_cast<int>(std::floor(u.entered.x)), static_cast<int>(std::floor(u.entered.y)));
    result.push_back(t);
  }
  if (any)
    for (int y = 0; y < out.rows; ++y) {
      const int* ids = rm.ids.ptr<int>(y);
      unsigned char* row = out.ptr<unsigned char>(y);
      for (int x = 0; x < out.cols; ++x)
        if (ids[x] > 0 && relabel[static_cast<std::size_t>(ids[x])])
          row[x] = static_cast<unsigned char>(kCorridorLabel);
    }
  if (found) *found = result;
  return out;
}

}  // namespace gridtopo::topology
