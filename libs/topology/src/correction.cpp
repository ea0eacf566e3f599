#include "gridtopo/topology/correction.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <opencv2/imgproc.hpp>
#include <set>

#include "gridtopo/core/error.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/edge_route.h"
#include "gridtopo/topology/regions.h"
#include "gridtopo/core/distance_transform.h"
#include "mask_ops.h"

namespace gridtopo::topology {

const OptionSchema<CorrectionOptions>& correctionOptionSchema() {
  using O = CorrectionOptions;
  using R = OptionRange;
  static const OptionSchema<O> schema =
      OptionSchema<O>("gridtopo::topology::CorrectionOptions")
          .add("enabled", &O::enabled, R::any(), "", "apply the region correction rules")
          .add("min_place_area", &O::min_place_area, R::atLeast(0), "m^2", "R0: smaller connected free patches get no label")
          .add("min_room_area", &O::min_room_area, R::atLeast(0), "m^2", "R1: smaller room regions join a neighbour")
          .add("min_corridor_area", &O::min_corridor_area, R::atLeast(0), "m^2",
               "R1: smaller corridor regions join a neighbour")
          .add("min_doorway_area", &O::min_doorway_area, R::atLeast(0), "m^2",
               "R1: smaller doorway regions join a neighbour")
          .add("doorways_must_separate", &O::doorways_must_separate, R::any(), "",
               "R2: a doorway joining fewer than two places takes its neighbour's label")
          .add("max_doorway_area", &O::max_doorway_area, R::atLeast(0), "m^2",
               "R3: larger doorway regions are not doors (0 = off)")
          .add("junctions", &O::junctions, R::any(), "",
               "R4: corridors run on through the room regions that join two corridor regions directly")
          .add("junction_min_border", &O::junction_min_border, R::atLeast(0), "m",
               "R4: the shortest border with a corridor region that counts")
          .add("junction_max_half_width", &O::junction_max_half_width, R::atLeast(0), "m",
               "R4: wider passages (median clearance along the path) stay room")
          .add("max_passes", &O::max_passes, R::closed(0, 1000), "", "passes of each rule at most");
  return schema;
}

void CorrectionOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& s, const std::string& sec) {
  correctionOptionSchema().load(*this, s, sec);
}

void CorrectionOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t, const std::string& sec) const {
  correctionOptionSchema().save(*this, t, sec);
}

void CorrectionOptions::dumpToTextStream(std::ostream& out) const { correctionOptionSchema().dump(*this, out); }

void CorrectionOptions::validate(const std::string& file, const std::string& section) const {
  correctionOptionSchema().validate(*this, file, section);
}

namespace {
// Relabels regions per `new_label` (index id-1; -1 = keep).
void apply(cv::Mat& labels, const RegionMap& rm, const std::vector<int>& new_label) {
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      const int id = rm.ids.at<int>(y, x);
      if (id > 0 && new_label[static_cast<std::size_t>(id - 1)] >= 0)
        labels.at<unsigned char>(y, x) = static_cast<unsigned char>(new_label[static_cast<std::size_t>(id - 1)]);
    }
}

