#include "gridtopo/topology/door_passages.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/regions.h"
#include "gridtopo/core/distance_transform.h"

namespace gridtopo::topology {

namespace {
constexpr unsigned char kDoorway = static_cast<unsigned char>(places::PlaceLabel::Doorway);
constexpr int kRoomLabel = static_cast<int>(places::PlaceLabel::Room);
constexpr int kCorridorLabel = static_cast<int>(places::PlaceLabel::Corridor);

bool isGap(const cv::Point2d& p) { return std::isnan(p.x); }

// Distance (cells) from `p` along the unit vector `n` to the first cell that is no place (or off the image),
// marching half a cell at a time; at most `cap`.
double rayToWall(const cv::Mat& places, cv::Point2d p, cv::Point2d n, double cap) {
  for (double t = 0.5;; t += 0.5) {
    if (t >= cap) return cap;
    const int x = static_cast<int>(std::floor(p.x + t * n.x)), y = static_cast<int>(std::floor(p.y + t * n.y));
    if (x < 0 || y < 0 || x >= places.cols || y >= places.rows || !places.at<unsigned char>(y, x)) return t;
  }
}

struct Chord {
  double width = std::numeric_limits<double>::quiet_NaN();  // cells; NaN when the point is no place
  cv::Point2d a, b;
};

// The shortest chord through `p` within `max_angle` (radians) of the normal to `dir`.
Chord shortestChord(const cv::Mat& places, cv::Point2d p, cv::Point2d dir, double max_angle, double cap) {
  Chord c;
  const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
  if (x < 0 || y < 0 || x >= places.cols || y >= places.rows || !places.at<unsigned char>(y, x)) return c;
  const double step = 5.0 * M_PI / 180.0;
  const int k = static_cast<int>(std::floor(max_angle / step + 1e-9));
  const cv::Point2d normal(-dir.y, dir.x);
  for (int i = -k; i <= k; ++i) {
    const double an = i * step, cs = std::cos(an), sn = std::sin(an);
    const cv::Point2d n(cs * normal.x - sn * normal.y, sn * normal.x + cs * normal.y);
    const double plus = rayToWall(places, p, n, cap), minus = rayToWall(places, p, -n, cap);
    if (std::isnan(c.width) || plus + minus < c.width) {
      c.width = plus + minus;
      c.a = p - minus * n;
      c.b = p + plus * n;
    }
  }
  return c;
}

// Which side of the line through a and b the point q lies on.
double side(cv::Point2d a, cv::Point2d b, cv::Point2d q) { return (b - a).cross(q - a); }
}  // namespace

std::vector<cv::Point2d> samplePath(const std::vector<cv::Point2d>& path, double step, double max_jump) {
  std::vector<cv::Point2d> out;
  if (path.empty()) return out;
  const cv::Point2d gap(std::numeric_limits<double>::quiet_NaN(), 0);
  out.push_back(path.front());
  double carried = 0;  // arc length since the last sample
  for (std::size_t i = 1; i < path.size(); ++i) {
    const cv::Point2d p = path[i - 1], q = path[i];
    const double len = cv::norm(q - p);
    if (len > max_jump) {
      out.push_back(gap);
      out.push_back(q);
      carried = 0;
      continue;
    }
    double t = step - carried;  // arc length along this segment of the next sample
    for (; t <= len; t += step) out.push_back(p + (q - p) * (t / len));
    carried = len - (t - step);
  }
  return out;
}

PathOverRegions pathOverRegions(const std::vector<cv::Point2d>& path, const cv::Mat& ids, double resolution) {
  PathOverRegions r;
  r.samples = samplePath(path, 1.0, kMaxPathJump / resolution);
  r.region.assign(r.samples.size(), 0);
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    const cv::Point2d& q = r.samples[i];
    if (isGap(q)) {
      r.region[i] = -1;
      continue;
    }
    const int x = static_cast<int>(std::floor(q.x)), y = static_cast<int>(std::floor(q.y));
    if (x >= 0 && y >= 0 && x < ids.cols && y < ids.rows) r.region[i] = ids.at<int>(y, x);
  }
  return r;
}

