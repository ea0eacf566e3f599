#pragma once
// Exports of a topological map: GraphML, JSON, DOT, a PNG overlay, and the pixel-aligned label and
// room-segmentation images.
#include <opencv2/core.hpp>
#include <string>

#include "gridtopo/places/occupancy.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/door_passages.h"
#include "gridtopo/topology/graph.h"
#include "gridtopo/topology/regions.h"

namespace gridtopo::topology {

std::string toGraphML(const TopologicalGraph& g);
std::string toJson(const TopologicalGraph& g);
std::string toDot(const TopologicalGraph& g);

/// Parses back what toJson() wrote (through OpenCV's JSON reader). Throws gridtopo::InputError.
TopologicalGraph graphFromJson(const std::string& path);

/// How overlay.png and the GUI draw a free cell that is no place (places::kSeen, map_preparation.h) at column x,
/// row y: light grey crossed by a fine darker diagonal hatch (BGR).
inline cv::Vec3b seenNotPlaceColour(int x, int y) {
  return (x + y) % 6 < 2 ? cv::Vec3b(150, 150, 150) : cv::Vec3b(225, 225, 225);
}

/// The enlargement overlay.png gets: `requested` (at least 1) lowered until the image has at most
/// kOverlayMaxSide pixels a side and kOverlayMaxPixels in all (ImageMagick's default limits on Debian 12: 16 KP
/// width and height, 128 MP area), so that common tools open it; 1 if even that is larger. On the Freiburg
/// hospital's SLAM map (10 079 x 5 034 cells) the default 2 would give a 20 158 x 10 068 image of 609 MB.
inline constexpr int kOverlayMaxSide = 16384;
inline constexpr long long kOverlayMaxPixels = 128LL * 1000 * 1000;
int overlayScaleFor(cv::Size map, int requested);

/// Colour overlay: the map in grey, free cells that are no place hatched (seenNotPlaceColour), place labels coloured (room blue, corridor green, doorway red), region
/// borders, region ids at the centroids and the graph drawn on top. `scale` >= 1 enlarges the image (as far as
/// overlayScaleFor allows).
/// `door_passages`, when given: the chords of the doors the robot's path went through (door_passages.h), in magenta.
/// `labels` and `regions` may cover a part of the map (TopologyResult::frame): their cell (0, 0) is the map's cell
/// `frame`; the graph and the door passages are in the map's frame.
cv::Mat renderOverlay(const places::OccupancyImage& occ, const cv::Mat& labels, const RegionMap& regions,
                      const TopologicalGraph& g, int scale = 2,
                      const std::vector<DoorPassage>* door_passages = nullptr, cv::Point frame = {});
/// The same with the region borders given as regionBorders of the regions' ids (same size as `labels`).
cv::Mat renderOverlay(const places::OccupancyImage& occ, const cv::Mat& labels, const cv::Mat& region_borders,
                      const TopologicalGraph& g, int scale = 2,
                      const std::vector<DoorPassage>* door_passages = nullptr, cv::Point frame = {});

/// The cells renderOverlay draws as region borders: CV_8U, 255 where a cell of a region (id > 0) has a right or
/// lower neighbour in another region, 0 elsewhere. `ids`: CV_32S region ids (RegionMap::ids).
cv::Mat regionBorders(const cv::Mat& ids);

/// Throws std::runtime_error when `segmentation` (CV_32S) has ids above 65535 (too many for a 16-bit picture).
void requireSixteenBitSegments(const cv::Mat& segmentation);

/// Room segmentation as a 16-bit image (ids <= 65535; throws otherwise, requireSixteenBitSegments), 0 for non-free
/// cells.
cv::Mat segmentationImage16(const cv::Mat& segmentation);

/// Saturated label colours (BGR) of the evaluation views: room blue, corridor green, doorway red.
inline const cv::Vec3b kLabelColoursBgr[places::kNumLabels] = {{220, 60, 0}, {0, 170, 0}, {0, 0, 230}};


/// The colour of segment `id` in colourSegmentation (black for 0).
cv::Vec3b segmentColour(int id);

/// A colour rendering of a segmentation (random but fixed colour per id, segmentColour) for viewing.
cv::Mat colourSegmentation(const cv::Mat& segmentation);

}  // namespace gridtopo::topology
