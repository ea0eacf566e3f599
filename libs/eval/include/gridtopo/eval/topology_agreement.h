#pragma once
// Two topologies of the same building (e.g. two SLAM runs, or one log read in two layouts): how far they give the
// same places. The second map is aligned to the first (reference_alignment.h: affine ECC of the free spaces); then,
// on the first map's grid, the labels are compared on the cells that are places in both, and the places each has
// that the other lacks are measured in square metres. gridtopo-topology-compare's mode with a topology as the
// reference.
#include <opencv2/core.hpp>

#include <string>

#include "gridtopo/eval/reference_alignment.h"
#include "gridtopo/topology/pipeline.h"

namespace gridtopo::eval {

/// A topology on its map: the map file and the gridtopo-topology output directory (its labels.png).
struct TopologyOnMap {
  std::string map, topology_dir;
};

struct TopologyAgreement {
  std::string map, reference_map;
  ReferenceAlignment alignment;  ///< the first map's pixels -> the reference map's pixels
  double resolution = 0.05;      ///< m per cell of the first map
  cv::Mat labels;                ///< the first topology's labels (0..2, places::kNoLabel), its map's grid
  cv::Mat reference_labels;      ///< the reference topology's labels carried onto that grid
  long long both = 0, agree = 0;          ///< cells that are places in both; of them, with the same label
  long long only_here = 0, only_reference = 0;  ///< cells that are places in one only (the reference's counted
                                                 ///< on its own grid, through the inverse alignment)
  double reference_resolution = 0.05;
  double agreement() const { return both ? static_cast<double>(agree) / static_cast<double>(both) : 0.0; }
  double onlyHereM2() const { return static_cast<double>(only_here) * resolution * resolution; }
  double onlyReferenceM2() const {
    return static_cast<double>(only_reference) * reference_resolution * reference_resolution;
  }
  /// The confusion of labels on the cells that are places in both: [ours][reference's].
  long long confusion[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

/// Aligns the reference's map to the map (free cells thresholded by `options` for each map's kind), carries the
/// reference's labels over and counts. InputError naming the file for a missing or mis-sized image.
TopologyAgreement compareTopologies(const TopologyOnMap& topology, const TopologyOnMap& reference,
                                    const topology::TopologyOptions& options);

/// The JSON of that mode (format "gridtopo-topology-agreement").
std::string agreementJson(const TopologyAgreement& a);
/// One line: alignment, agreement on the common places, areas each has alone.
std::string agreementSummary(const TopologyAgreement& a);
/// On the first map's grid: common places with the same label in light grey, with another label in red, places of
/// the first only in blue, of the reference only in orange; the rest of the map in dark grey / black.
cv::Mat agreementOverlay(const TopologyAgreement& a);

}  // namespace gridtopo::eval
