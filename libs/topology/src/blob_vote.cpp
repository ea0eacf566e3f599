#include "gridtopo/topology/blob_vote.h"

#include <deque>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "gridtopo/places/labelling.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/core/distance_transform.h"
#include "mask_ops.h"

namespace gridtopo::topology {

namespace {
constexpr int kRoom = static_cast<int>(places::PlaceLabel::Room);
constexpr int kCorridor = static_cast<int>(places::PlaceLabel::Corridor);
constexpr int kDoorway = static_cast<int>(places::PlaceLabel::Doorway);

// The vote over `areas`; with `vote_doorway_cells`, cells labelled doorway count and are voted as well.
cv::Mat voteAreas(const cv::Mat& labels, const cv::Mat& areas, const cv::Mat& probs, double min_share,
                  bool vote_doorway_cells) {
  CV_Assert(labels.type() == CV_8U && areas.type() == CV_32S && probs.type() == CV_32FC3);
  CV_Assert(labels.size() == areas.size() && labels.size() == probs.size());
  double mx = 0;
  cv::minMaxLoc(areas, nullptr, &mx);
  const auto n = static_cast<std::size_t>(mx) + 1;
  std::vector<double> room(n, 0.0), corridor(n, 0.0);
  auto votes = [&](int l) { return l == kRoom || l == kCorridor || (vote_doorway_cells && l == kDoorway); };
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      const int a = areas.at<int>(y, x);
      if (a <= 0 || !votes(labels.at<unsigned char>(y, x))) continue;
      const cv::Vec3f& p = probs.at<cv::Vec3f>(y, x);
      room[static_cast<std::size_t>(a)] += p[kRoom];
      corridor[static_cast<std::size_t>(a)] += p[kCorridor];
    }
  std::vector<int> winner(n, -1);
  for (std::size_t a = 1; a < n; ++a) {
    const double sum = room[a] + corridor[a];
    if (!(sum > 0)) continue;
    const int w = corridor[a] > room[a] ? kCorridor : kRoom;
    if ((w == kRoom ? room[a] : corridor[a]) >= min_share * sum) winner[a] = w;
  }
  cv::Mat out = labels.clone();
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      const int a = areas.at<int>(y, x);
      unsigned char& l = out.at<unsigned char>(y, x);
      if (a <= 0 || !votes(l)) continue;
      const int w = winner[static_cast<std::size_t>(a)];
      if (w >= 0) l = static_cast<unsigned char>(w);
    }
  return out;
}
}  // namespace

cv::Mat cellProbabilities(const cv::Mat& labels, const places::Lattice& lattice, const cv::Mat& lattice_probs) {
  CV_Assert(labels.type() == CV_8U && lattice_probs.type() == CV_32FC3);
  cv::Mat out(labels.size(), CV_32FC3, cv::Scalar::all(0));
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      if (labels.at<unsigned char>(y, x) >= places::kNumLabels) continue;
      const int by = y / lattice.stride, bx = x / lattice.stride;
      if (lattice.block_sample.at<int>(by, bx) < 0) continue;
      out.at<cv::Vec3f>(y, x) = lattice_probs.at<cv::Vec3f>(by, bx);
    }
  return out;
}

cv::Mat geometricBlobs(const cv::Mat& free_mask, double resolution, const BlobVoteOptions& o) {
  CV_Assert(free_mask.type() == CV_8U && resolution > 0);
  // Free cells with a one-cell non-free frame, so the image border counts as a wall.
  cv::Mat free(free_mask.rows + 2, free_mask.cols + 2, CV_8U, cv::Scalar(0));
  cv::compare(free_mask, 0, free(cv::Rect(1, 1, free_mask.cols, free_mask.rows)), cv::CMP_NE);
  // Obstacles not connected to the frame and no larger than fill_obstacle_area: furniture.
  const double fill_px = o.fill_obstacle_area / (resolution * resolution);
  const cv::Mat area = fill_px > 0 ? fillSmallHoles(free, fill_px) : free.clone();
  cv::Mat dist, core, cc, stats, cent;
  dist = preciseDistance(area);
  cv::compare(dist, 0.5 * o.neck_width / resolution, core, cv::CMP_GT);
  const int n = cv::connectedComponentsWithStats(core, cc, stats, cent, 8, CV_32S);
  const double min_core_px = o.min_core_area / (resolution * resolution);
  std::vector<int> id(static_cast<std::size_t>(n), 0);
  int next = 0;
  for (int c = 1; c < n; ++c)
    if (stats.at<int>(c, cv::CC_STAT_AREA) >= min_core_px) id[static_cast<std::size_t>(c)] = ++next;
  cv::Mat blobs(free.size(), CV_32S, cv::Scalar(0));
  for (int y = 0; y < cc.rows; ++y)
    for (int x = 0; x < cc.cols; ++x) {
      const int b = id[static_cast<std::size_t>(cc.at<int>(y, x))];
      if (b && free.at<unsigned char>(y, x)) blobs.at<int>(y, x) = b;
    }
  const int max_steps = o.grow_limit > 0 ? static_cast<int>(o.grow_limit / resolution) : -1;
  growSeeds(blobs, free, max_steps);
  if (max_steps >= 0) {
    // Free cells no core reached within the limit: blobs of their own.
    cv::Mat rest = free & (blobs == 0), rc;
    const int m = cv::connectedComponents(rest, rc, 8, CV_32S);
    (void)m;
    for (int y = 0; y < rc.rows; ++y)
      for (int x = 0; x < rc.cols; ++x)
        if (const int c = rc.at<int>(y, x)) blobs.at<int>(y, x) = next + c;
  }
  return blobs(cv::Rect(1, 1, free_mask.cols, free_mask.rows)).clone();
}

cv::Mat voteLabelsInAreas(const cv::Mat& labels, const cv::Mat& areas, const cv::Mat& cell_probs, double min_share,
                          bool vote_doorway_cells) {
  return voteAreas(labels, areas, cell_probs, min_share, vote_doorway_cells);
}

cv::Mat voteInGeometricBlobs(const cv::Mat& labels, double resolution, const BlobVoteOptions& options,
                             const places::Lattice& lattice, const cv::Mat& lattice_probs) {
  const cv::Mat blobs = geometricBlobs(labels < places::kNumLabels, resolution, options);
  return voteLabelsInAreas(labels, blobs, cellProbabilities(labels, lattice, lattice_probs), options.min_share);
}

}  // namespace gridtopo::topology