std::vector<DoorPassage> findDoorPassages(const cv::Mat& places, const std::vector<cv::Point2d>& path,
                                          double resolution, const DoorPassageOptions& o) {
  std::vector<DoorPassage> found;
  if (places.empty() || path.size() < 2) return found;
  const std::vector<cv::Point2d> s = samplePath(path, 1.0, kMaxPathJump / resolution);
  const std::size_t n = s.size();
  const double cap = (o.max_width + o.wider_by) / resolution;
  const int half_dir = std::max(1, static_cast<int>(std::lround(0.25 / resolution)));  // travel direction over ±0.25 m
  const double max_angle = o.max_angle * M_PI / 180.0;
  // The start of every sample's piece and the piece's end (one past).
  std::vector<std::size_t> piece_begin(n), piece_end(n);
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    while (j < n && !isGap(s[j])) ++j;
    for (std::size_t k = i; k < j; ++k) piece_begin[k] = i, piece_end[k] = j;
    if (j < n) piece_begin[j] = piece_end[j] = j;
    i = j + 1;
  }
  // The clearance of every place (the distance transform): where it is at least half the longest chord that
  // matters, every chord through the point is that long (each side reaches at least the clearance), and the
  // point's width is taken as twice its clearance without casting rays.
  // Only the path's cells need it (preciseDistanceAt: no float image of the map); the samples are a cell apart, so
  // consecutive ones often share a cell, whose value is kept.
  cv::Point last_cell(-1, -1);
  float last_clearance = 0;
  const auto clearanceAt = [&](int cx, int cy) {
    if (cv::Point(cx, cy) != last_cell) last_cell = {cx, cy}, last_clearance = preciseDistanceAt(places, last_cell);
    return last_clearance;
  };
  std::vector<Chord> chord(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (isGap(s[i])) continue;
    const int cx = static_cast<int>(std::floor(s[i].x)), cy = static_cast<int>(std::floor(s[i].y));
    const bool in_place = cx >= 0 && cy >= 0 && cx < places.cols && cy < places.rows && places.at<unsigned char>(cy, cx);
    const float clearance = in_place ? clearanceAt(cx, cy) : 0.0f;
    if (in_place && 2.0 * clearance >= cap) {
      chord[i].width = 2.0 * clearance;
      chord[i].a = chord[i].b = s[i];
      continue;
    }
    const std::size_t lo = std::max(piece_begin[i], i >= static_cast<std::size_t>(half_dir) ? i - half_dir : 0);
    const std::size_t hi = std::min(piece_end[i] - 1, i + half_dir);
    const cv::Point2d d = s[hi] - s[lo];
    const double len = cv::norm(d);
    if (len < 1e-9) continue;
    chord[i] = shortestChord(places, s[i], d / len, max_angle, cap);
  }
  const auto width_m = [&](std::size_t i) { return chord[i].width * resolution; };
  const auto narrow = [&](std::size_t i) { return !std::isnan(chord[i].width) && width_m(i) <= o.max_width; };
  const std::size_t context = static_cast<std::size_t>(std::ceil(o.context / resolution));
  const std::size_t max_run = static_cast<std::size_t>(std::floor(o.max_length / resolution)) + 1;
  for (std::size_t i = 0; i < n;) {
    if (!narrow(i)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < n && narrow(j)) ++j;  // [i, j): a narrow stretch (gaps are never narrow)
    const std::size_t begin = i, end = j;
    i = j;
    if (end - begin > max_run) continue;
    std::size_t best = begin;
    for (std::size_t k = begin; k < end; ++k)
      if (chord[k].width < chord[best].width) best = k;
    const double w = width_m(best);
    if (w < o.min_width) continue;
    // Wider before and after, within `context` along the path of the stretch's ends.
    const std::size_t before_lo = begin >= piece_begin[begin] + context ? begin - context : piece_begin[begin];
    const std::size_t after_hi = std::min(piece_end[begin], end + context);  // one past
    double wide_before = 0, wide_after = 0;
    for (std::size_t k = before_lo; k < begin; ++k)
      if (!std::isnan(chord[k].width)) wide_before = std::max(wide_before, width_m(k));
    for (std::size_t k = end; k < after_hi; ++k)
      if (!std::isnan(chord[k].width)) wide_after = std::max(wide_after, width_m(k));
    if (wide_before < w + o.wider_by || wide_after < w + o.wider_by) continue;
    // Through the door: the path's ends of the window lie on opposite sides of the chord.
    const Chord& c = chord[best];
    if (before_lo == begin || after_hi == end) continue;
    if (side(c.a, c.b, s[before_lo]) * side(c.a, c.b, s[after_hi - 1]) >= 0) continue;
    const cv::Point centre(static_cast<int>(std::floor(s[best].x)), static_cast<int>(std::floor(s[best].y)));
    bool merged = false;
    for (DoorPassage& d : found) {
      const double reach = std::max(d.width, w) / resolution;
      if (cv::norm(cv::Point2d(d.centre - centre)) > reach) continue;
      ++d.passes;
      if (w < d.width) d.a = c.a, d.b = c.b, d.centre = centre, d.width = w, d.sample = best;
      merged = true;
      break;
    }
    if (!merged) found.push_back({c.a, c.b, centre, w, best, 1});
  }
  return found;
}

