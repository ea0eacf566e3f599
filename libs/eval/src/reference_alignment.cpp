#include "gridtopo/eval/reference_alignment.h"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <cmath>
#include <map>

#include "gridtopo/core/error.h"
#include "gridtopo/places/place_label.h"

namespace gridtopo::eval {

namespace {
// Free mask as a smooth float image: ECC needs gradients away from the walls, so the masks are blurred.
cv::Mat smoothMask(const cv::Mat& free_mask, double sigma) {
  cv::Mat f;
  cv::Mat(free_mask != 0).convertTo(f, CV_32F, 1.0 / 255.0);
  cv::GaussianBlur(f, f, cv::Size(0, 0), sigma);
  return f;
}
cv::Point2d centroid(const cv::Mat& mask) {
  const cv::Moments m = cv::moments(mask != 0, true);
  return {m.m10 / m.m00, m.m01 / m.m00};
}
}  // namespace

ReferenceAlignment identityAlignment(const cv::Mat& map_free, const cv::Mat& reference_free) {
  CV_Assert(map_free.size() == reference_free.size());
  ReferenceAlignment a;
  a.map_to_reference = cv::Matx23d(1, 0, 0, 0, 1, 0);
  a.correlation = cv::computeECC(smoothMask(map_free, 3.0), smoothMask(reference_free, 3.0));
  return a;
}

ReferenceAlignment alignReference(const cv::Mat& map_free, const cv::Mat& reference_free, const std::string& source) {
  const double area_map = cv::countNonZero(map_free), area_ref = cv::countNonZero(reference_free);
  if (area_map <= 0) throw InputError(source, "the map has no free cell to align");
  if (area_ref <= 0) throw InputError(source, "the reference has no free cell to align");
  const double scale = std::sqrt(area_ref / area_map);  // reference pixels per map pixel
  const cv::Point2d cm = centroid(map_free), cr = centroid(reference_free);
  // Every start is climbed on quarter-size masks blurred a lot (wide capture, cheap); the best one is then refined
  // at full size with less blur (precise walls).
  const double f = 0.25;
  cv::Mat map_small, ref_small;
  cv::resize(map_free != 0, map_small, cv::Size(), f, f, cv::INTER_AREA);
  cv::resize(reference_free != 0, ref_small, cv::Size(), f, f, cv::INTER_AREA);
  const cv::Mat map_coarse = smoothMask(map_small, 2.0), ref_coarse = smoothMask(ref_small, 2.0 * scale);
  const auto criteria = cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-6);
  ReferenceAlignment best;
  best.correlation = -2;
  cv::Mat best_warp;
  for (int start = 0; start < 8; ++start) {
    // Rotation by k * 90° (and mirroring of x first if bit 2): R maps map offsets to reference offsets.
    const int k = start & 3;
    const double c = k == 0 ? 1 : k == 2 ? -1 : 0, s = k == 1 ? 1 : k == 3 ? -1 : 0;
    const double mx = (start & 4) ? -1 : 1;
    cv::Matx22d R(c * mx * scale, -s * scale, s * mx * scale, c * scale);
    cv::Matx21d t = cv::Matx21d(cr.x, cr.y) - R * cv::Matx21d(cm.x, cm.y);
    // In quarter-size pixels the linear part is the same and the translation scales by f.
    cv::Mat warp = (cv::Mat_<float>(2, 3) << R(0, 0), R(0, 1), f * t(0), R(1, 0), R(1, 1), f * t(1));
    double rho = -2;
    try {
      rho = cv::findTransformECC(map_coarse, ref_coarse, warp, cv::MOTION_AFFINE, criteria, cv::noArray(), 1);
    } catch (const cv::Exception&) {
      continue;  // this start diverged (ECC throws when the warp leaves the image)
    }
    if (rho > best.correlation) {
      best.correlation = rho;
      best.start = start;
      best_warp = warp.clone();
    }
  }
  if (best.correlation < -1) throw InputError(source, "no alignment of the reference converged");
  best_warp.at<float>(0, 2) /= static_cast<float>(f);
  best_warp.at<float>(1, 2) /= static_cast<float>(f);
  try {
    best.correlation = cv::findTransformECC(smoothMask(map_free, 3.0), smoothMask(reference_free, 3.0 * scale),
                                            best_warp, cv::MOTION_AFFINE, criteria, cv::noArray(), 1);
  } catch (const cv::Exception&) {
    throw InputError(source, "the alignment of the reference diverged at full resolution");
  }
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 3; ++j) best.map_to_reference(i, j) = best_warp.at<float>(i, j);
  return best;
}

cv::Mat warpReferenceToMap(const cv::Mat& reference, const ReferenceAlignment& a, cv::Size map_size) {
  cv::Mat src = reference, out;
  if (reference.type() == CV_32S) reference.convertTo(src, CV_32F);  // ids < 2^24 stay exact
  cv::warpAffine(src, out, cv::Mat(a.map_to_reference), map_size, cv::INTER_NEAREST | cv::WARP_INVERSE_MAP,
                 cv::BORDER_CONSTANT, cv::Scalar(0));
  if (reference.type() == CV_32S) out.convertTo(out, CV_32S);
  return out;
}

ReferenceScore scoreAgainstReference(const cv::Mat& map_free, const cv::Mat& labels, const cv::Mat& segments,
                                     const cv::Mat& reference_free, const cv::Mat& reference_codes,
                                     const cv::Mat& reference_rooms, int min_room_cells, const std::string& source) {
  CV_Assert(reference_free.size() == reference_codes.size() && reference_free.size() == reference_rooms.size());
  return scoreAligned(map_free, labels, segments, reference_codes, reference_rooms,
                      alignReference(map_free, reference_free, source), min_room_cells);
}

ReferenceScore scoreAligned(const cv::Mat& map_free, const cv::Mat& labels, const cv::Mat& segments,
                            const cv::Mat& reference_codes, const cv::Mat& reference_rooms,
                            const ReferenceAlignment& alignment, int min_room_cells) {
  CV_Assert(map_free.size() == labels.size() && map_free.size() == segments.size());
  CV_Assert(reference_codes.size() == reference_rooms.size());
  ReferenceScore r;
  r.alignment = alignment;
  const cv::Size size = map_free.size();
  cv::Mat codes = warpReferenceToMap(reference_codes, r.alignment, size);
  codes.setTo(0, map_free == 0);  // only cells our map knows to be free are scored
  r.labels.add(codes, labels);
  cv::Mat rooms = warpReferenceToMap(reference_rooms, r.alignment, size);
  rooms.setTo(0, map_free == 0);
  std::map<int, int> room_cells;
  for (int y = 0; y < rooms.rows; ++y)
    for (int x = 0; x < rooms.cols; ++x)
      if (const int g = rooms.at<int>(y, x)) ++room_cells[g];
  for (int y = 0; y < rooms.rows; ++y)
    for (int x = 0; x < rooms.cols; ++x) {
      int& g = rooms.at<int>(y, x);
      if (g && room_cells[g] < min_room_cells) g = 0;
    }
  cv::Mat seg = segments.clone();
  seg.setTo(0, rooms == 0);  // segments outside the reference's rooms (streaks, unlabelled space) are not scored
  r.segmentation = scoreSegmentation(seg, rooms);
  return r;
}

}  // namespace gridtopo::eval
