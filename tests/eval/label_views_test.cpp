// The evaluation pictures and the blob oracle on a 4 x 6 map: which colour every cell gets and why.
#include "gridtopo/eval/label_views.h"

#include <gtest/gtest.h>

#include "gridtopo/eval/oracle_diagnostics.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/places/place_label.h"
#include "gridtopo/topology/export.h"

using namespace gridtopo;
using namespace gridtopo::eval;

namespace {
// Row 0 occupied; rows 1-3 free. Truth: columns 0-2 room (77), 3-5 corridor (115).
places::OccupancyImage occupancy() {
  places::OccupancyImage o;
  o.resolution = 0.1;
  o.cells = cv::Mat(4, 6, CV_8U, cv::Scalar(places::kFree));
  o.cells.row(0).setTo(places::kOccupied);
  return o;
}
cv::Mat truth() {
  cv::Mat t(4, 6, CV_8U, cv::Scalar(77));
  t.colRange(3, 6).setTo(115);
  return t;
}
}  // namespace

TEST(LabelViews, ErrorOverlayPaleWhenRightSaturatedPredictedColourWhenWrong) {
  const auto occ = occupancy();
  cv::Mat pred(4, 6, CV_8U, cv::Scalar(0));  // all room
  pred.at<unsigned char>(3, 5) = places::kNoLabel;
  const cv::Mat img = labelErrorOverlay(occ, truth(), pred);
  EXPECT_EQ(img.at<cv::Vec3b>(0, 0), cv::Vec3b(90, 90, 90));     // not free
  EXPECT_EQ(img.at<cv::Vec3b>(1, 1), cv::Vec3b(250, 215, 190));  // room, right: pale room
  EXPECT_EQ(img.at<cv::Vec3b>(1, 4), topology::kLabelColoursBgr[0]);  // corridor called room: room's colour
  EXPECT_EQ(img.at<cv::Vec3b>(3, 5), cv::Vec3b(0, 0, 0));        // no prediction
}

TEST(LabelViews, SegmentationViewDrawsGroundTruthBordersRedAndSegmentBordersBlack) {
  const auto occ = occupancy();
  cv::Mat seg(4, 6, CV_32S, cv::Scalar(1)), gt(4, 6, CV_32S, cv::Scalar(1));
  seg.colRange(2, 6).setTo(2);  // segment border between columns 1 and 2
  gt.colRange(4, 6).setTo(2);   // room border between columns 3 and 4
  const cv::Mat v = segmentationView(occ, seg, gt);
  EXPECT_EQ(v.at<cv::Vec3b>(0, 0), cv::Vec3b(110, 110, 110));
  EXPECT_EQ(v.at<cv::Vec3b>(2, 1), cv::Vec3b(0, 0, 0));    // next to the other segment
  EXPECT_EQ(v.at<cv::Vec3b>(2, 2), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(v.at<cv::Vec3b>(2, 3), cv::Vec3b(0, 0, 255));  // next to the other room (and not a segment border)
  EXPECT_EQ(v.at<cv::Vec3b>(2, 4), cv::Vec3b(0, 0, 255));
  EXPECT_EQ(v.at<cv::Vec3b>(2, 5), topology::colourSegmentation(seg).at<cv::Vec3b>(2, 5));  // inside: its colour
  cv::Mat labels(4, 6, CV_8U, cv::Scalar(1));
  labels.at<unsigned char>(2, 2) = places::kNoLabel;
  const cv::Mat l = labelsView(occ, labels);
  EXPECT_EQ(l.at<cv::Vec3b>(1, 1), topology::kLabelColoursBgr[1]);
  EXPECT_EQ(l.at<cv::Vec3b>(2, 2), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(l.at<cv::Vec3b>(0, 2), cv::Vec3b(110, 110, 110));
}

TEST(OracleDiagnostics, BlobOracleVotesEachBlobWithItsTrueMajority) {
  // One blob over columns 0-3 (truth: 9 room cells, 3 corridor cells), one over 4-5 (all corridor). Predicted all
  // corridor, a doorway at (1, 0): the first blob becomes room, the second stays corridor, the doorway stays.
  cv::Mat blobs(4, 6, CV_32S, cv::Scalar(1)), labels(4, 6, CV_8U, cv::Scalar(1));
  blobs.colRange(4, 6).setTo(2);
  blobs.row(0).setTo(0);
  labels.row(0).setTo(places::kNoLabel);
  labels.at<unsigned char>(1, 0) = 2;
  const cv::Mat v = blobOracleVote(truth(), labels, blobs);
  EXPECT_EQ(v.at<unsigned char>(2, 0), 0);
  EXPECT_EQ(v.at<unsigned char>(2, 3), 0);  // a corridor cell of the room-majority blob
  EXPECT_EQ(v.at<unsigned char>(2, 4), 1);
  EXPECT_EQ(v.at<unsigned char>(1, 0), 2);
  EXPECT_EQ(v.at<unsigned char>(0, 0), places::kNoLabel);
}
