#include "gridtopo/session/map_layer.h"

#include <cmath>

#include "gridtopo/io/map_io.h"

namespace gridtopo::session {

bool MapLayer::worldToCell(double x, double y, int& row, int& col) const {
  if (empty()) return false;
  const double fc = std::floor((x - origin_x) / resolution), fr = std::floor((y - origin_y) / resolution);
  if (fc < 0 || fr < 0 || fc >= cols() || fr >= rows()) return false;
  col = static_cast<int>(fc);
  row = rows() - 1 - static_cast<int>(fr);
  return true;
}

MapLayer mapLayerFromImage(const MapImage& map) {
  MapLayer m;
  m.grey = map.grey;
  m.resolution = map.resolution;
  m.origin_x = map.origin.x;
  m.origin_y = map.origin.y;
  m.source = map.source;
  m.kind = map.kind;
  return m;
}

MapLayer mapLayerFromGrid(const mrpt::maps::COccupancyGridMap2D& grid, const std::string& source, MapKind kind) {
  return mapLayerFromImage(io::mapImageOfGrid(grid, kind, source));
}

MapLayer mapLayerFromSlam(const slam::GridMap& map) {
  MapLayer m;
  m.resolution = map.resolution();
  m.source = "<slam>";
  m.kind = MapKind::ProbabilisticGrid;
  int x0, y0, x1, y1;
  map.cellBounds(x0, y0, x1, y1);
  if (x1 <= x0 || y1 <= y0) return m;
  const int w = x1 - x0, h = y1 - y0;
  m.grey = cv::Mat(h, w, CV_8U, cv::Scalar(128));
  m.origin_x = x0 * m.resolution;
  m.origin_y = y0 * m.resolution;
  // Log-odds -> grey through a table (log-odds are clamped by the filter to a small range).
  static const auto lut = [] {
    std::array<unsigned char, 1024> t{};
    for (int i = 0; i < 1024; ++i) {
      const double l = (i - 512) / 32.0;  // [-16, 16)
      t[static_cast<std::size_t>(i)] = static_cast<unsigned char>(std::lround(255.0 / (1.0 + std::exp(l))));
    }
    return t;
  }();
  constexpr int T = slam::GridMap::kTileSize;
  for (int ty = y0; ty < y1; ty += T)
    for (int tx = x0; tx < x1; tx += T) {
      if (!map.cell(tx, ty)) continue;  // tile not allocated (cell() of a tile's first cell)
      for (int cy = ty; cy < std::min(ty + T, y1); ++cy) {
        unsigned char* row = m.grey.ptr<unsigned char>(y1 - 1 - cy);
        for (int cx = tx; cx < std::min(tx + T, x1); ++cx) {
          const auto c = map.cell(cx, cy);
          if (!c || c->log_odds == 0.0f) continue;
          const int i = std::clamp(static_cast<int>(std::lround(c->log_odds * 32.0f)) + 512, 0, 1023);
          row[cx - x0] = lut[static_cast<std::size_t>(i)];
        }
      }
    }
  return m;
}

MapLayer tiledMap(const MapLayer& src, int cols, int rows) {
  MapLayer m = src;
  m.grey = cv::Mat(rows, cols, CV_8U);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) m.grey.at<unsigned char>(r, c) = src.grey.at<unsigned char>(r % src.rows(), c % src.cols());
  m.source = src.source + " (tiled " + std::to_string(cols) + "x" + std::to_string(rows) + ")";
  return m;
}

mrpt::maps::COccupancyGridMap2D gridFromLayer(const MapLayer& layer) {
  const double r = layer.resolution;
  mrpt::maps::COccupancyGridMap2D g(static_cast<float>(layer.origin_x),
                                    static_cast<float>(layer.origin_x + layer.cols() * r),
                                    static_cast<float>(layer.origin_y),
                                    static_cast<float>(layer.origin_y + layer.rows() * r), static_cast<float>(r));
  const int w = std::min<int>(layer.cols(), static_cast<int>(g.getSizeX()));
  const int h = std::min<int>(layer.rows(), static_cast<int>(g.getSizeY()));
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col)
      g.setCell(col, h - 1 - row, static_cast<float>(layer.grey.at<unsigned char>(row, col) / 255.0));
  return g;
}

}  // namespace gridtopo::session
