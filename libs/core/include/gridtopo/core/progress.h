#pragma once
// A terminal progress bar with rate and ETA, drawn on stderr only when stderr is a TTY (quiet in CI/pipes).
#include <chrono>
#include <cstddef>
#include <string>

namespace gridtopo {

class ProgressBar {
 public:
  /// `total` steps; `unit` names a step in the rate ("scans/s"). `enabled`: -1 = auto (TTY), 0 = off, 1 = on.
  ProgressBar(std::size_t total, std::string label, std::string unit = "it", int enabled = -1);
  ~ProgressBar();

  /// Sets the number of completed steps; redraws at most ~10 times per second.
  void update(std::size_t done, const std::string& note = "");
  /// Draws the final state and a newline.
  void finish();
  bool enabled() const { return enabled_; }

  /// The line that would be drawn (exposed for tests).
  std::string render(std::size_t done, double elapsed_s, const std::string& note) const;

 private:
  std::size_t total_;
  std::string label_, unit_;
  bool enabled_, finished_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::size_t last_done_ = 0;
};

/// "1:02:03" / "02:03" formatting of a duration in seconds.
std::string formatDuration(double seconds);

}  // namespace gridtopo
