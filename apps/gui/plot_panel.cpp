#include "plot_panel.h"

#include <mrpt/3rdparty/mathplot/mathplot.h>

#include <algorithm>

namespace gridtopo::gui {

namespace {
mpWindow* makePlot(wxWindow* parent, const wxString& title, const wxString& ylabel, std::vector<mpFXYVector*> layers) {
  auto* w = new mpWindow(parent, wxID_ANY, wxDefaultPosition, wxSize(250, 150));
  w->SetMargins(20, 10, 30, 55);
  auto* x = new mpScaleX(wxT("step"), mpALIGN_BORDER_BOTTOM, true);
  auto* y = new mpScaleY(ylabel, mpALIGN_BORDER_LEFT, true);
  w->AddLayer(x);
  w->AddLayer(y);
  for (auto* l : layers) w->AddLayer(l);
  w->AddLayer(new mpText(title, 40, 2));
  w->EnableMousePanZoom(true);
  return w;
}
mpFXYVector* series(const wxString& name, const wxColour& c, bool continuous, int width = 1) {
  auto* v = new mpFXYVector(name);
  v->SetContinuity(continuous);
  v->SetPen(wxPen(c, width));
  v->SetDrawOutsideMargins(false);
  v->ShowName(false);
  return v;
}
}  // namespace

PlotPanel::PlotPanel(wxWindow* parent) : wxPanel(parent) {
  neff_ = series(wxT("Neff"), wxColour(0, 90, 200), true);
  resampled_ = series(wxT("resampled"), wxColour(220, 30, 30), false, 5);
  count_ = series(wxT("particles"), wxColour(110, 110, 110), true);
  time_ = series(wxT("ms"), wxColour(30, 140, 30), true);
  map_mem_ = series(wxT("maps"), wxColour(120, 60, 160), true);
  rss_ = series(wxT("RSS"), wxColour(200, 120, 0), true);
  neff_win_ = makePlot(this, wxT("Neff, particles (grey; red: resampling)"), wxT("Neff"),
                       {count_, neff_, resampled_});
  time_win_ = makePlot(this, wxT("time per step (ms)"), wxT("ms"), {time_});
  mem_win_ = makePlot(this, wxT("memory MB (orange RSS, violet maps)"), wxT("MB"), {rss_, map_mem_});
  auto* sizer = new wxBoxSizer(wxHORIZONTAL);
  sizer->Add(neff_win_, 1, wxEXPAND | wxALL, 2);
  sizer->Add(time_win_, 1, wxEXPAND | wxALL, 2);
  sizer->Add(mem_win_, 1, wxEXPAND | wxALL, 2);
  SetSizer(sizer);
}

void PlotPanel::clear() {
  for (auto* v : {neff_, resampled_, count_, time_, map_mem_, rss_}) v->Clear();
  rss_x_.clear();
  rss_y_.clear();
  last_version_ = 0;
  for (auto* w : {neff_win_, time_win_, mem_win_}) w->UpdateAll();
}

void PlotPanel::update(const session::SlamSnapshot& s) {
  if (s.version == last_version_) return;
  last_version_ = s.version;
  std::vector<double> x, neff, count, rx, ry, t, mem;
  double most = 1.0;
  for (const auto& st : s.stats) {
    x.push_back(static_cast<double>(st.step));
    neff.push_back(st.neff);
    count.push_back(st.particles);  // the adaptive particle set's count (KLD-sampling), else constant
    most = std::max(most, static_cast<double>(st.particles));
    t.push_back(st.time_s * 1000.0);
    mem.push_back(st.map_bytes / 1048576.0);
    if (st.resampled) rx.push_back(static_cast<double>(st.step)), ry.push_back(st.neff);
  }
  if (rss_x_.empty() || static_cast<double>(s.steps) > rss_x_.back()) {
    rss_x_.push_back(static_cast<double>(s.steps));
    rss_y_.push_back(s.rss_bytes / 1048576.0);
  }
  neff_->SetData(x, neff);
  count_->SetData(x, count);
  resampled_->SetData(rx, ry);
  time_->SetData(x, t);
  map_mem_->SetData(x, mem);
  rss_->SetData(rss_x_, rss_y_);
  if (x.size() >= 2) {
    neff_win_->Fit(0, x.back(), 0, most * 1.05);
    time_win_->Fit();
    mem_win_->Fit();
  }
}

}  // namespace gridtopo::gui
