#include "gridtopo/topology/correction.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <set>

#include "gridtopo/core/error.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/regions.h"

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
