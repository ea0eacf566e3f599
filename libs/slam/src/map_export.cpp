#include "gridtopo/slam/map_export.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace gridtopo::slam {

mrpt::maps::COccupancyGridMap2D toOccupancyGrid(const GridMap& map) {
  int x0, y0, x1, y1;
  map.cellBounds(x0, y0, x1, y1);
  // Trim to the cells that carry information.
  int ax = x1, ay = y1, bx = x0 - 1, by = y0 - 1;
  for (int cy = y0; cy < y1; ++cy)
    for (int cx = x0; cx < x1; ++cx) {
      const auto c = map.cell(cx, cy);
      if (c && c->log_odds != 0.0f) {
        ax = std::min(ax, cx);
        ay = std::min(ay, cy);
        bx = std::max(bx, cx);
        by = std::max(by, cy);
      }
    }
  if (bx < ax) {
    ax = ay = 0;
    bx = by = 1;
  }
  const double r = map.resolution();
  mrpt::maps::COccupancyGridMap2D g(static_cast<float>((ax - 1) * r), static_cast<float>((bx + 2) * r),
                                    static_cast<float>((ay - 1) * r), static_cast<float>((by + 2) * r),
                                    static_cast<float>(r));
  g.fill(0.5f);
  for (unsigned iy = 0; iy < g.getSizeY(); ++iy)
    for (unsigned ix = 0; ix < g.getSizeX(); ++ix) {
      const int cx = map.cellIndex(g.idx2x(ix)), cy = map.cellIndex(g.idx2y(iy));
      const auto c = map.cell(cx, cy);
      if (!c || c->log_odds == 0.0f) continue;
      // MRPT stores the probability of being free.
      const double p_occ = 1.0 / (1.0 + std::exp(-static_cast<double>(c->log_odds)));
      g.setCell(static_cast<int>(ix), static_cast<int>(iy), static_cast<float>(1.0 - p_occ));
    }
  return g;
}

cv::Mat renderMap(const mrpt::maps::COccupancyGridMap2D& grid, const std::vector<TimedPose>& trajectory,
                  const std::vector<ClosureLine>& closures) {
  const int w = static_cast<int>(grid.getSizeX()), h = static_cast<int>(grid.getSizeY());
  cv::Mat img(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto v = static_cast<unsigned char>(std::lround(255.0 * grid.getCell(x, h - 1 - y)));
      img.at<cv::Vec3b>(y, x) = {v, v, v};
    }
  auto toPixel = [&](const mrpt::math::TPose2D& p) {
    return cv::Point(grid.x2idx(p.x), h - 1 - grid.y2idx(p.y));
  };
  for (std::size_t i = 1; i < trajectory.size(); ++i)
    cv::line(img, toPixel(trajectory[i - 1].pose), toPixel(trajectory[i].pose), cv::Scalar(0, 0, 220), 1,
             cv::LINE_AA);
  for (const bool global : {false, true})
    for (const ClosureLine& c : closures)
      if (c.global == global) {
        const cv::Point a = toPixel({c.from.x, c.from.y, c.from.theta}), b = toPixel({c.to.x, c.to.y, c.to.theta});
        cv::line(img, a, b, global ? cv::Scalar(0, 140, 255) : cv::Scalar(200, 0, 200), global ? 3 : 1, cv::LINE_AA);
        // A global closure joins two poses at one place (the place and the query's centre): a ring marks it.
        if (global) cv::circle(img, b, 8, cv::Scalar(0, 140, 255), 2, cv::LINE_AA);
      }
  if (!trajectory.empty()) cv::circle(img, toPixel(trajectory.front().pose), 4, cv::Scalar(0, 170, 0), -1);
  return img;
}

}  // namespace gridtopo::slam
