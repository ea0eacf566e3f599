// Aligning a labelled reference floor plan to a map of the same building in another frame, and scoring against it.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "gridtopo/core/error.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/eval/evaluation.h"
#include "gridtopo/topology/pipeline.h"
#include "gridtopo/eval/reference_alignment.h"

using namespace gridtopo;
using namespace gridtopo::topology;
using namespace gridtopo::eval;

namespace {
const std::string kPlaces = std::string(GRIDTOPO_DATA_DIR) + "/places";

// A known map frame: lab_intel mirrored top to bottom, turned by 90°, scaled by 0.86 and shifted (our SLAM map of
// Intel relates to lab_intel by such a transform). Returns reference pixel -> map pixel.
cv::Matx23d knownTransform(cv::Size ref) {
  const double s = 0.86;
  // mirror y, then rotate by 90° (x' = -y, y' = x), then scale and shift.
  const cv::Matx22d A = s * cv::Matx22d(0, 1, 1, 0);
  return cv::Matx23d(A(0, 0), A(0, 1), 40, A(1, 0), A(1, 1), 25 + 0 * ref.width);
}
cv::Mat toMap(const cv::Mat& ref, const cv::Matx23d& T, cv::Size size) {
  cv::Mat out, src = ref;
  if (ref.type() == CV_32S) ref.convertTo(src, CV_32F);
  cv::warpAffine(src, out, cv::Mat(T), size, cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar(0));
  if (ref.type() == CV_32S) out.convertTo(out, CV_32S);
  return out;
}
}  // namespace

TEST(ReferenceAlignment, RecoversAMirroredRotatedScaledFrame) {
  const cv::Mat ref = cv::imread(kPlaces + "/maps/lab_intel.png", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(ref.empty());
  const cv::Size size(720, 760);
  const cv::Matx23d T = knownTransform(ref.size());
  const cv::Mat map_free = toMap(ref > 250, T, size);
  const ReferenceAlignment a = alignReference(map_free, ref > 250);
  EXPECT_GT(a.correlation, 0.95);
  // The found warp (map -> reference) composed with T is the identity, to within a pixel over the whole plan.
  for (const cv::Point2d p : {cv::Point2d(0, 0), cv::Point2d(ref.cols, 0), cv::Point2d(0, ref.rows),
                              cv::Point2d(ref.cols, ref.rows), cv::Point2d(ref.cols / 2.0, ref.rows / 2.0)}) {
    const cv::Vec3d ph(p.x, p.y, 1);
    const cv::Vec2d m = T * ph;
    const cv::Vec2d back = a.map_to_reference * cv::Vec3d(m[0], m[1], 1);
    EXPECT_NEAR(back[0], p.x, 1.5) << p;
    EXPECT_NEAR(back[1], p.y, 1.5) << p;
  }
}

TEST(ReferenceAlignment, PerfectLabelsAndSegmentsScoreNearOne) {
  const cv::Mat ref = cv::imread(kPlaces + "/maps/lab_intel.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat codes = cv::imread(kPlaces + "/labelled/training_intel.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat rooms =
      groundTruthRooms(cv::imread(kPlaces + "/groundtruth/lab_intel_gt_segmentation.png", cv::IMREAD_UNCHANGED));
  ASSERT_FALSE(codes.empty());
  const cv::Size size(720, 760);
  const cv::Matx23d T = knownTransform(ref.size());
  const cv::Mat map_free = toMap(ref > 250, T, size);
  // "Our" result = the truth carried into the map frame.
  const cv::Mat map_codes = toMap(codes, T, size);
  cv::Mat labels(size, CV_8U, cv::Scalar(places::kNoLabel));
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x) {
      const int l = places::labelFromCode(map_codes.at<unsigned char>(y, x));
      if (l >= 0) labels.at<unsigned char>(y, x) = static_cast<unsigned char>(l);
    }
  const cv::Mat segments = toMap(rooms, T, size);
  const ReferenceScore s = scoreAgainstReference(map_free, labels, segments, ref > 250, codes, rooms);
  EXPECT_GT(s.labels.accuracy(), 0.98);
  EXPECT_GT(s.segmentation.recall, 0.97);
  EXPECT_GT(s.segmentation.precision, 0.97);
  EXPECT_GE(s.segmentation.rooms, 20);
  // A wrong answer scores low: every cell called room.
  cv::Mat all_room(size, CV_8U, cv::Scalar(0));
  all_room.setTo(places::kNoLabel, map_free == 0);
  const ReferenceScore w = scoreAgainstReference(map_free, all_room, segments, ref > 250, codes, rooms);
  EXPECT_LT(w.labels.accuracy(), 0.75);
}

TEST(ReferenceAlignment, EmptyMasksAreClearErrors) {
  const cv::Mat empty = cv::Mat::zeros(50, 50, CV_8U), some = cv::Mat::zeros(50, 50, CV_8U);
  some(cv::Rect(10, 10, 20, 20)).setTo(255);
  EXPECT_THROW(alignReference(empty, some, "ref.png"), InputError);
  EXPECT_THROW(alignReference(some, empty, "ref.png"), InputError);
}

TEST(TopologyOptions, FreeOpeningKeysAreReadCheckedAndPickedByMapKind) {
  TopologyOptions opt;
  EXPECT_DOUBLE_EQ(opt.freeOpeningRadiusFor(MapKind::PlainImage), 0.0);
  EXPECT_DOUBLE_EQ(opt.freeOpeningRadiusFor(MapKind::RosMap), 0.05);
  EXPECT_DOUBLE_EQ(opt.freeOpeningRadiusFor(MapKind::ProbabilisticGrid), 0.05);
  EXPECT_EQ(opt.freeThresholdFor(MapKind::PlainImage), 250);
  EXPECT_EQ(opt.freeThresholdFor(MapKind::RosMap), 250);
  EXPECT_EQ(opt.freeThresholdFor(MapKind::ProbabilisticGrid), 204);
  const std::string ini = testing::TempDir() + "/opening.ini";
  for (const std::string bad : {"grid_free_opening_radius = -0.1", "free_opening_radius = 2", "free_opening_radius = x"}) {
    FILE* f = std::fopen(ini.c_str(), "w");
    std::fprintf(f, "[topology]\n%s\n", bad.c_str());
    std::fclose(f);
    try {
      loadTopologyOptions(ini);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(bad.substr(0, bad.find(' '))), std::string::npos) << e.what();
    }
  }
}
