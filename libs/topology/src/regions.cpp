#include "gridtopo/topology/regions.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <vector>

#include "gridtopo/places/place_label.h"

namespace gridtopo::topology {

RegionMap extractRegions(const cv::Mat& labels, double resolution) {
  // One pass over the image with union-find (the four neighbours already visited: west, north-west, north,
  // north-east), then one pass that numbers the components and gathers their statistics. Components are numbered
  // by label, and within a label in the order of the first 2 x 2 block (row-major over blocks) that holds one of
  // their cells: the numbering of one cv::connectedComponentsWithStats per label (8-connected; its block-based
  // labelling creates labels in that order), which this replaced (two image scans instead of six, no mask images).
  CV_Assert(labels.type() == CV_8U);
  const int rows = labels.rows, cols = labels.cols;
  RegionMap rm;
  rm.ids = cv::Mat(labels.size(), CV_32S, cv::Scalar(0));
  std::vector<int> parent{0};               // provisional label -> parent (a root is its own parent; 0 unused)
  std::vector<unsigned char> label_of{255};  // provisional label -> place label
  std::vector<int> first_block{0};           // provisional label -> its first 2 x 2 block (row-major index)
  const int block_cols = (cols + 1) / 2;
  const auto find = [&](int a) {
    while (parent[static_cast<std::size_t>(a)] != a) {
      const int up = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
      parent[static_cast<std::size_t>(a)] = up;
      a = up;
    }
    return a;
  };
  // The smaller root wins: a component's root is the provisional label of its first cell in row-major order.
  const auto unite = [&](int a, int b) {
    a = find(a), b = find(b);
    if (a < b) parent[static_cast<std::size_t>(b)] = a;
    else if (b < a) parent[static_cast<std::size_t>(a)] = b;
    return std::min(a, b);
  };
  for (int y = 0; y < rows; ++y) {
    const unsigned char* l = labels.ptr<unsigned char>(y);
    const unsigned char* lu = y > 0 ? labels.ptr<unsigned char>(y - 1) : nullptr;
    int* id = rm.ids.ptr<int>(y);
    const int* idu = y > 0 ? rm.ids.ptr<int>(y - 1) : nullptr;
    const int block_row = (y / 2) * block_cols;
    for (int x = 0; x < cols; ++x) {
      const unsigned char v = l[x];
      if (v >= places::kNumLabels) continue;
      int c = 0;
      if (x > 0 && l[x - 1] == v) c = id[x - 1];
      if (lu) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx;
          if (xx < 0 || xx >= cols || lu[xx] != v) continue;
          c = c ? (c == idu[xx] ? c : unite(c, idu[xx])) : idu[xx];
        }
      }
      if (!c) {
        c = static_cast<int>(parent.size());
        parent.push_back(c);
        label_of.push_back(v);
        first_block.push_back(block_row + x / 2);
      }
      id[x] = c;
      int& fb = first_block[static_cast<std::size_t>(c)];
      fb = std::min(fb, block_row + x / 2);
    }
  }
  // Final numbers: per label, the components in the order of their first block.
  const std::size_t np = parent.size();
  std::vector<int> local(np, 0), final_id(np, 0);  // number within its label; the region id
  for (std::size_t p = 1; p < np; ++p) {
    const auto r = static_cast<std::size_t>(find(static_cast<int>(p)));
    first_block[r] = std::min(first_block[r], first_block[p]);
  }
  std::vector<std::pair<int, int>> order[places::kNumLabels];  // (first block, root)
  for (std::size_t p = 1; p < np; ++p)
    if (static_cast<std::size_t>(find(static_cast<int>(p))) == p)
      order[label_of[p]].emplace_back(first_block[p], static_cast<int>(p));
  int count[places::kNumLabels] = {0, 0, 0};
  for (int l = 0; l < places::kNumLabels; ++l) {
    std::sort(order[l].begin(), order[l].end());
    for (const auto& [block, root] : order[l]) local[static_cast<std::size_t>(root)] = ++count[l];
  }
  const int base[places::kNumLabels] = {0, count[0], count[0] + count[1]};
  for (std::size_t p = 1; p < np; ++p) {
    const auto r = static_cast<std::size_t>(find(static_cast<int>(p)));
    final_id[p] = base[label_of[r]] + local[r];
  }
  const int n = count[0] + count[1] + count[2];
  std::vector<long long> cells(static_cast<std::size_t>(n) + 1, 0), sx(cells), sy(cells);
  std::vector<int> x0(static_cast<std::size_t>(n) + 1, cols), y0(x0.size(), rows), x1(x0.size(), -1), y1(x0.size(), -1);
  for (int y = 0; y < rows; ++y) {
    int* id = rm.ids.ptr<int>(y);
    for (int x = 0; x < cols; ++x) {
      if (!id[x]) continue;
      const int f = final_id[static_cast<std::size_t>(id[x])];
      id[x] = f;
      const auto u = static_cast<std::size_t>(f);
      ++cells[u], sx[u] += x, sy[u] += y;
      x0[u] = std::min(x0[u], x), x1[u] = std::max(x1[u], x), y0[u] = std::min(y0[u], y), y1[u] = std::max(y1[u], y);
    }
  }
  rm.regions.resize(static_cast<std::size_t>(n));
  for (int i = 1; i <= n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    Region& r = rm.regions[u - 1];
    r.id = i;
    r.label = i <= base[1] ? 0 : i <= base[2] ? 1 : 2;
    r.cells = static_cast<int>(cells[u]);
    r.area_m2 = r.cells * resolution * resolution;
    r.centroid = cv::Point2d(static_cast<double>(sx[u]) / r.cells, static_cast<double>(sy[u]) / r.cells);
    r.bbox = cv::Rect(x0[u], y0[u], x1[u] - x0[u] + 1, y1[u] - y0[u] + 1);
  }
  return rm;
}

namespace {
template <class T>
std::map<std::pair<int, int>, int> adjacencyOf(const cv::Mat& ids) {
  std::map<std::pair<int, int>, int> adj;
  static const int d[4][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};  // half of the 8-neighbourhood
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x) {
      const int a = ids.at<T>(y, x);
      if (a <= 0) continue;
      for (const auto& o : d) {
        const int yy = y + o[0], xx = x + o[1];
        if (yy < 0 || xx < 0 || yy >= ids.rows || xx >= ids.cols) continue;
        const int b = ids.at<T>(yy, xx);
        if (b <= 0 || b == a) continue;
        adj[{std::min(a, b), std::max(a, b)}]++;
      }
    }
  return adj;
}
}  // namespace

std::map<std::pair<int, int>, int> regionAdjacency(const cv::Mat& ids) {
  CV_Assert(ids.type() == CV_32S || ids.type() == CV_16U);
  return ids.type() == CV_16U ? adjacencyOf<unsigned short>(ids) : adjacencyOf<int>(ids);
}

}  // namespace gridtopo::topology
