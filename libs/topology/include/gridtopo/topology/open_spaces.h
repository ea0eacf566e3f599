#pragma once
// One node per open space the robot crossed (issue 35): a large open space must not come out as alternating room /
// corridor pieces. The robot's trajectory says which neighbouring pieces are one space: where the path steps from a
// room region straight into a corridor region or back (consecutive path cells, no doorway cell between them), and
// the two regions share a border at least `min_contact` long (no constriction between them: a door is narrower),
// the two pieces belong to one space. Pieces joined so form a space; the space takes the label of the larger
// labelled area (an area-weighted vote of the classifier's labels). A piece whose label would change must have been
// crossed: the path entered it from a piece of the space and left it into a piece of the space (straight steps
// both) at points at least `min_through` apart, and at least `min_shared` of its border (8-neighbour cell pairs with
// any cell outside it: walls, unknown, other regions) lies against the space's other pieces (it lies inside the
// space, not beside it); otherwise (a room the robot entered through its open side and left the same way, a room
// open onto a corridor along part of one wall, the corridor loop beside a row of such rooms) the piece leaves the
// space and keeps its label, and the vote is taken again without it. Runs after the correction rules, before the room entries (door_passages.h), so that the
// room entries never put a doorway between two pieces of one space.
#include <opencv2/core.hpp>

#include <vector>

namespace gridtopo::topology {

struct OpenSpaceOptions {
  bool enabled = false;      ///< [topology] open_spaces (needs the robot's path; off: no gain on the Intel maps)
  double min_contact = 2.0;  ///< [topology] open_space_min_contact (m): the two pieces' shared border at least
  double min_through = 2.0;  ///< [topology] open_space_min_through (m): a relabelled piece was crossed this far
  double min_shared = 0.3;   ///< [topology] open_space_min_shared: a relabelled piece's border share with the space
};

/// One space of several pieces joined by the rule.
struct OpenSpace {
  int label = 0;         ///< the space's label (places::PlaceLabel as int: room or corridor)
  int pieces = 0;        ///< room / corridor regions joined
  int relabelled = 0;    ///< of them, pieces whose label changed
  double area_m2 = 0;    ///< the space's area
  double relabelled_m2 = 0;
  cv::Point at;          ///< a cell of the space's largest piece (its centroid's cell when that is in the piece)
};

/// `labels` (CV_8U, 0..2 or places::kNoLabel, after the correction rules) with the room / corridor pieces of every
/// open space the path (cells, pathInCells) crossed set to the space's label. `spaces` gets the spaces of more than
/// one piece. A copy of `labels` when disabled or without a path.
cv::Mat mergeOpenSpaces(const cv::Mat& labels, const std::vector<cv::Point2d>& path, double resolution,
                        const OpenSpaceOptions& o, std::vector<OpenSpace>* spaces = nullptr);

}  // namespace gridtopo::topology
