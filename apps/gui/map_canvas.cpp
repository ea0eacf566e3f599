#include "map_canvas.h"

#include <wx/dcbuffer.h>

#include <chrono>
#include <opencv2/imgproc.hpp>

namespace gridtopo::gui {

MapCanvas::MapCanvas(wxWindow* parent, session::Session& s)
    : wxPanel(parent, wxID_ANY, wxDefaultPosition, wxDefaultSize, wxFULL_REPAINT_ON_RESIZE | wxWANTS_CHARS), s_(s) {
  SetBackgroundStyle(wxBG_STYLE_PAINT);
  Bind(wxEVT_PAINT, &MapCanvas::onPaint, this);
  Bind(wxEVT_SIZE, &MapCanvas::onSize, this);
  for (auto ev : {wxEVT_LEFT_DOWN, wxEVT_LEFT_UP, wxEVT_MOTION, wxEVT_MOUSEWHEEL, wxEVT_MIDDLE_DOWN, wxEVT_MIDDLE_UP,
                  wxEVT_RIGHT_DOWN, wxEVT_RIGHT_UP, wxEVT_LEAVE_WINDOW})
    Bind(ev, &MapCanvas::onMouse, this);
}

void MapCanvas::fit() {
  double x0, y0, x1, y1;
  const wxSize sz = GetClientSize();
  if (sz.x < 10 || sz.y < 10) return;
  if (s_.bounds(mode_, x0, y0, x1, y1)) {
    view_.fit(x0, y0, x1, y1, sz.x, sz.y);
    fitted_ = true;
  }
  auto_fit = true;
  Refresh(false);
}

wxPoint MapCanvas::toClient(double x, double y) const {
  const cv::Point2d p = view_.toScreen(x, y);
  return {static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))};
}

cv::Mat MapCanvas::renderImage() {
  const wxSize sz = GetClientSize();
  if (screen_.cols != sz.x || screen_.rows != sz.y) screen_.create(std::max(1, sz.y), std::max(1, sz.x), CV_8UC3);
  if (!fitted_ || (auto_fit && mode_ == session::ViewMode::Slam && s_.runner())) {
    double x0, y0, x1, y1;
    if (s_.bounds(mode_, x0, y0, x1, y1)) view_.fit(x0, y0, x1, y1, sz.x, sz.y), fitted_ = true;
  }
  s_.render(screen_, mode_, view_, layers_);
  return screen_;
}

void MapCanvas::onPaint(wxPaintEvent&) {
  wxAutoBufferedPaintDC dc(this);
  const auto t0 = std::chrono::steady_clock::now();
  renderImage();
  cv::cvtColor(screen_, rgb_, cv::COLOR_BGR2RGB);
  wxImage img(rgb_.cols, rgb_.rows, rgb_.data, true);  // shares rgb_'s pixels
  dc.DrawBitmap(wxBitmap(img), 0, 0);
  render_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++frames;
}

void MapCanvas::onSize(wxSizeEvent& e) {
  Refresh(false);
  e.Skip();
}

void MapCanvas::paintAt(const wxPoint& p, bool fill) {
  const cv::Point2d w = view_.toWorld(p.x, p.y);
  int row, col;
  if (!s_.map().worldToCell(w.x, w.y, row, col) || s_.canvas().empty()) return;
  if (fill) s_.canvas().floodFill(row, col, paint_code);
  else s_.canvas().brush(row, col, brush_radius, paint_code);
  s_.canvasChanged();
  Refresh(false);
}

void MapCanvas::onMouse(wxMouseEvent& e) {
  const wxPoint p = e.GetPosition();
  if (e.GetEventType() == wxEVT_MOUSEWHEEL) {
    const double steps = static_cast<double>(e.GetWheelRotation()) / std::max(1, e.GetWheelDelta());
    view_.zoomAt(p.x, p.y, std::pow(1.25, steps));
    auto_fit = false;
    Refresh(false);
    return;
  }
  const bool painting_mode = mode_ == session::ViewMode::Labels && tool != PaintTool::None && !s_.canvas().empty();
  if (e.LeftDown() || e.MiddleDown() || e.RightDown()) {
    SetFocus();
    drag_start_ = last_ = p;
    moved_ = false;
    if (e.LeftDown() && painting_mode) {
      painting_ = true;
      if (tool == PaintTool::Fill) {
        paintAt(p, true);
      } else {
        s_.canvas().beginStroke();
        paintAt(p, false);
      }
    } else {
      dragging_ = true;
    }
    if (!HasCapture()) CaptureMouse();
    return;
  }
  if (e.LeftUp() || e.MiddleUp() || e.RightUp()) {
    if (HasCapture()) ReleaseMouse();
    if (painting_) {
      painting_ = false;
      s_.canvas().endStroke();
    } else if (dragging_ && !moved_ && e.LeftUp()) {
      const cv::Point2d w = view_.toWorld(p.x, p.y);
      s_.select(mode_, w.x, w.y, 8.0 / view_.ppm);  // 8 pixels of tolerance
      if (on_select) on_select();
      Refresh(false);
    }
    dragging_ = false;
    return;
  }
  if (e.Dragging()) {
    if (std::abs(p.x - drag_start_.x) + std::abs(p.y - drag_start_.y) > 3) moved_ = true;
    if (painting_ && tool == PaintTool::Brush) {
      paintAt(p, false);
    } else if (dragging_ && moved_) {
      view_.pan(p.x - last_.x, p.y - last_.y);
      auto_fit = false;
      Refresh(false);
    }
    last_ = p;
  }
  if (e.Moving() || e.Dragging()) {
    const cv::Point2d w = view_.toWorld(p.x, p.y);
    if (on_hover) on_hover(s_.hoverText(mode_, w.x, w.y));
  }
}

}  // namespace gridtopo::gui
