#pragma once
// Shared fixtures of the GUI-state tests: a temporary directory, a synthetic floor plan and a hand-made place
// model (fixed stumps on the narrowest-passage feature), so the topology plumbing is tested without training.
#include <filesystem>
#include <random>
#include <string>

#include <opencv2/imgproc.hpp>

#include "gridtopo/places/features.h"
#include "gridtopo/places/model.h"

namespace gridtopo::guitest {

/// Pixels of exactly the colour `c` (BGR).
inline int pixelsOf(const cv::Mat& img, const cv::Scalar& c) {
  cv::Mat mask;
  cv::inRange(img, c, c, mask);
  return cv::countNonZero(mask);
}

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() /
           ("gridtopo_gui_test_" + std::to_string(std::random_device{}()) + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

/// 200 x 120 cells at 0.05 m: two rooms (4 m x 3 m) above a 1.2 m wide corridor, joined to it by 0.8 m doors.
/// Free 255, walls 0, outside unknown 128.
inline cv::Mat floorPlan() {
  cv::Mat m(120, 200, CV_8U, cv::Scalar(128));
  auto free = [&](int x0, int y0, int x1, int y1) { cv::rectangle(m, {x0, y0}, {x1, y1}, cv::Scalar(255), cv::FILLED); };
  auto wall = [&](int x0, int y0, int x1, int y1) { cv::rectangle(m, {x0, y0}, {x1, y1}, cv::Scalar(0), 2); };
  // Room A: cols 10..90, rows 10..70; room B: cols 110..190, rows 10..70; corridor: cols 10..190, rows 80..104.
  wall(8, 8, 92, 72), wall(108, 8, 192, 72), wall(8, 78, 192, 106);
  free(10, 10, 90, 70), free(110, 10, 190, 70), free(10, 80, 190, 104);
  free(42, 71, 57, 79), free(142, 71, 157, 79);  // doors (16 cells = 0.8 m wide)
  return m;
}

/// A decision list "corridor vs rest" then "room vs doorway" on min_chord (narrowest passage through the
/// cell): < 0.95 m doorway, < 1.6 m corridor, else room.
inline places::PlacesModel handMadeModel() {
  places::PlacesModel m;
  m.scan.num_beams = 360;
  m.scan.max_range = 20.0;
  m.scan.lattice_spacing = 0.1;
  m.feature_names = places::featureNames(m.features);
  int f = -1;
  for (std::size_t i = 0; i < m.feature_names.size(); ++i)
    if (m.feature_names[i] == "min_chord") f = static_cast<int>(i);
  m.order = {1, 0, 2};
  // first: corridor (positive) when 0.95 < min_chord <= 1.6
  m.first.stumps = {{f, 1.6f, 1.0f, -1.5f}, {f, 0.95f, -2.0f, 0.0f}};
  // second: room (positive) vs doorway: room when min_chord > 0.95
  m.second.stumps = {{f, 0.95f, -1.5f, 1.5f}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) m.compatibility[a][b] = a == b ? 0.5 : -0.2;
  m.notes = "hand-made test model";
  return m;
}

}  // namespace gridtopo::guitest
