#pragma once
// Step 1 of Mozos et al. (ICRA 2005): a simulated 360-degree range scan at every cell to classify.
// Whole-map technique: for every beam direction the grid is partitioned into parallel digital lines, and a
// forward and a backward sweep over the lines give the free run length of every cell in that direction and its
// opposite at once -- O(cells) per pair of directions instead of one ray cast per cell and beam. The sweeps
// advance all lines of a direction together, column by column, so the image is read in memory order.
// Cells are classified on a lattice of square blocks (side `lattice_spacing` metres); every free cell of a
// block takes the result of its block's sample cell.
#include <mrpt/config/CLoadableOptions.h>

#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "gridtopo/core/option_schema.h"
#include "gridtopo/core/bulk_allocator.h"
#include "gridtopo/places/occupancy.h"

namespace gridtopo::places {

/// What a simulated beam reads when it meets an unknown cell or leaves the map (issue 15, item 2). A real laser
/// logs a beam that meets nothing as "no return", which every reader turns into the maximum range, so no return
/// and max range are one choice here.
enum class BeamStop {
  kObstacle,  ///< the beam ends there: range = distance to that cell (or to the map border)
  kMaxRange,  ///< the beam reads max_range (no return)
  kPass,      ///< unknown cells only: the beam goes on through them as through free cells
};
/// "obstacle" / "max_range" / "pass"; parseBeamStop throws InputError(where, 0, key, ...) for other text, and
/// for "pass" when `allow_pass` is false (the map border: there is nothing beyond it to pass into).
std::string beamStopName(BeamStop b);
BeamStop parseBeamStop(const std::string& text, const std::string& where, const std::string& key, bool allow_pass);

struct ScanSimulationOptions;
/// The key table of ScanSimulationOptions ([scan_simulation]).
const OptionSchema<ScanSimulationOptions>& scanSimulationOptionSchema();

/// Loaded, saved, dumped and validated through scanSimulationOptionSchema (section [scan_simulation] of a training INI).
struct ScanSimulationOptions : TableOptions<ScanSimulationOptions, scanSimulationOptionSchema> {
  static constexpr const char* kSection = "scan_simulation";
  int num_beams = 360;          ///< beams per scan (even, >= 8); 360 = 1 degree apart
  double max_range = 30.0;      ///< metres; longer beams are capped here (<= 65 m)
  double lattice_spacing = 0.1; ///< metres between classified cells (block side); <= resolution = every cell
  int threads = 2;              ///< worker threads (results do not depend on it)
  BeamStop unknown_cells = BeamStop::kObstacle;  ///< a beam that meets an unknown cell (`unknown_cells`)
  BeamStop map_border = BeamStop::kObstacle;     ///< a beam that leaves the image (`map_border`; not kPass)
};

/// The classification lattice: blocks of stride x stride cells, one sample cell (free) per block that has any
/// free cell (the free cell nearest the block centre).
struct Lattice {
  int stride = 1;
  cv::Mat block_sample;             ///< CV_32S, blocks grid (ceil(rows/stride) x ceil(cols/stride)); -1 = no free cell
  std::vector<cv::Point> samples;   ///< pixel (x = col, y = row) of each sample
  std::vector<cv::Point> blocks;    ///< block coordinates of each sample

  /// Sample index whose result a pixel takes, or -1 (pixel not free is not checked here).
  int sampleOfPixel(int row, int col) const { return block_sample.at<int>(row / stride, col / stride); }
};

Lattice buildLattice(const OccupancyImage& occ, double lattice_spacing);

/// Simulated scans of the lattice samples: ranges in millimetres (uint16), beam k at angle 2*pi*k/M
/// counter-clockwise from the image's +x (column) axis, with image up (decreasing row) as +y.
struct SimulatedScans {
  int num_beams = 0;
  /// samples x num_beams; a bulk buffer (core/bulk_allocator.h): resize() does not zero it
  std::vector<std::uint16_t, BulkAllocator<std::uint16_t>> ranges_mm;
  std::size_t size() const { return num_beams ? ranges_mm.size() / static_cast<std::size_t>(num_beams) : 0; }
  const std::uint16_t* scan(std::size_t i) const { return ranges_mm.data() + i * static_cast<std::size_t>(num_beams); }
};

/// Simulates the scans of `samples` (pixels that must be free). Beams stop at the first occupied cell; at an
/// unknown cell and at the image border they do what `unknown_cells` and `map_border` say (by default they stop
/// there as at an obstacle). `progress(done, total)` is called after each pair of directions (from the calling
/// thread only).
SimulatedScans simulateScans(const OccupancyImage& occ, const std::vector<cv::Point>& samples,
                             const ScanSimulationOptions& options,
                             const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The same ranges beam-major: CV_16U, num_beams x samples (row k holds beam k of every sample), without the
/// sample-major copy simulateScans makes. The sweeps cover only the rows of the samples and scanRowMargin rows on
/// either side (what a beam reads depends on nothing farther), so a stripe of samples costs a stripe of the map;
/// the ranges are those of the whole-map sweeps, bit for bit.
cv::Mat simulateBeams(const OccupancyImage& occ, const std::vector<cv::Point>& samples,
                      const ScanSimulationOptions& options,
                      const std::function<void(std::size_t, std::size_t)>& progress = {});

/// Rows beyond a sample's row that its simulated beams depend on: floor(max_range / resolution) + 3.
int scanRowMargin(const OccupancyImage& occ, const ScanSimulationOptions& options);

}  // namespace gridtopo::places
