#include "mask_ops.h"

#include <deque>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace gridtopo::topology {

cv::Mat fillSmallHoles(const cv::Mat& mask, double max_cells, const cv::Mat& veto) {
  CV_Assert(mask.type() == CV_8U && (veto.empty() || (veto.type() == CV_8U && veto.size() == mask.size())));
  cv::Mat cc, stats, cent;
  const int n = cv::connectedComponentsWithStats(mask == 0, cc, stats, cent, 4, CV_32S);
  std::vector<unsigned char> fill(static_cast<std::size_t>(n), 0);
  for (int c = 1; c < n; ++c) fill[static_cast<std::size_t>(c)] = stats.at<int>(c, cv::CC_STAT_AREA) <= max_cells;
  for (int y = 0; y < cc.rows; ++y)
    for (int x = 0; x < cc.cols; ++x) {
      const int c = cc.at<int>(y, x);
      if (!c) continue;
      const bool border = y == 0 || x == 0 || y == cc.rows - 1 || x == cc.cols - 1;
      if (border || (!veto.empty() && veto.at<unsigned char>(y, x))) fill[static_cast<std::size_t>(c)] = 0;
    }
  cv::Mat out = mask.clone();
  for (int y = 0; y < cc.rows; ++y)
    for (int x = 0; x < cc.cols; ++x)
      if (fill[static_cast<std::size_t>(cc.at<int>(y, x))]) out.at<unsigned char>(y, x) = 255;
  return out;
}

void growSeeds(cv::Mat& ids, const cv::Mat& allowed, int max_steps) {
  CV_Assert(ids.type() == CV_32S && allowed.type() == CV_8U && ids.size() == allowed.size());
  cv::Mat steps;
  if (max_steps >= 0) steps = cv::Mat(ids.size(), CV_32S, cv::Scalar(0));
  // Only seeds with a cell to take next to them are queued: cells are only ever taken, never given back, so a
  // seed with none now never takes one, and leaving it out changes neither the order nor the result.
  const auto open = [&](int y, int x) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int yy = y + dy, xx = x + dx;
        if (yy < 0 || xx < 0 || yy >= ids.rows || xx >= ids.cols) continue;
        if (allowed.at<unsigned char>(yy, xx) && !ids.at<int>(yy, xx)) return true;
      }
    return false;
  };
  std::deque<cv::Point> q;
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x)
      if (ids.at<int>(y, x) > 0 && open(y, x)) q.emplace_back(x, y);
  while (!q.empty()) {
    const cv::Point p = q.front();
    q.pop_front();
    const int st = max_steps >= 0 ? steps.at<int>(p) + 1 : 0;
    if (max_steps >= 0 && st > max_steps) continue;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int yy = p.y + dy, xx = p.x + dx;
        if (yy < 0 || xx < 0 || yy >= ids.rows || xx >= ids.cols) continue;
        if (!allowed.at<unsigned char>(yy, xx) || ids.at<int>(yy, xx)) continue;
        ids.at<int>(yy, xx) = ids.at<int>(p);
        if (max_steps >= 0) steps.at<int>(yy, xx) = st;
        q.emplace_back(xx, yy);
      }
  }
}

}  // namespace gridtopo::topology
