#include "mask_ops.h"

#include <algorithm>
#include <deque>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace gridtopo::topology {

RunComponents::RunComponents(const cv::Mat& mask, bool nonzero, int connectivity) {
  CV_Assert(mask.type() == CV_8U && (connectivity == 4 || connectivity == 8));
  const int reach = connectivity == 8 ? 1 : 0;  // a run touches those of the row above that overlap it widened so
  struct Run {
    int x0, x1, id;
  };
  const auto find = [&](int a) {
    while (root[static_cast<std::size_t>(a)] != a) {
      root[static_cast<std::size_t>(a)] = root[static_cast<std::size_t>(root[static_cast<std::size_t>(a)])];
      a = root[static_cast<std::size_t>(a)];
    }
    return a;
  };
  std::vector<Run> above, here;  // the runs of the row above and of this row
  int row = -1;
  std::size_t k = 0;  // the first run above that can still touch this row's next run
  forEachRun(mask, nonzero, [&](int y, int x0, int x1) {
    if (y != row) {  // a new row: its row above is the last one's only when they are adjacent
      if (y == row + 1) std::swap(above, here);
      else above.clear();
      here.clear();
      k = 0;
      row = y;
    }
    const int id = static_cast<int>(root.size());
    root.push_back(id);
    area.push_back(x1 - x0 + 1);
    here.push_back({x0, x1, id});
    while (k < above.size() && above[k].x1 < x0 - reach) ++k;
    for (std::size_t j = k; j < above.size() && above[j].x0 <= x1 + reach; ++j) {
      const int a = find(above[j].id), c = find(id);
      if (a == c) continue;
      const int lo = std::min(a, c), hi = std::max(a, c);
      root[static_cast<std::size_t>(hi)] = lo;
      area[static_cast<std::size_t>(lo)] += area[static_cast<std::size_t>(hi)];
    }
  });
  for (std::size_t i = 0; i < root.size(); ++i) root[i] = find(static_cast<int>(i));
}

std::vector<int> rootsInBlockOrder(const cv::Mat& mask, const RunComponents& comps) {
  const long long block_cols = (mask.cols + 1) / 2;
  std::vector<long long> first_block(comps.root.size(), std::numeric_limits<long long>::max());
  std::size_t run = 0;
  forEachRun(mask, true, [&](int y, int x0, int) {
    long long& b = first_block[static_cast<std::size_t>(comps.root[run++])];
    b = std::min(b, (y / 2) * block_cols + x0 / 2);
  });
  std::vector<std::pair<long long, int>> order;
  for (std::size_t c = 0; c < comps.root.size(); ++c)
    if (comps.root[c] == static_cast<int>(c)) order.emplace_back(first_block[c], static_cast<int>(c));
  std::sort(order.begin(), order.end());
  std::vector<int> roots;
  roots.reserve(order.size());
  for (const auto& [block, root] : order) roots.push_back(root);
  return roots;
}

std::vector<int> numbersInBlockOrder(const cv::Mat& mask, const RunComponents& comps, int& count) {
  std::vector<int> number(comps.root.size(), 0);
  count = 0;
  for (const int c : rootsInBlockOrder(mask, comps)) number[static_cast<std::size_t>(c)] = ++count;
  return number;
}

std::size_t RunComponents::componentsOfAtLeast(double min_cells) const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < root.size(); ++i)
    if (root[i] == static_cast<int>(i) && area[i] >= min_cells) ++n;
  return n;
}

cv::Mat fillSmallHoles(const cv::Mat& mask, double max_cells, const cv::Mat& veto) {
  CV_Assert(veto.empty() || veto.size() == mask.size());
  cv::Mat out = mask.clone();
  fillSmallHolesInPlace(out, max_cells, veto);
  return out;
}

