#pragma once
// The place-labelling pipeline of Mozos et al. on one occupancy image: simulate scans on the lattice, extract
// features, classify with the decision list, relax, and spread the lattice labels to every free cell.
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "gridtopo/places/model.h"
#include "gridtopo/places/occupancy.h"
#include "gridtopo/places/relaxation.h"
#include "gridtopo/places/scan_simulation.h"

namespace gridtopo::places {

constexpr unsigned char kNoLabel = 255;  ///< value of non-free cells in label images

struct LabellingResult {
  Lattice lattice;
  cv::Mat valid;                   ///< CV_8U lattice grid: 1 where a block has a sample (see labelPlaces' keep_grids)
  cv::Mat probs_initial, probs;    ///< CV_32FC3 lattice grids: classifier output, after relaxation
  RelaxationResult relaxation;
  cv::Mat labels_initial, labels;  ///< CV_8U per map cell: 0 room, 1 corridor, 2 doorway, kNoLabel not free
  double seconds_scans = 0, seconds_features = 0, seconds_classify = 0, seconds_relax = 0;
  /// The scans' and features' processor time (every thread's, std::clock): unlike the wall seconds, not stretched by
  /// other processes sharing the machine.
  double cpu_seconds_scans = 0, cpu_seconds_features = 0;
  /// The simulated scans and the features of the lattice samples: filled only when labelPlaces is asked to keep
  /// them (the GUI inspects them per cell).
  SimulatedScans scans;
  cv::Mat features;  ///< CV_32F samples x features
};

/// Steps 1-5 of the method, the one call every app and the GUI make: lattice, simulated scans, features, the
/// decision list, relaxation. `keep_scans_and_features`: also return the scans and features (for inspection).
/// `keep_initial` false: probs_initial and labels_initial stay empty (the relaxation then works on the classifier's
/// grid itself: a lattice grid of 12 bytes per block less at once on a large map; every other result the same).
/// `keep_grids` false (with a model without context features and without keep_scans_and_features): valid, probs and
/// probs_initial stay empty, and the relaxation works on a grid of only the part of the lattice it relaxes
/// (relaxationBox) instead of the whole map's; the labels the same.
/// Throws gridtopo::InputError (naming `source`) if the map has no free cell.
LabellingResult labelPlaces(const OccupancyImage& occ, const PlacesModel& model, const RelaxationOptions& relax,
                            int threads = 2, const std::string& source = "<map>",
                            const std::function<void(const std::string&, std::size_t, std::size_t)>& progress = {},
                            bool keep_scans_and_features = false, bool keep_initial = true,
                            bool keep_grids = true);

/// Samples per stripe of labelPlaces: the simulated scans (2 bytes per beam) and features of this many samples
/// are held at a time (about 260 MB with 360 beams and 74 features).
constexpr std::size_t kStripeSamples = std::size_t(1) << 18;

/// The lattice's samples in stripes of whole block rows, each of at most `max_samples` samples (or one block row):
/// [first, last) index ranges in order.
std::vector<std::pair<std::size_t, std::size_t>> latticeStripes(const Lattice& lattice, std::size_t max_samples);

/// The classifier's output (samples x 1, CV_32FC3) for every sample of `lattice`: scans (simulateBeams), features
/// and classification a stripe (latticeStripes(lattice, stripe_samples)) at a time; the same bits for any stripe
/// size. `progress(done, total)` counts pairs of beam directions over all stripes. Needs a model without context
/// features (they need every sample's features at once). `seconds`, when given, receives each step's seconds added
/// up over the stripes.
struct LatticeSeconds {
  double scans = 0, features = 0, classify = 0;  ///< wall
  double cpu_scans = 0, cpu_features = 0;        ///< processor (every thread's, std::clock)
};
cv::Mat classifyLattice(const OccupancyImage& occ, const Lattice& lattice, const PlacesModel& model, int threads,
                        std::size_t stripe_samples, const std::function<void(std::size_t, std::size_t)>& progress = {},
                        LatticeSeconds* seconds = nullptr);

/// Classifies precomputed features (as from computeSamples) and relaxes: used by training/evaluation.
LabellingResult labelFromFeatures(const OccupancyImage& occ, const Lattice& lattice, const cv::Mat& features,
                                  const PlacesModel& model, const RelaxationOptions& relax, int threads = 2);

/// Per-cell labels (argmax of the block's distribution) for every free cell; kNoLabel elsewhere.
/// `probs` may cover a part of the lattice grid whose block (0, 0) is the grid's `grid_offset` (every block with a
/// sample inside it).
cv::Mat cellLabels(const OccupancyImage& occ, const Lattice& lattice, const cv::Mat& probs,
                   cv::Point grid_offset = {});

/// Label indices -> training-map codes (room 77, corridor 115, doorway 179, 0 elsewhere).
cv::Mat labelsToCodes(const cv::Mat& labels);
/// Training-map codes -> label indices (0 room, 1 corridor, 2 doorway; kNoLabel for any other code): the inverse
/// of labelsToCodes, e.g. to read back a labels.png of gridtopo-topology.
cv::Mat labelsFromCodes(const cv::Mat& codes);

}  // namespace gridtopo::places
