#pragma once
// Painting place labels onto a map for training (gridtopo-train): brush and flood fill in the training code
// (room 77, corridor 115, doorway 179, other 0), undo, and saving as a pixel-aligned 8-bit PNG.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace gridtopo::session {

class LabelCanvas {
 public:
  LabelCanvas() = default;
  /// Starts a blank canvas (all 0) over an occupancy image (CV_8U grey; free = grey >= free_threshold).
  void reset(const cv::Mat& grey, int free_threshold = 250);
  /// Loads an existing labelled image (8-bit, same size as the map). Codes other than 0/77/115/179 throw
  /// gridtopo::InputError naming the file and the first bad pixel; the canvas is unchanged on error.
  void load(const std::string& path);
  /// Writes the codes as an 8-bit grey PNG, atomically.
  void save(const std::string& path) const;

  bool empty() const { return codes_.empty(); }
  const cv::Mat& codes() const { return codes_; }
  unsigned char code(int row, int col) const { return codes_.at<unsigned char>(row, col); }

  /// Paints a disc of `radius` cells centred on (row, col) with `code`. Only free cells are painted unless
  /// `free_only` is false. Dabs between beginStroke() and endStroke() undo as one step (a dab outside a stroke
  /// is its own step). Returns the number of cells whose code changed.
  int brush(int row, int col, int radius, unsigned char code, bool free_only = true);
  /// Fills the 4-connected free cells that share the seed's current code with `code`.
  int floodFill(int row, int col, unsigned char code);
  void beginStroke();
  void endStroke();
  bool canUndo() const { return !undo_.empty(); }
  /// Reverts the last stroke / fill. Returns false when there is nothing to undo.
  bool undo();
  std::size_t undoDepth() const { return undo_.size(); }
  /// Cells per code {0, 77, 115, 179} among free cells.
  std::vector<long> histogram() const;

  static bool isTrainingCode(unsigned char c) { return c == 0 || c == 77 || c == 115 || c == 179; }

 private:
  struct Patch {
    cv::Rect rect;
    cv::Mat before;
  };
  using Step = std::vector<Patch>;
  void pushPatch(const cv::Rect& r);

  cv::Mat codes_, free_;  // CV_8U; free_ = 1 on free cells
  std::vector<Step> undo_;
  bool in_stroke_ = false;
  std::size_t max_undo_ = 200;
};

}  // namespace gridtopo::session
