#pragma once
// Doorways from the robot's trajectory: a door the robot went through is a fact, not a guess. Along the path
// (gridtopo-slam's trajectory.txt, `-t`), every cell-length step measures the width of the places across the
// direction of travel: the shortest chord through the robot's position, wall to wall, within `max_angle` of the
// normal to the travel direction (a door crossed at a slant still measures its own width; where the places'
// distance transform gives a clearance of at least half of max_width + wider_by, the width is twice the clearance,
// without casting rays: wide enough for every test below). A door passage is a
//   - short stretch of the path (at most `max_length` long) where that width lies in [min_width, max_width], and
//   - on both sides of it, within `context` along the path, the width grows beyond the door's by `wider_by` (the
//     path leaves a narrow corridor or runs along a shelf: no door), and
//   - the path enters on one side of the door's chord and leaves on the other (the robot went through; it did not
//     turn back in the opening).
// The door's chord at its narrowest point of the stretch is drawn into the labels as a doorway `depth` thick (wall
// to wall, across the travel direction), after the doorways from geometry (doorway_geometry.h) and the
// classifier's: a door the robot passed is never missing, one it did not pass still comes from the map. Doors
// passed several times (within the door's width of each other) are one.
#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

namespace gridtopo::topology {

struct DoorPassageOptions {
  bool enabled = true;      ///< [topology] door_passages
  double min_width = 0.6;   ///< [topology] door_passage_min_width (m)
  double max_width = 1.4;   ///< [topology] door_passage_max_width (m)
  double max_length = 1.0;  ///< [topology] door_passage_max_length (m): the narrow stretch along the path at most
  double wider_by = 0.4;    ///< [topology] door_passage_wider_by (m): before and after, the width exceeds the door's
  double context = 1.5;     ///< [topology] door_passage_context (m): how far along the path before and after
  double max_angle = 45;    ///< [topology] door_passage_max_angle (degrees): chords within this of the normal
  double depth = 0.25;      ///< [topology] door_passage_depth (m): the doorway's thickness across its chord
  bool room_entries = true; ///< [topology] door_passage_room_entries (addRoomEntries)
  double entry_depth = 1.0; ///< [topology] door_passage_entry_depth (m): how far into the room the path must go
};

/// One door the path went through: its chord (cells, the first non-place cell at either end), the narrowest
/// point's cell, the width and the index of the path sample there (samples are `samplePath`'s).
struct DoorPassage {
  cv::Point2d a, b;
  cv::Point centre;
  double width = 0;  ///< m
  std::size_t sample = 0;
  int passes = 1;    ///< how often the path went through it
};

/// The path (cells, as pathInCells) resampled every `step` cells along its polyline; jumps longer than
/// `max_jump` cells (a gap in the trajectory; findDoorPassages: 3 m) start a new piece: pieces are separated by a
/// NaN point.
std::vector<cv::Point2d> samplePath(const std::vector<cv::Point2d>& path, double step = 1.0, double max_jump = 40.0);

/// A step of more than this between two poses is a gap in the trajectory (m), for every step that reads the path.
constexpr double kMaxPathJump = 3.0;

/// The path resampled every cell (samplePath, gaps at kMaxPathJump) and the region of `ids` (CV_32S, RegionMap::ids)
/// at each sample: 0 off every region, -1 at a gap.
struct PathOverRegions {
  std::vector<cv::Point2d> samples;
  std::vector<int> region;
};
PathOverRegions pathOverRegions(const std::vector<cv::Point2d>& path, const cv::Mat& ids, double resolution);

/// The doors that `path` (cells of the map, pathInCells) went through in `places` (CV_8U, non-zero = a place,
/// everything else is wall), in the order the path first passed them.
std::vector<DoorPassage> findDoorPassages(const cv::Mat& places, const std::vector<cv::Point2d>& path,
                                          double resolution, const DoorPassageOptions& o);

/// `labels` (CV_8U, 0..2 or places::kNoLabel; places are the labelled cells) with the chord of every door passage
/// drawn in as doorway cells `o.depth` thick. `found` gets the passages. A copy of `labels` when disabled or without
/// a path.
cv::Mat addDoorPassages(const cv::Mat& labels, const std::vector<cv::Point2d>& path, double resolution,
                        const DoorPassageOptions& o, std::vector<DoorPassage>* found = nullptr);

/// Room entries, after the correction rules: where the path steps from a corridor region straight into a room
/// region or back (no doorway cell on the way, no doorway between the two regions within door_passage_max_width
/// of the step), the robot went
/// through the room's door even where the map shows no wall or door frame there (a SLAM map's open door, a wall
/// seen only in part). The room's cells within `o.depth` of the corridor region and within half
/// door_passage_max_width of the step become a doorway: the doorway node between the room and the corridor.
/// `labels` as addDoorPassages'; `entries` gets the steps (cells), one per place (within max_width of each other).
cv::Mat addRoomEntries(const cv::Mat& labels, const std::vector<cv::Point2d>& path, double resolution,
                       const DoorPassageOptions& o, std::vector<cv::Point>* entries = nullptr);

}  // namespace gridtopo::topology
