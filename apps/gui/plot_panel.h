#pragma once
// Neff over time with resampling events, time per step and memory: MRPT's bundled wxMathPlot (mpWindow).
#include <wx/wx.h>

#include "gridtopo/session/slam_runner.h"

class mpWindow;
class mpFXYVector;

namespace gridtopo::gui {

class PlotPanel : public wxPanel {
 public:
  explicit PlotPanel(wxWindow* parent);
  void update(const session::SlamSnapshot& s);
  void clear();

 private:
  mpWindow *neff_win_, *time_win_, *mem_win_;
  mpFXYVector *neff_, *resampled_, *count_, *time_, *map_mem_, *rss_;
  std::vector<double> rss_x_, rss_y_;
  std::uint64_t last_version_ = 0;
};

}  // namespace gridtopo::gui
