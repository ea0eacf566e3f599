#include "gridtopo/session/render.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

namespace gridtopo::session {

void ViewTransform::zoomAt(double sx, double sy, double factor) {
  const cv::Point2d w = toWorld(sx, sy);
  ppm = std::clamp(ppm * factor, 1e-3, 1e5);
  x0 = w.x - sx / ppm;
  y0 = w.y + sy / ppm;
}

void ViewTransform::fit(double xmin, double ymin, double xmax, double ymax, int w, int h, double margin) {
  const double dx = std::max(xmax - xmin, 1e-6), dy = std::max(ymax - ymin, 1e-6);
  ppm = std::min(w / (dx * (1 + 2 * margin)), h / (dy * (1 + 2 * margin)));
  if (!(ppm > 0)) ppm = 1;
  x0 = 0.5 * (xmin + xmax) - 0.5 * w / ppm;
  y0 = 0.5 * (ymin + ymax) + 0.5 * h / ppm;
}

void MapRaster::set(const cv::Mat& bgr, const MapLayer& geometry) {
  geo_ = geometry;
  geo_.grey = cv::Mat();
  levels_.clear();
  if (bgr.empty()) return;
  levels_.push_back(bgr);
  while (levels_.back().cols > 64 && levels_.back().rows > 64 && levels_.size() < 12) {
    cv::Mat half;
    cv::resize(levels_.back(), half, cv::Size((levels_.back().cols + 1) / 2, (levels_.back().rows + 1) / 2), 0, 0,
               cv::INTER_AREA);
    levels_.push_back(half);
  }
}

void MapRaster::draw(cv::Mat& screen, const ViewTransform& v) const {
  if (levels_.empty()) return;
  // Screen pixels per map cell; pick the mip level with about one texel per pixel or more.
  const double spc = geo_.resolution * v.ppm;
  std::size_t k = 0;
  while (k + 1 < levels_.size() && spc * std::pow(2.0, static_cast<double>(k + 1)) <= 1.0) ++k;
  const cv::Mat& src = levels_[k];
  const double sx = static_cast<double>(levels_[0].cols) / src.cols, sy = static_cast<double>(levels_[0].rows) / src.rows;
  // screen = A · texel: texel (c, r) of level k is cell (c·sx, r·sy); cell (col,row) top-left corner in world =
  // (origin_x + col·res, origin_y + (rows - row)·res).
  const double a = spc * sx, d = spc * sy;
  const double tx = (geo_.origin_x - v.x0) * v.ppm;
  const double ty = (v.y0 - (geo_.origin_y + levels_[0].rows * geo_.resolution)) * v.ppm;
  // Only the screen rectangle the map covers is touched.
  const double left = std::max(0.0, std::floor(tx)), top = std::max(0.0, std::floor(ty));
  const double right = std::min<double>(screen.cols, std::ceil(tx + a * src.cols));
  const double bottom = std::min<double>(screen.rows, std::ceil(ty + d * src.rows));
  if (right <= left || bottom <= top) return;
  const cv::Rect roi(static_cast<int>(left), static_cast<int>(top), static_cast<int>(right - left),
                     static_cast<int>(bottom - top));
  cv::Mat dst = screen(roi);
  // Inverse map: texel = ((screen - t) / a); sample at pixel centres.
  // Pixel centres: screen x + 0.5 <-> texel c + 0.5 (warpAffine rounds to the nearest texel).
  cv::Mat M = (cv::Mat_<double>(2, 3) << a, 0, tx + 0.5 * a - 0.5 - roi.x, 0, d, ty + 0.5 * d - 0.5 - roi.y);
  cv::warpAffine(src, dst, M, dst.size(), cv::INTER_NEAREST, cv::BORDER_TRANSPARENT);
}

cv::Mat greyToBgr(const cv::Mat& grey) {
  cv::Mat out;
  cv::cvtColor(grey, out, cv::COLOR_GRAY2BGR);
  return out;
}

cv::Scalar labelColour(int label) {
  switch (label) {
    case 0: return {220, 120, 40};   // room: blue
    case 1: return {60, 190, 60};    // corridor: green
    case 2: return {40, 40, 230};    // doorway: red
    default: return {128, 128, 128};
  }
}

cv::Mat labelOverlay(const cv::Mat& grey, const cv::Mat& labels, const cv::Mat& confidence) {
  cv::Mat out = greyToBgr(grey);
  for (int r = 0; r < grey.rows; ++r) {
    const unsigned char* l = labels.ptr<unsigned char>(r);
    const float* cf = confidence.empty() ? nullptr : confidence.ptr<float>(r);
    cv::Vec3b* o = out.ptr<cv::Vec3b>(r);
    for (int c = 0; c < grey.cols; ++c) {
      if (l[c] > 2) continue;
      const double alpha = cf ? 0.25 + 0.5 * std::clamp(static_cast<double>(cf[c]), 0.0, 1.0) : 0.6;
      const cv::Scalar col = labelColour(l[c]);
      for (int k = 0; k < 3; ++k)
        o[c][k] = static_cast<unsigned char>(std::lround((1 - alpha) * o[c][k] + alpha * col[k]));
    }
  }
  return out;
}

cv::Mat codesOverlay(const cv::Mat& grey, const cv::Mat& codes) {
  cv::Mat labels(codes.size(), CV_8U, cv::Scalar(255));
  for (int r = 0; r < codes.rows; ++r)
    for (int c = 0; c < codes.cols; ++c) {
      const unsigned char v = codes.at<unsigned char>(r, c);
      labels.at<unsigned char>(r, c) = v == 77 ? 0 : v == 115 ? 1 : v == 179 ? 2 : 255;
    }
  return labelOverlay(grey, labels);
}

void drawScaleBar(cv::Mat& screen, const ViewTransform& v) {
  const double target_m = screen.cols / 6.0 / v.ppm;
  const double p = std::pow(10.0, std::floor(std::log10(target_m)));
  double len = p;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p <= target_m) len = m * p;
  const int px = static_cast<int>(std::lround(len * v.ppm));
  const cv::Point a(12, screen.rows - 14), b(12 + px, screen.rows - 14);
  cv::rectangle(screen, cv::Rect(6, screen.rows - 34, px + 12 + 60, 28), cv::Scalar(255, 255, 255), cv::FILLED);
  cv::line(screen, a, b, cv::Scalar(0, 0, 0), 3);
  cv::line(screen, a + cv::Point(0, -5), a + cv::Point(0, 5), cv::Scalar(0, 0, 0), 2);
  cv::line(screen, b + cv::Point(0, -5), b + cv::Point(0, 5), cv::Scalar(0, 0, 0), 2);
  char text[32];
  if (len >= 1) std::snprintf(text, sizeof text, "%g m", len);
  else std::snprintf(text, sizeof text, "%g cm", len * 100);
  cv::putText(screen, text, b + cv::Point(6, 5), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

void drawPath(cv::Mat& screen, const ViewTransform& v, const std::vector<cv::Point2d>& pts, const cv::Scalar& c,
              int thickness) {
  if (pts.size() < 2) return;
  std::vector<cv::Point> s;
  s.reserve(pts.size());
  for (const auto& p : pts) {
    const cv::Point2d q = v.toScreen(p.x, p.y);
    const cv::Point qi(static_cast<int>(std::lround(std::clamp(q.x, -1e6, 1e6))),
                       static_cast<int>(std::lround(std::clamp(q.y, -1e6, 1e6))));
    if (s.empty() || qi != s.back()) s.push_back(qi);  // drop repeated pixels: long paths stay cheap
  }
  cv::polylines(screen, s, false, c, thickness, cv::LINE_AA);
}

void drawPose(cv::Mat& screen, const ViewTransform& v, double x, double y, double theta, const cv::Scalar& c, int r) {
  const cv::Point2d q = v.toScreen(x, y);
  if (q.x < -20 || q.y < -20 || q.x > screen.cols + 20 || q.y > screen.rows + 20) return;
  const cv::Point p(static_cast<int>(std::lround(q.x)), static_cast<int>(std::lround(q.y)));
  cv::circle(screen, p, r, c, cv::FILLED, cv::LINE_AA);
  const cv::Point h(static_cast<int>(std::lround(q.x + (r + 4) * std::cos(theta))),
                    static_cast<int>(std::lround(q.y - (r + 4) * std::sin(theta))));
  cv::line(screen, p, h, c, 1, cv::LINE_AA);
}

void drawClosure(cv::Mat& screen, const ViewTransform& v, const cv::Point2d& a, const cv::Point2d& b,
                 bool rejected, bool global) {
  auto pixel = [](const cv::Point2d& q) {  // clamped: a far point must not overflow int
    return cv::Point(static_cast<int>(std::lround(std::clamp(q.x, -1e6, 1e6))),
                     static_cast<int>(std::lround(std::clamp(q.y, -1e6, 1e6))));
  };
  const cv::Point pa = pixel(v.toScreen(a.x, a.y)), pb = pixel(v.toScreen(b.x, b.y));
  const cv::Scalar& c = rejected ? kRejectedClosureColour : global ? kGlobalClosureColour : kClosureColour;
  // Clipped to the screen first, so that a dashed line zoomed far in costs the screen's length, not the line's.
  cv::Point p = pa, q = pb;
  if (cv::clipLine(cv::Rect(-4, -4, screen.cols + 8, screen.rows + 8), p, q)) {
    if (!rejected) {
      cv::line(screen, p, q, c, 2, cv::LINE_8);
    } else {
      const double len = std::hypot(q.x - p.x, q.y - p.y);
      constexpr double kDash = 6.0, kGap = 4.0;
      for (double t = 0; t < len; t += kDash + kGap) {
        const double t1 = std::min(len, t + kDash);
        const cv::Point d0(static_cast<int>(std::lround(p.x + (q.x - p.x) * t / len)),
                           static_cast<int>(std::lround(p.y + (q.y - p.y) * t / len)));
        const cv::Point d1(static_cast<int>(std::lround(p.x + (q.x - p.x) * t1 / len)),
                           static_cast<int>(std::lround(p.y + (q.y - p.y) * t1 / len)));
        cv::line(screen, d0, d1, c, 2, cv::LINE_8);
      }
    }
  }
  for (const cv::Point& e : {pa, pb})
    if (e.x > -10 && e.y > -10 && e.x < screen.cols + 10 && e.y < screen.rows + 10)
      cv::circle(screen, e, 3, c, cv::FILLED, cv::LINE_8);
}

}  // namespace gridtopo::session