// R4 (see correctRegions).
void junctionStrips(cv::Mat& labels, double resolution, const CorrectionOptions& o, CorrectionStats& st) {
  const RegionMap rm = extractRegions(labels, resolution);
  const int corridor = static_cast<int>(places::PlaceLabel::Corridor);
  const int room = static_cast<int>(places::PlaceLabel::Room);
  const int min_len = static_cast<int>(std::ceil(o.junction_min_border / resolution));
  std::vector<std::set<int>> corridor_nbs(rm.regions.size());
  for (const auto& [k, len] : regionAdjacency(rm.ids)) {
    if (len < min_len) continue;
    for (auto [u, v] : {std::pair{k.first, k.second}, std::pair{k.second, k.first}})
      if (rm.region(u).label == room && rm.region(v).label == corridor)
        corridor_nbs[static_cast<std::size_t>(u - 1)].insert(v);
  }
  // The clearance (cells to the nearest cell without a place, preciseDistance of the places) of the cells of a room's
  // box, for the few rooms between two corridors: over the box widened by `margin`, exact wherever the value found
  // is within the margin (a cell outside the widened box is further); when some cell's value exceeds it, once more
  // over the box widened by the largest value found (which bounds every true value).
  const auto halfWidthOfBox = [&](const cv::Rect& box) {
    int margin = 64;
    for (;;) {
      const cv::Rect wide = cv::Rect(box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin) &
                            cv::Rect(0, 0, labels.cols, labels.rows);
      const cv::Mat d = preciseDistance(labels(wide) < places::kNumLabels);
      cv::Mat own = d(box - wide.tl()).clone();
      double largest = 0;
      cv::minMaxLoc(own, nullptr, &largest);
      if (largest <= margin || wide == cv::Rect(0, 0, labels.cols, labels.rows)) return own;
      margin = static_cast<int>(std::ceil(largest)) + 1;
    }
  };
  const int dx[8] = {1, -1, 0, 0, 1, 1, -1, -1}, dy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  const double scale = kPathClearanceScale / resolution;  // cells
  cv::Mat strip = cv::Mat::zeros(labels.size(), CV_8U);
  for (std::size_t i = 0; i < rm.regions.size(); ++i) {
    const Region& r = rm.regions[i];
    if (corridor_nbs[i].size() < 2) continue;
    // Everything below works in the region's box: `inside` its cells, `touch` the corridor region each of them
    // borders (0: none), box-local indices y * box.width + x.
    const cv::Rect box = r.bbox;
    const cv::Mat inside = rm.ids(box) == r.id;
    const cv::Mat half_width = halfWidthOfBox(box);  // box coordinates
    cv::Mat touch(box.size(), CV_32S, cv::Scalar(0));
    for (int y = 0; y < box.height; ++y)
      for (int x = 0; x < box.width; ++x) {
        if (!inside.at<unsigned char>(y, x)) continue;
        for (int d = 0; d < 8 && touch.at<int>(y, x) == 0; ++d) {
          const int nx = box.x + x + dx[d], ny = box.y + y + dy[d];
          if (nx < 0 || ny < 0 || nx >= labels.cols || ny >= labels.rows) continue;
          const int id = rm.ids.at<int>(ny, nx);
          if (id > 0 && corridor_nbs[i].count(id)) touch.at<int>(y, x) = id;
        }
      }
    const std::vector<int> nbs(corridor_nbs[i].begin(), corridor_nbs[i].end());
    for (std::size_t a = 0; a < nbs.size(); ++a)
      for (std::size_t b = a + 1; b < nbs.size(); ++b) {
        // Least-cost path (kPathClearanceScale, as the edge routes: it keeps to the middle of the passage) from the
        // cells touching corridor a to the first cell touching corridor b, inside the region.
        cv::Mat parent(box.size(), CV_32S, cv::Scalar(-1));
        cv::Mat cost(box.size(), CV_64F, cv::Scalar(std::numeric_limits<double>::infinity()));
        using Item = std::pair<double, int>;
        std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
        for (int y = 0; y < box.height; ++y)
          for (int x = 0; x < box.width; ++x)
            if (touch.at<int>(y, x) == nbs[a]) {
              parent.at<int>(y, x) = y * box.width + x;
              cost.at<double>(y, x) = 0.0;
              queue.push({0.0, y * box.width + x});
            }
        int goal = -1;
        while (!queue.empty()) {
          const auto [c0, idx] = queue.top();
          queue.pop();
          const cv::Point p(idx % box.width, idx / box.width);
          if (c0 > cost.at<double>(p)) continue;
          if (touch.at<int>(p) == nbs[b]) {
            goal = idx;
            break;
          }
          for (int d = 0; d < 8; ++d) {
            const int nx = p.x + dx[d], ny = p.y + dy[d];
            if (nx < 0 || ny < 0 || nx >= box.width || ny >= box.height || !inside.at<unsigned char>(ny, nx)) continue;
            const double q = scale / std::max(1.0f, half_width.at<float>(ny, nx));
            const double nc = c0 + (d < 4 ? 1.0 : M_SQRT2) * (1.0 + q * q);
            if (nc < cost.at<double>(ny, nx)) {
              cost.at<double>(ny, nx) = nc;
              parent.at<int>(ny, nx) = idx;
              queue.push({nc, ny * box.width + nx});
            }
          }
        }
        if (goal < 0) continue;
        // The path back to corridor a, and the passage's half-width: the median clearance along it.
        cv::Mat on_path = cv::Mat::ones(box.size(), CV_8U);
        std::vector<float> widths;
        for (int c = goal;; c = parent.at<int>(c / box.width, c % box.width)) {
          const cv::Point p(c % box.width, c / box.width);
          on_path.at<unsigned char>(p) = 0;
          widths.push_back(half_width.at<float>(p));
          if (parent.at<int>(p) == c) break;
        }
        std::nth_element(widths.begin(), widths.begin() + static_cast<long>(widths.size() / 2), widths.end());
        const float w = widths[widths.size() / 2];
        if (w * resolution > o.junction_max_half_width) continue;
        strip(box).setTo(1, inside & withinDistance(on_path, w));
        ++st.junctions;
      }
  }
  labels.setTo(corridor, strip);
}
}  // namespace