cv::Mat addDoorPassages(const cv::Mat& labels, const std::vector<cv::Point2d>& path, double resolution,
                        const DoorPassageOptions& o, std::vector<DoorPassage>* found) {
  cv::Mat out = labels.clone();
  std::vector<DoorPassage> doors;
  if (o.enabled && !path.empty()) {
    const cv::Mat places = labels < places::kNumLabels;
    doors = findDoorPassages(places, path, resolution, o);
    cv::Mat drawn = cv::Mat::zeros(labels.size(), CV_8U);
    const int thickness = std::max(1, static_cast<int>(std::lround(o.depth / resolution)));
    const auto cell = [](cv::Point2d p) {
      return cv::Point(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)));
    };
    for (const DoorPassage& d : doors) cv::line(drawn, cell(d.a), cell(d.b), cv::Scalar(255), thickness, cv::LINE_8);
    drawn &= places;
    out.setTo(kDoorway, drawn);
  }
  if (found) *found = std::move(doors);
  return out;
}

cv::Mat addRoomEntries(const cv::Mat& labels, const std::vector<cv::Point2d>& path, double resolution,
                       const DoorPassageOptions& o, std::vector<cv::Point>* entries) {
  cv::Mat out = labels.clone();
  std::vector<cv::Point> found;
  if (!o.enabled || !o.room_entries || path.empty()) {
    if (entries) *entries = found;
    return out;
  }
  const RegionMap rm = extractRegions(labels, resolution);
  const double near = o.max_width / resolution;
  struct Entry {
    cv::Point2d at;
    int room, corridor;
  };
  std::vector<Entry> steps;
  // The doorway regions between each pair of regions (a < b).
  std::map<std::pair<int, int>, std::vector<int>> doors_between;
  {
    std::map<int, std::vector<int>> nbs;
    for (const auto& [ab, len] : regionAdjacency(rm.ids)) nbs[ab.first].push_back(ab.second), nbs[ab.second].push_back(ab.first);
    for (const auto& [d, list] : nbs) {
      if (rm.region(d).label != static_cast<int>(kDoorway)) continue;
      for (int a : list)
        for (int b : list)
          if (a < b) doors_between[{a, b}].push_back(d);
    }
  }
  // A doorway between the room and the corridor already lies within max_width of the step.
  const auto door_near = [&](cv::Point2d p, int room, int corridor) {
    const auto it = doors_between.find({std::min(room, corridor), std::max(room, corridor)});
    if (it == doors_between.end()) return false;
    const int r = static_cast<int>(std::ceil(near));
    const cv::Rect box = cv::Rect(static_cast<int>(std::floor(p.x)) - r, static_cast<int>(std::floor(p.y)) - r,
                                  2 * r + 1, 2 * r + 1) &
                         cv::Rect(0, 0, labels.cols, labels.rows);
    for (int y = box.y; y < box.y + box.height; ++y)
      for (int x = box.x; x < box.x + box.width; ++x) {
        const int id = rm.ids.at<int>(y, x);
        if (id > 0 && std::find(it->second.begin(), it->second.end(), id) != it->second.end() &&
            std::hypot(x + 0.5 - p.x, y + 0.5 - p.y) <= near)
          return true;
      }
    return false;
  };
  // The path's room / corridor / doorway region at every sample (0 off the regions, -1 at a gap).
  const PathOverRegions over = pathOverRegions(path, rm.ids, resolution);
  const std::vector<cv::Point2d>& samples = over.samples;
  const std::vector<int>& at = over.region;
  // Whether the path goes at least entry_depth into the room from a step: the largest distance to the corridor's
  // cells of its samples in the room region, from sample i on in direction dir, until it reaches another room /
  // corridor region. The distances are looked up at the samples (preciseDistanceAt, searched no further than a
  // little beyond entry_depth: no float image of the box) and the walk stops once one reaches entry_depth.
  const cv::Mat not_corridor = labels != kCorridorLabel;
  const int reach = static_cast<int>(std::ceil(o.entry_depth / resolution)) + 1;
  const auto goes_deep_into = [&](long i, int room, int dir) {
    float best = 0;
    for (; i >= 0 && i < static_cast<long>(at.size()); i += dir) {
      const int id = at[static_cast<std::size_t>(i)];
      if (id < 0) break;
      if (id == 0 || rm.region(id).label == static_cast<int>(kDoorway)) continue;
      if (id != room) break;
      const cv::Point2d& q = samples[static_cast<std::size_t>(i)];
      const cv::Point cell(static_cast<int>(std::floor(q.x)), static_cast<int>(std::floor(q.y)));
      best = std::max(best, preciseDistanceAt(not_corridor, cell, reach));
      if (best * resolution >= o.entry_depth) return true;
    }
    return best * resolution >= o.entry_depth;
  };
  long last_i = -1;  // the sample of the last room / corridor region of the path
  bool through_door = false;
  for (long i = 0; i < static_cast<long>(at.size()); ++i) {
    const int id = at[static_cast<std::size_t>(i)];
    if (id < 0) {
      last_i = -1;
      continue;
    }
    if (id == 0) continue;
    const int l = rm.region(id).label;
    if (l == static_cast<int>(kDoorway)) {
      through_door = true;
      continue;
    }
    const int last = last_i >= 0 ? at[static_cast<std::size_t>(last_i)] : 0;
    if (last && id != last && !through_door) {
      const int la = rm.region(last).label;
      if ((la == kCorridorLabel && l == kRoomLabel) || (la == kRoomLabel && l == kCorridorLabel)) {
        const cv::Point2d mid = (samples[static_cast<std::size_t>(last_i)] + samples[static_cast<std::size_t>(i)]) * 0.5;
        const bool entering = l == kRoomLabel;
        const int room = entering ? id : last, corridor = entering ? last : id;
        bool known = door_near(mid, room, corridor);
        for (const Entry& e : steps) known = known || cv::norm(e.at - mid) <= near;
        // The robot went into the room (not along its border with the corridor).
        if (!known && (entering ? goes_deep_into(i, room, 1) : goes_deep_into(last_i, room, -1)))
          steps.push_back({mid, room, corridor});
      }
    }
    last_i = i;
    through_door = false;
  }
  const double depth = std::max(1.0, o.depth / resolution), half = near / 2;
  for (const Entry& e : steps) {
    const int r = static_cast<int>(std::ceil(half + depth)) + 1;
    const cv::Rect box = cv::Rect(static_cast<int>(std::floor(e.at.x)) - r, static_cast<int>(std::floor(e.at.y)) - r,
                                  2 * r + 1, 2 * r + 1) &
                         cv::Rect(0, 0, labels.cols, labels.rows);
    cv::Mat to_corridor;
    to_corridor = preciseDistance(rm.ids(box) != e.corridor);
    int drawn = 0;
    for (int y = 0; y < box.height; ++y)
      for (int x = 0; x < box.width; ++x)
        if (rm.ids.at<int>(box.y + y, box.x + x) == e.room && to_corridor.at<float>(y, x) <= depth &&
            std::hypot(box.x + x + 0.5 - e.at.x, box.y + y + 0.5 - e.at.y) <= half) {
          out.at<unsigned char>(box.y + y, box.x + x) = kDoorway;
          ++drawn;
        }
    if (drawn) found.emplace_back(static_cast<int>(std::floor(e.at.x)), static_cast<int>(std::floor(e.at.y)));
  }
  if (entries) *entries = found;
  return out;
}

}  // namespace gridtopo::topology
