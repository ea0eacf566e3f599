#pragma once
// A rotation-invariant signature of a place for proposing loop closures anywhere in the map, whatever the drift:
// the polar occupancy grid of Scan Context (Kim & Kim, "Scan Context: Egocentric spatial descriptor for place
// recognition within 3D point cloud map", IROS 2018), taken over the points of a stretch of trajectory in the frame
// of one of its poses (a 2D laser's single scan is too little). Rings of equal width up to a radius, sectors of
// equal angle; each bin is 1 when any of the stretch's points falls in it (occupancy, not counts: counts rank the
// true place of a corridor driven back the other way far lower, since the two passes see its parts from different
// distances, doc/slam.md "Global search"). Its ring key (per
// ring, the share of occupied sectors) does not change with the heading and ranks the candidates cheaply; the full
// distance is the best over the column shifts, whose shift estimates the heading between the two places.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gridtopo/slam/correlative_matcher.h"

namespace gridtopo::slam {

struct PlaceSignatureShape {
  int rings = 15;        ///< radial bins
  int sectors = 72;      ///< angular bins (5 degrees each)
  double radius = 15.0;  ///< m, the outer ring's edge
};

class PlaceSignature {
 public:
  PlaceSignature() = default;
  /// The signature of `points` (in the frame of the signature's centre pose).
  PlaceSignature(const std::vector<Point2>& points, const PlaceSignatureShape& shape);

  bool empty() const { return occupied_sectors_ == 0; }
  const std::vector<float>& ringKey() const { return ring_key_; }
  /// Sectors that hold at least one point.
  int occupiedSectors() const { return occupied_sectors_; }

  /// The Scan Context distance: 1 − the mean cosine similarity of the two signatures' sectors (columns), over the
  /// sectors occupied in either, minimised over the column shifts; `yaw` receives the heading of `other`'s frame
  /// in this one's that the best shift implies (rad). In [0, 1]; 1 when either is empty.
  double distance(const PlaceSignature& other, double* yaw = nullptr) const;
  /// The ring keys' mean absolute difference (heading-free).
  double ringKeyDistance(const PlaceSignature& other) const;
  /// The distance at the column shift that best aligns the two sector keys (per sector, its occupied rings), and
  /// its neighbours: Scan Context's fast alignment, within a few per cent of distance() at a tenth of its cost.
  double alignedDistance(const PlaceSignature& other, double* yaw = nullptr) const;
  std::size_t bytes() const { return bins_.size() + ring_key_.size() * sizeof(float) + col_norm_.size() * sizeof(float); }

 private:
  int rings_ = 0, sectors_ = 0;
  std::vector<std::uint8_t> bins_;  ///< sector-major: bins_[sector * rings_ + ring]
  std::vector<float> col_norm_;     ///< per sector, the Euclidean norm of its column
  std::vector<float> ring_key_;
  std::vector<std::uint8_t> sector_key_;  ///< per sector, the number of occupied rings
  /// 1 − the mean cosine similarity of the columns with `other`'s turned by `shift` sectors.
  double distanceAtShift(const PlaceSignature& other, int shift) const;
  double yawOfShift(int shift) const;
  int occupied_sectors_ = 0;
};

}  // namespace gridtopo::slam