cv::Mat correctRegions(const cv::Mat& labels_in, double resolution, const CorrectionOptions& o,
                       CorrectionStats* stats) {
  o.validate();
  cv::Mat labels = labels_in.clone();
  CorrectionStats st;
  if (!o.enabled) {
    if (stats) *stats = st;
    return labels;
  }
  // R0
  {
    // The groups of places from their runs (RunComponents: no image of group numbers).
    const cv::Mat placed = labels < places::kNumLabels;
    const RunComponents groups(placed, true, 8);
    const double cell = resolution * resolution;
    const auto small = [&](std::size_t root) { return static_cast<double>(groups.area[root]) * cell < o.min_place_area; };
    for (std::size_t i = 0; i < groups.root.size(); ++i)
      if (groups.root[i] == static_cast<int>(i) && small(i)) ++st.patches_removed;
    std::size_t i = 0;
    forEachRun(placed, true, [&](int y, int x0, int x1) {
      if (small(static_cast<std::size_t>(groups.root[i++])))
        std::fill(labels.ptr<unsigned char>(y) + x0, labels.ptr<unsigned char>(y) + x1 + 1, static_cast<unsigned char>(255));
    });
  }
  const double min_area[3] = {o.min_room_area, o.min_corridor_area, o.min_doorway_area};
  for (int pass = 0; pass < o.max_passes; ++pass) {
    const RegionMap rm = extractRegions(labels, resolution);
    const auto adj = regionAdjacency(rm.ids);
    const std::size_t n = rm.regions.size();
    std::vector<int> best_nb(n, 0), best_len(n, 0);
    std::vector<std::set<int>> non_door_nbs(n);
    for (const auto& [k, len] : adj) {
      const auto [a, b] = k;
      for (auto [u, v] : {std::pair{a, b}, std::pair{b, a}}) {
        const std::size_t ui = static_cast<std::size_t>(u - 1);
        if (len > best_len[ui]) best_len[ui] = len, best_nb[ui] = v;
        if (rm.region(v).label != static_cast<int>(places::PlaceLabel::Doorway)) non_door_nbs[ui].insert(v);
      }
    }
    std::vector<int> new_label(n, -1);
    bool changed = false;
    // R1, smallest regions first so a small region merges into a large neighbour rather than another small one
    // that changes at the same time; a region whose best neighbour is changing this pass waits. Between two small
    // regions of equal size the one with the higher id waits (else both change and they swap labels forever).
    for (std::size_t i = 0; i < n; ++i) {
      const Region& r = rm.regions[i];
      if (r.area_m2 >= min_area[r.label] || best_nb[i] == 0) continue;
      const Region& nb = rm.region(best_nb[i]);
      if (nb.area_m2 < min_area[nb.label] && (nb.cells < r.cells || (nb.cells == r.cells && nb.id < r.id)))
        continue;
      if (nb.label == r.label) continue;
      new_label[i] = nb.label;
      ++st.small_merged;
      changed = true;
    }
    if (!changed) {
      for (std::size_t i = 0; i < n; ++i) {
        const Region& r = rm.regions[i];
        if (r.label != static_cast<int>(places::PlaceLabel::Doorway) || best_nb[i] == 0) continue;
        if (o.doorways_must_separate && non_door_nbs[i].size() < 2) {
          // Longest border among non-doorway neighbours (a doorway next to a doorway merges with it anyway).
          int lbl = rm.region(best_nb[i]).label;
          if (lbl == r.label) continue;
          new_label[i] = lbl;
          ++st.doorways_not_separating;
          changed = true;
        } else if (o.max_doorway_area > 0 && r.area_m2 > o.max_doorway_area) {
          new_label[i] = rm.region(best_nb[i]).label;
          ++st.doorways_oversized;
          changed = true;
        }
      }
    }
    st.passes = pass + 1;
    if (!changed) break;
    apply(labels, rm, new_label);
  }
  // R4, once the small regions are settled: where a room region joins two corridor regions directly, the corridor
  // runs on through it (in a SLAM map a junction opens onto rooms with open doors and reads as room together with
  // them). The cells of the room region within the passage's half-width of the least-cost path between the two
  // corridors become corridor.
  if (o.junctions) junctionStrips(labels, resolution, o, st);
  if (stats) *stats = st;
  return labels;
}

}  // namespace gridtopo::topology
