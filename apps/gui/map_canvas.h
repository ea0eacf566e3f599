#pragma once
// The map view: blits the image session::Session::render() draws, and turns mouse input into pan (drag), zoom
// (wheel, around the cursor), selection (click) and label painting.
#include <wx/wx.h>

#include <functional>

#include "gridtopo/session/session.h"

namespace gridtopo::gui {

enum class PaintTool { None, Brush, Fill };

class MapCanvas : public wxPanel {
 public:
  MapCanvas(wxWindow* parent, session::Session& s);

  session::ViewTransform& view() { return view_; }
  session::Layers& layers() { return layers_; }
  session::ViewMode mode() const { return mode_; }
  void setMode(session::ViewMode m) { mode_ = m; Refresh(false); }
  void fit();
  /// Renders the current view to an image of the canvas size (what the window shows).
  cv::Mat renderImage();
  /// Screen position (client pixels) of a world point.
  wxPoint toClient(double x, double y) const;

  /// Keep the whole map in view while it grows (set by fit(), cleared by any pan or zoom of the user).
  bool auto_fit = true;
  PaintTool tool = PaintTool::None;
  unsigned char paint_code = 77;
  int brush_radius = 5;  ///< cells

  std::function<void(const std::string&)> on_hover;  ///< status text
  std::function<void()> on_select;                   ///< after a click selected something
  /// Frames drawn and time spent drawing them (for the frame-rate figure).
  long frames = 0;
  double render_seconds = 0.0;

 private:
  void onPaint(wxPaintEvent&);
  void onSize(wxSizeEvent&);
  void onMouse(wxMouseEvent&);
  void paintAt(const wxPoint& p, bool fill);

  session::Session& s_;
  session::ViewTransform view_;
  session::Layers layers_;
  session::ViewMode mode_ = session::ViewMode::Slam;
  cv::Mat screen_, rgb_;
  wxPoint drag_start_, last_;
  bool dragging_ = false, moved_ = false, painting_ = false;
  bool fitted_ = false;
};

}  // namespace gridtopo::gui