void fillSmallHolesInPlace(cv::Mat& mask, double max_cells, const cv::Mat& veto, cv::Point veto_offset) {
  CV_Assert(mask.type() == CV_8U);
  CV_Assert(veto.empty() || veto.type() == CV_8U || veto.type() == CV_16U || veto.type() == CV_32S);
  // Whether any cell x0..x1 of mask row y is a veto cell.
  const auto vetoed = [&](int y, int x0, int x1) {
    const int vy = y - veto_offset.y;
    if (veto.empty() || vy < 0 || vy >= veto.rows) return false;
    const int a = std::max(x0 - veto_offset.x, 0), b = std::min(x1 - veto_offset.x, veto.cols - 1);
    for (int x = a; x <= b; ++x)
      if (idAt(veto, vy, x)) return true;
    return false;
  };
  // The 4-connected components of zero cells from their runs (RunComponents: no image of component numbers, which
  // would take 4 bytes a cell of a segment or corridor region spanning most of a large map); a component touching
  // the border or a veto cell is no hole.
  const RunComponents zero(mask, false, 4);
  std::vector<char> blocked(zero.root.size(), 0);
  std::size_t i = 0;
  forEachRun(mask, false, [&](int y, int x0, int x1) {
    char& b = blocked[static_cast<std::size_t>(zero.root[i++])];
    if (b) return;
    b = y == 0 || y == mask.rows - 1 || x0 == 0 || x1 == mask.cols - 1 || vetoed(y, x0, x1);
  });
  // Filled run by run as they are found (a run is found before it is filled: the scan goes on after it).
  i = 0;
  forEachRun(mask, false, [&](int y, int x0, int x1) {
    const auto r = static_cast<std::size_t>(zero.root[i++]);
    if (!blocked[r] && zero.area[r] <= max_cells) std::fill(mask.ptr<unsigned char>(y) + x0, mask.ptr<unsigned char>(y) + x1 + 1, 255);
  });
}

namespace {
template <class T>
void growSeedsOf(cv::Mat& ids, const cv::Mat& allowed, int max_steps) {
  cv::Mat steps;
  if (max_steps >= 0) steps = cv::Mat(ids.size(), CV_32S, cv::Scalar(0));
  // Only seeds with a cell to take next to them are queued: cells are only ever taken, never given back, so a
  // seed with none now never takes one, and leaving it out changes neither the order nor the result.
  const auto open = [&](int y, int x) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int yy = y + dy, xx = x + dx;
        if (yy < 0 || xx < 0 || yy >= ids.rows || xx >= ids.cols) continue;
        if (allowed.at<unsigned char>(yy, xx) && !ids.at<T>(yy, xx)) return true;
      }
    return false;
  };
  std::deque<cv::Point> q;
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x)
      if (ids.at<T>(y, x) > 0 && open(y, x)) q.emplace_back(x, y);
  while (!q.empty()) {
    const cv::Point p = q.front();
    q.pop_front();
    const int st = max_steps >= 0 ? steps.at<int>(p) + 1 : 0;
    if (max_steps >= 0 && st > max_steps) continue;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int yy = p.y + dy, xx = p.x + dx;
        if (yy < 0 || xx < 0 || yy >= ids.rows || xx >= ids.cols) continue;
        if (!allowed.at<unsigned char>(yy, xx) || ids.at<T>(yy, xx)) continue;
        ids.at<T>(yy, xx) = ids.at<T>(p);
        if (max_steps >= 0) steps.at<int>(yy, xx) = st;
        q.emplace_back(xx, yy);
      }
  }
}
}  // namespace

void growSeeds(cv::Mat& ids, const cv::Mat& allowed, int max_steps) {
  CV_Assert((ids.type() == CV_32S || ids.type() == CV_16U) && allowed.type() == CV_8U && ids.size() == allowed.size());
  if (ids.type() == CV_16U) growSeedsOf<unsigned short>(ids, allowed, max_steps);
  else growSeedsOf<int>(ids, allowed, max_steps);
}

}  // namespace gridtopo::topology
