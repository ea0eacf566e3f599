#include "gridtopo/slam/place_signature.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gridtopo::slam {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

PlaceSignature::PlaceSignature(const std::vector<Point2>& points, const PlaceSignatureShape& shape)
    : rings_(shape.rings), sectors_(shape.sectors) {
  bins_.assign(static_cast<std::size_t>(rings_) * sectors_, 0);
  const double ring_width = shape.radius / rings_;
  for (const Point2& p : points) {
    const double r = std::hypot(p.x, p.y);
    if (r >= shape.radius) continue;
    const int ring = std::min(rings_ - 1, static_cast<int>(r / ring_width));
    double a = std::atan2(p.y, p.x);
    if (a < 0.0) a += 2.0 * kPi;
    const int sector = std::min(sectors_ - 1, static_cast<int>(a / (2.0 * kPi) * sectors_));
    bins_[static_cast<std::size_t>(sector) * rings_ + ring] = 1;
  }
  col_norm_.assign(static_cast<std::size_t>(sectors_), 0.0f);
  sector_key_.assign(static_cast<std::size_t>(sectors_), 0);
  ring_key_.assign(static_cast<std::size_t>(rings_), 0.0f);
  for (int s = 0; s < sectors_; ++s) {
    double n2 = 0.0;
    for (int r = 0; r < rings_; ++r) {
      const double v = bins_[static_cast<std::size_t>(s) * rings_ + r];
      n2 += v * v;
      if (v > 0) {
        ring_key_[static_cast<std::size_t>(r)] += 1.0f;
        ++sector_key_[static_cast<std::size_t>(s)];
      }
    }
    col_norm_[static_cast<std::size_t>(s)] = static_cast<float>(std::sqrt(n2));
    if (n2 > 0.0) ++occupied_sectors_;
  }
  for (float& k : ring_key_) k /= static_cast<float>(sectors_);
}

double PlaceSignature::ringKeyDistance(const PlaceSignature& other) const {
  if (ring_key_.size() != other.ring_key_.size() || ring_key_.empty()) return 1.0;
  double d = 0.0;
  for (std::size_t r = 0; r < ring_key_.size(); ++r) d += std::abs(ring_key_[r] - other.ring_key_[r]);
  return d / static_cast<double>(ring_key_.size());
}

double PlaceSignature::distanceAtShift(const PlaceSignature& other, int shift) const {
  // Sector s of this signature against sector s − shift of the other: the other's frame turned by +shift sectors.
  double sim = 0.0;
  int used = 0;
  for (int s = 0; s < sectors_; ++s) {
    const int t = ((s - shift) % sectors_ + sectors_) % sectors_;
    const float na = col_norm_[static_cast<std::size_t>(s)], nb = other.col_norm_[static_cast<std::size_t>(t)];
    if (na == 0.0f && nb == 0.0f) continue;
    ++used;
    if (na == 0.0f || nb == 0.0f) continue;  // one side empty: similarity 0
    const std::uint8_t* a = &bins_[static_cast<std::size_t>(s) * rings_];
    const std::uint8_t* b = &other.bins_[static_cast<std::size_t>(t) * rings_];
    int dot = 0;
    for (int r = 0; r < rings_; ++r) dot += static_cast<int>(a[r]) * b[r];
    sim += dot / (static_cast<double>(na) * nb);
  }
  return used ? 1.0 - sim / used : 1.0;
}

double PlaceSignature::yawOfShift(int shift) const {
  // The other's sector t seen at this one's sector t + shift: a point at angle a in the other's frame lies at
  // a + shift·Δ in this one's, so the other's frame is turned by that much.
  double y = (((shift % sectors_) + sectors_) % sectors_) * 2.0 * kPi / sectors_;
  if (y > kPi) y -= 2.0 * kPi;
  return y;
}

double PlaceSignature::distance(const PlaceSignature& other, double* yaw) const {
  if (empty() || other.empty() || rings_ != other.rings_ || sectors_ != other.sectors_) {
    if (yaw) *yaw = 0.0;
    return 1.0;
  }
  double best = std::numeric_limits<double>::infinity();
  int best_shift = 0;
  for (int shift = 0; shift < sectors_; ++shift) {
    const double d = distanceAtShift(other, shift);
    if (d < best) {
      best = d;
      best_shift = shift;
    }
  }
  if (yaw) *yaw = yawOfShift(best_shift);
  return best;
}

double PlaceSignature::alignedDistance(const PlaceSignature& other, double* yaw) const {
  if (empty() || other.empty() || rings_ != other.rings_ || sectors_ != other.sectors_) {
    if (yaw) *yaw = 0.0;
    return 1.0;
  }
  int best_key = std::numeric_limits<int>::max(), key_shift = 0;
  for (int shift = 0; shift < sectors_; ++shift) {
    int d = 0;
    for (int s = 0; s < sectors_; ++s) {
      const int t = (s - shift + sectors_) % sectors_;
      d += std::abs(static_cast<int>(sector_key_[static_cast<std::size_t>(s)]) - other.sector_key_[static_cast<std::size_t>(t)]);
    }
    if (d < best_key) {
      best_key = d;
      key_shift = shift;
    }
  }
  double best = std::numeric_limits<double>::infinity();
  int best_shift = key_shift;
  for (int k = -2; k <= 2; ++k) {
    const double d = distanceAtShift(other, key_shift + k);
    if (d < best) {
      best = d;
      best_shift = key_shift + k;
    }
  }
  if (yaw) *yaw = yawOfShift(best_shift);
  return best;
}

}  // namespace gridtopo::slam
