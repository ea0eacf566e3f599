#pragma once
// Heuristic region correction after Mozos et al. Rules, applied in this order, each pass until nothing changes:
//  R0 small free patches: a connected patch of labelled cells (any labels, 8-connected) smaller than
//     min_place_area is not a place (isolated specks and one-cell free lines of scanned maps); it loses its label.
//  R1 small regions: a room / corridor / doorway region smaller than its minimum area takes the label of the
//     neighbouring region it shares the longest border with (isolated small regions are kept).
//  R2 doorways separate: a doorway region that touches fewer than two non-doorway regions (so joins nothing)
//     takes the label of its longest-border neighbour.
//  R3 oversized doorways: a doorway region larger than max_doorway_area is not a door; it takes the label of its
//     longest-border neighbour.
#include <mrpt/config/CLoadableOptions.h>

#include <opencv2/core.hpp>

#include "gridtopo/core/option_schema.h"

namespace gridtopo::topology {

struct CorrectionOptions : public mrpt::config::CLoadableOptions {
  bool enabled = true;
  double min_place_area = 0.5;      ///< m^2 (R0)
  double min_room_area = 4.0;       ///< m^2 (R1)
  double min_corridor_area = 4.0;   ///< m^2 (R1)
  double min_doorway_area = 0.1;    ///< m^2 (R1)
  bool doorways_must_separate = true;  ///< R2
  double max_doorway_area = 6.0;    ///< m^2 (R3); 0 = off
  /// R4, corridors through junctions read as room: where a room region borders two corridor regions directly (each
  /// along at least junction_min_border, not through a doorway), the cells within the passage's half-width of the
  /// least-cost path between them become corridor, when that half-width (median clearance along the path) is at
  /// most junction_max_half_width (a corridor is narrow; a wider space between corridors is a hall or a room).
  bool junctions = true;
  double junction_min_border = 0.5;       ///< m (R4)
  double junction_max_half_width = 1.25;  ///< m (R4)
  int max_passes = 20;

  void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override;
  /// Every key, loadable by loadFromConfigFile to the same values (doubles to 17 digits).
  void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  void dumpToTextStream(std::ostream& out) const override;
  /// InputError(file, 0, "[section] key", ...) for a value out of its range.
  void validate(const std::string& file = "<options>", const std::string& section = "correction") const;
};

/// The key table of [correction] (load, save, dump, validation, help, the GUI's grid).
const OptionSchema<CorrectionOptions>& correctionOptionSchema();

struct CorrectionStats {
  int patches_removed = 0, small_merged = 0, doorways_not_separating = 0, doorways_oversized = 0, junctions = 0,
      passes = 0;
};

/// Corrected copy of `labels` (CV_8U, 0..2 place labels, other values = no label).
cv::Mat correctRegions(const cv::Mat& labels, double resolution, const CorrectionOptions& options,
                       CorrectionStats* stats = nullptr);

}  // namespace gridtopo::topology
