#pragma once
// The three place classes of Mozos et al. and their pixel codes in the labelled maps of the
// room-segmentation benchmark (room 77, corridor 115, doorway 179, other 0).
#include <array>
#include <string>

namespace gridtopo::places {

enum class PlaceLabel : int { Room = 0, Corridor = 1, Doorway = 2 };
constexpr int kNumLabels = 3;
constexpr unsigned char kNoLabelCode = 0;

constexpr std::array<unsigned char, kNumLabels> kLabelCodes{77, 115, 179};

inline unsigned char labelCode(int label) { return kLabelCodes[static_cast<std::size_t>(label)]; }
/// -1 for a code that is not one of the three place classes.
inline int labelFromCode(unsigned char code) {
  for (int l = 0; l < kNumLabels; ++l)
    if (kLabelCodes[static_cast<std::size_t>(l)] == code) return l;
  return -1;
}
inline std::string labelName(int label) {
  static const char* names[] = {"room", "corridor", "doorway"};
  return label >= 0 && label < kNumLabels ? names[label] : "none";
}

}  // namespace gridtopo::places
