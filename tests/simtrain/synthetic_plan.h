#pragma once
// A labelled plan for the simulation tests: a 16 m x 9 m building, a 2 m corridor along its south side and three
// 5 m x 6 m rooms north of it, each opening onto the corridor through a 1 m door; 0.05 m per pixel, walls 0.1 m.
#include <opencv2/core.hpp>

namespace gridtopo::simtrain::test {

struct LabelledPlan {
  cv::Mat grey, codes;  ///< 255 free / 0 wall; 77 room, 115 corridor, 179 doorway, 0 other
  double resolution = 0.05;
};

inline LabelledPlan threeRoomPlan() {
  LabelledPlan p;
  const int W = 330, H = 190;  // 16.5 m x 9.5 m with the outer walls
  p.grey = cv::Mat(H, W, CV_8U, cv::Scalar(0));
  p.codes = cv::Mat(H, W, CV_8U, cv::Scalar(0));
  // corridor: rows 145..184 (2 m), columns 5..324
  p.grey(cv::Rect(5, 145, 320, 40)).setTo(255);
  p.codes(cv::Rect(5, 145, 320, 40)).setTo(115);
  for (int k = 0; k < 3; ++k) {
    const int x0 = 5 + k * 108;  // rooms 104 px wide (5.2 m) with 4 px (0.2 m) walls between them
    p.grey(cv::Rect(x0, 5, 104, 138)).setTo(255);
    p.codes(cv::Rect(x0, 5, 104, 138)).setTo(77);
    // door: 20 px (1 m) through the 2-px wall between room and corridor
    p.grey(cv::Rect(x0 + 42, 143, 20, 2)).setTo(255);
    p.codes(cv::Rect(x0 + 42, 141, 20, 6)).setTo(179);
  }
  return p;
}

}  // namespace gridtopo::simtrain::test
