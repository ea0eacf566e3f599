#include "gridtopo/topology/correction.h"
#include "gridtopo/core/ini_value.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <set>

#include "gridtopo/core/error.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

void CorrectionOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& s, const std::string& sec) {
  readIniValue(s, sec, "enabled", enabled);
  readIniValue(s, sec, "min_place_area", min_place_area);
  readIniValue(s, sec, "min_room_area", min_room_area);
  readIniValue(s, sec, "min_corridor_area", min_corridor_area);
  readIniValue(s, sec, "min_doorway_area", min_doorway_area);
  readIniValue(s, sec, "doorways_must_separate", doorways_must_separate);
  readIniValue(s, sec, "max_doorway_area", max_doorway_area);
  readIniValue(s, sec, "max_passes", max_passes);
  validate("[" + sec + "]");
}

void CorrectionOptions::saveToConfigFile(mrpt::config::CConfigFileBase& t, const std::string& sec) const {
  t.write(sec, "enabled", iniText(enabled));
  t.write(sec, "min_place_area", iniText(min_place_area));
  t.write(sec, "min_room_area", iniText(min_room_area));
  t.write(sec, "min_corridor_area", iniText(min_corridor_area));
  t.write(sec, "min_doorway_area", iniText(min_doorway_area));
  t.write(sec, "doorways_must_separate", iniText(doorways_must_separate));
  t.write(sec, "max_doorway_area", iniText(max_doorway_area));
  t.write(sec, "max_passes", iniText(max_passes));
}

void CorrectionOptions::dumpToTextStream(std::ostream& out) const {
  out << "enabled                = " << enabled << "\n"
      << "min_place_area         = " << min_place_area << "   // m^2\n"
      << "min_room_area          = " << min_room_area << "   // m^2\n"
      << "min_corridor_area      = " << min_corridor_area << "   // m^2\n"
      << "min_doorway_area       = " << min_doorway_area << "   // m^2\n"
      << "doorways_must_separate = " << doorways_must_separate << "\n"
      << "max_doorway_area       = " << max_doorway_area << "   // m^2, 0 = off\n"
      << "max_passes             = " << max_passes << "\n";
}

void CorrectionOptions::validate(const std::string& where) const {
  for (auto [v, n] : {std::pair{min_room_area, "min_room_area"}, {min_corridor_area, "min_corridor_area"},
                      {min_doorway_area, "min_doorway_area"}, {min_place_area, "min_place_area"}, {max_doorway_area, "max_doorway_area"}})
    if (!std::isfinite(v) || v < 0) throw InputError(where, 0, n, "must be a finite area >= 0 (m^2)");
  if (max_passes < 0 || max_passes > 1000) throw InputError(where, 0, "max_passes", "must be in [0, 1000]");
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
    cv::Mat cc, stats, cents;
    const int n = cv::connectedComponentsWithStats(labels < places::kNumLabels, cc, stats, cents, 8, CV_32S);
    const double cell = resolution * resolution;
    for (int k = 1; k < n; ++k)
      if (stats.at<int>(k, cv::CC_STAT_AREA) * cell < o.min_place_area) ++st.patches_removed;
    for (int y = 0; y < labels.rows; ++y)
      for (int x = 0; x < labels.cols; ++x) {
        const int k = cc.at<int>(y, x);
        if (k > 0 && stats.at<int>(k, cv::CC_STAT_AREA) * cell < o.min_place_area) labels.at<unsigned char>(y, x) = 255;
      }
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
  if (stats) *stats = st;
  return labels;
}

}  // namespace gridtopo::topology
