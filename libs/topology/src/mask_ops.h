#pragma once
// Mask operations shared by the segmentation rule S1, the blob vote and the corridor pieces (library-internal).
#include <opencv2/core.hpp>

#include <algorithm>
#include <vector>

namespace gridtopo::topology {

/// The 4- or 8-connected components of the cells of `mask` (CV_8U) that are non-zero (`nonzero`) or zero, found
/// from their runs row by row (union-find over the runs): no image of component numbers, only a few numbers per
/// run. Runs are numbered in row-major order (forEachRun gives them in that order).
struct RunComponents {
  std::vector<int> root;        ///< per run: the run that stands for its component
  std::vector<long long> area;  ///< per run that is a root: the component's cells
  RunComponents(const cv::Mat& mask, bool nonzero, int connectivity);
  /// The roots of the components of at least `min_cells` cells.
  std::size_t componentsOfAtLeast(double min_cells) const;
};

/// The value at (y, x) of an id image (region ids, segments, pieces: CV_16U or CV_32S; a CV_8U mask too) as an int.
inline int idAt(const cv::Mat& ids, int y, int x) {
  switch (ids.depth()) {
    case CV_8U: return ids.at<unsigned char>(y, x);
    case CV_16U: return ids.at<unsigned short>(y, x);
    default: return ids.at<int>(y, x);
  }
}

/// Writes `id` into cells x0..x1 of row y of an id image (CV_16U, where it must fit, or CV_32S).
inline void setIds(cv::Mat& ids, int y, int x0, int x1, int id) {
  if (ids.depth() == CV_16U)
    std::fill(ids.ptr<unsigned short>(y) + x0, ids.ptr<unsigned short>(y) + x1 + 1, static_cast<unsigned short>(id));
  else
    std::fill(ids.ptr<int>(y) + x0, ids.ptr<int>(y) + x1 + 1, id);
}

/// Calls f(y, x0, x1) for each run [x0, x1] of row y of the non-zero (`nonzero`) or zero cells of `mask`, in
/// row-major order (RunComponents' numbering).
template <class F>
void forEachRun(const cv::Mat& mask, bool nonzero, F&& f) {
  for (int y = 0; y < mask.rows; ++y) {
    const unsigned char* m = mask.ptr<unsigned char>(y);
    for (int x = 0; x < mask.cols;) {
      if ((m[x] != 0) != nonzero) {
        ++x;
        continue;
      }
      const int x0 = x;
      while (x < mask.cols && (m[x] != 0) == nonzero) ++x;
      f(y, x0, x - 1);
    }
  }
}

/// The roots of `comps` (the 8-connected components of the non-zero cells of `mask`) in the order of their first
/// 2 x 2 block, row-major over the blocks of `mask`: the order in which cv::connectedComponents (8-connected,
/// block-based) numbers them, without its image of component numbers.
std::vector<int> rootsInBlockOrder(const cv::Mat& mask, const RunComponents& comps);

/// Per run of `comps`' numbering, its component's number 1, 2, ... in rootsInBlockOrder's order (indexed by root;
/// other entries 0), and in `count` how many there are.
std::vector<int> numbersInBlockOrder(const cv::Mat& mask, const RunComponents& comps, int& count);

/// Copy of `mask` (CV_8U, 0 / 255) with its small holes set to 255: the 4-connected components of zero cells that
/// touch no image border, have at most `max_cells` cells and, when `veto` (CV_8U, same size) is given, hold no
/// cell where veto != 0.
cv::Mat fillSmallHoles(const cv::Mat& mask, double max_cells, const cv::Mat& veto = cv::Mat());
/// The same fill written into `mask` itself. `veto` may be CV_8U, CV_16U or CV_32S (a veto cell is non-zero) and
/// cover a part of the mask: the veto of mask cell (y, x) is veto(y - veto_offset.y, x - veto_offset.x), none
/// outside it.
void fillSmallHolesInPlace(cv::Mat& mask, double max_cells, const cv::Mat& veto = cv::Mat(),
                           cv::Point veto_offset = {});

/// Multi-source breadth-first growth, 8-connected: the cells of `ids` (CV_32S, or CV_16U) > 0 are the seeds (queued in
/// row-major order); each cell reached takes the id of the cell it was reached from. Only cells with
/// allowed != 0 (CV_8U, same size) and ids == 0 are entered; with `max_steps` >= 0, no cell farther than that many
/// steps from its seed.
void growSeeds(cv::Mat& ids, const cv::Mat& allowed, int max_steps = -1);

}  // namespace gridtopo::topology
