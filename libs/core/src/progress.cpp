#include "gridtopo/core/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace gridtopo {

std::string formatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%02ld:%02ld", s / 60, s % 60);
  return buf;
}

ProgressBar::ProgressBar(std::size_t total, std::string label, std::string unit, int enabled)
    : total_(total),
      label_(std::move(label)),
      unit_(std::move(unit)),
      enabled_(enabled < 0 ? ::isatty(STDERR_FILENO) != 0 : enabled != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_ - std::chrono::seconds(1)) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && !finished_) std::fputc('\n', stderr);
}

std::string ProgressBar::render(std::size_t done, double elapsed, const std::string& note) const {
  const double frac = total_ ? std::min(1.0, static_cast<double>(done) / static_cast<double>(total_)) : 1.0;
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(frac * kWidth);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar += std::string(static_cast<std::size_t>(kWidth - filled), '.');
  const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
  const double eta = (rate > 0 && total_ >= done) ? static_cast<double>(total_ - done) / rate : NAN;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s [%s] %3.0f%% %zu/%zu %.1f %s/s elapsed %s ETA %s", label_.c_str(),
                bar.c_str(), frac * 100.0, done, total_, rate, unit_.c_str(), formatDuration(elapsed).c_str(),
                formatDuration(eta).c_str());
  std::string line(buf);
  if (!note.empty()) line += "  " + note;
  return line;
}

void ProgressBar::update(std::size_t done, const std::string& note) {
  last_done_ = done;
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(100) && done < total_) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r\033[K%s", render(done, elapsed, note).c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (finished_) return;
  if (enabled_) {
    last_draw_ = std::chrono::steady_clock::time_point{};
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "\r\033[K%s\n", render(last_done_, elapsed, "").c_str());
  }
  finished_ = true;
}

}  // namespace gridtopo
