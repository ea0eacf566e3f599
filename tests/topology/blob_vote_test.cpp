// Round 5: region-level votes (topology/blob_vote.h): the oracle region vote of the evaluation, geometric blobs
// and the blob vote of pipeline step 7b.
#include <gtest/gtest.h>

#include "common/scratch.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "gridtopo/core/error.h"
#include "gridtopo/places/labelling.h"
#include "gridtopo/topology/blob_vote.h"
#include "gridtopo/eval/evaluation.h"
#include "gridtopo/eval/oracle_diagnostics.h"
#include "gridtopo/topology/pipeline.h"

using namespace gridtopo;
using namespace gridtopo::topology;
using namespace gridtopo::eval;
namespace fs = std::filesystem;

namespace {
constexpr unsigned char R = 0, C = 1, D = 2, N = places::kNoLabel;

// A lattice of stride 1 with a sample in every cell, so cellProbabilities hands each cell its own distribution.
places::Lattice cellLattice(cv::Size size) {
  places::Lattice l;
  l.stride = 1;
  l.block_sample = cv::Mat(size, CV_32S, cv::Scalar(0));
  return l;
}

// The floor plan of topology_test.cpp (0.05 m: a 20 x 2 m corridor, three 4 x 4 m rooms above it joined by
// 1 m doors), with the top 1.6 m of the left room labelled corridor.
cv::Mat confusedFloorPlan() {
  cv::Mat l(140, 420, CV_8U, cv::Scalar(N));
  l(cv::Rect(10, 100, 400, 40)).setTo(C);
  for (int i = 0; i < 3; ++i) {
    l(cv::Rect(20 + 130 * i, 10, 80, 80)).setTo(R);
    l(cv::Rect(50 + 130 * i, 90, 20, 10)).setTo(D);
  }
  l(cv::Rect(20, 10, 80, 32)).setTo(C);
  return l;
}

// Probabilities by label: room (0.6, 0.3, 0.1), corridor (0.3, 0.6, 0.1), doorway (0.1, 0.1, 0.8).
cv::Mat probsOf(const cv::Mat& labels) {
  cv::Mat p(labels.size(), CV_32FC3, cv::Scalar::all(0));
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) {
      const int l = labels.at<unsigned char>(y, x);
      if (l == R) p.at<cv::Vec3f>(y, x) = {0.6f, 0.3f, 0.1f};
      else if (l == C) p.at<cv::Vec3f>(y, x) = {0.3f, 0.6f, 0.1f};
      else if (l == D) p.at<cv::Vec3f>(y, x) = {0.1f, 0.1f, 0.8f};
    }
  return p;
}
}  // namespace

TEST(BlobVote, OracleRegionVoteSumsProbabilitiesPerGroundTruthRegion) {
  // 10 x 30 cells: truth room (cols 0-11), doorway (12-13), corridor (14-29).
  cv::Mat truth(10, 30, CV_8U, cv::Scalar(115));
  truth.colRange(0, 12).setTo(77);
  truth.colRange(12, 14).setTo(179);
  cv::Mat pred(10, 30, CV_8U, cv::Scalar(C)), probs(10, 30, CV_32FC3, cv::Scalar(0.2, 0.7, 0.1));
  // Room region: 80 cells predicted room with little confidence, 40 corridor with much: the probability sums
  // (room 80 * 0.55 + 40 * 0.05 = 46, corridor 80 * 0.40 + 40 * 0.95 = 70) say corridor, a cell count would say room.
  pred.colRange(0, 8).setTo(R);
  probs.colRange(0, 8).setTo(cv::Scalar(0.55, 0.40, 0.05));
  probs.colRange(8, 12).setTo(cv::Scalar(0.05, 0.95, 0.0));
  // Doorway region: half predicted doorway, half room; its cells are never voted.
  pred.col(12).setTo(D), probs.col(12).setTo(cv::Scalar(0.1, 0.1, 0.8));
  pred.col(13).setTo(R), probs.col(13).setTo(cv::Scalar(0.7, 0.2, 0.1));
  // Corridor region: 60 room, 99 corridor, 1 doorway -> corridor (61.9 vs 81.4).
  pred.colRange(14, 20).setTo(R);
  probs.colRange(14, 20).setTo(cv::Scalar(0.7, 0.2, 0.1));
  pred.at<unsigned char>(0, 25) = D, probs.at<cv::Vec3f>(0, 25) = {0.1f, 0.1f, 0.8f};
  std::vector<int> region_label;
  const cv::Mat regions = groundTruthRegions(truth, pred, &region_label);
  ASSERT_EQ(region_label.size(), 4u);  // index 0 unused, then room, corridor, doorway (ids by label order)
  EXPECT_EQ(region_label[1], R);
  EXPECT_EQ(region_label[2], C);
  EXPECT_EQ(region_label[3], D);
  EXPECT_EQ(regions.at<int>(5, 0), 1);
  EXPECT_EQ(regions.at<int>(5, 29), 2);
  EXPECT_EQ(regions.at<int>(5, 12), 3);

  ConfusionMatrix before, oracle, keep;
  before.add(truth, pred);
  EXPECT_NEAR(before.accuracy(), 189.0 / 300.0, 1e-12);  // 80 + 10 + 99
  const cv::Mat o = oracleRegionVote(truth, pred, probs, false);
  oracle.add(truth, o);
  EXPECT_NEAR(oracle.accuracy(), 170.0 / 300.0, 1e-12);  // room region all corridor (0), door 10, corridor 160
  EXPECT_EQ(o.at<unsigned char>(5, 0), C);
  EXPECT_EQ(o.at<unsigned char>(5, 13), R);                 // doorway region keeps its prediction
  EXPECT_EQ(o.at<unsigned char>(0, 25), C);                 // the predicted doorway in the corridor is voted
  const cv::Mat k = oracleRegionVote(truth, pred, probs, true);
  keep.add(truth, k);
  EXPECT_NEAR(keep.accuracy(), 169.0 / 300.0, 1e-12);
  EXPECT_EQ(k.at<unsigned char>(0, 25), D);                 // ... unless predicted doorways are kept
  // Cells without a prediction (not free) belong to no region and stay unpredicted.
  pred.at<unsigned char>(9, 29) = N;
  EXPECT_EQ(groundTruthRegions(truth, pred).at<int>(9, 29), 0);
  ConfusionMatrix m;
  m.add(truth, oracleRegionVote(truth, pred, probs, false));
  EXPECT_EQ(m.unpredicted, 1);
  EXPECT_EQ(m.total(), 299);
}

TEST(BlobVote, GeometricBlobsSplitAtDoorsAndIgnoreFurniture) {
  // Two 4 x 4 m rooms joined by a 0.9 m opening in a 0.2 m wall.
  cv::Mat free(100, 200, CV_8U, cv::Scalar(0));
  free(cv::Rect(10, 10, 80, 80)).setTo(255);
  free(cv::Rect(94, 10, 80, 80)).setTo(255);
  free(cv::Rect(90, 40, 4, 18)).setTo(255);
  BlobVoteOptions o;
  o.neck_width = 1.3, o.min_core_area = 0.5, o.fill_obstacle_area = 0.25, o.grow_limit = 0;
  cv::Mat b = geometricBlobs(free, 0.05, o);
  double mx = 0;
  cv::minMaxLoc(b, nullptr, &mx);
  EXPECT_EQ(mx, 2.0);
  EXPECT_NE(b.at<int>(50, 30), b.at<int>(50, 150));
  EXPECT_EQ(b.at<int>(50, 90), b.at<int>(50, 30));  // the opening is cut in its middle
  EXPECT_EQ(b.at<int>(50, 93), b.at<int>(50, 150));
  EXPECT_EQ(cv::countNonZero(b), cv::countNonZero(free));  // every free cell in a blob
  EXPECT_EQ(cv::countNonZero((b != 0) & (free == 0)), 0);
  // A neck of 0.6 m: the 0.9 m opening is a passage, one blob.
  o.neck_width = 0.6;
  cv::minMaxLoc(geometricBlobs(free, 0.05, o), nullptr, &mx);
  EXPECT_EQ(mx, 1.0);
  // Furnished: a 0.2 m chair every metre. Without filling, the band around the chairs leaves no core at all.
  for (int y = 18; y < 90; y += 20)
    for (int x = 18; x < 174; x += 20)
      if (x < 84 || x > 100) free(cv::Rect(x, y, 4, 4)).setTo(0);
  o.neck_width = 1.3, o.fill_obstacle_area = 0;
  EXPECT_EQ(cv::countNonZero(geometricBlobs(free, 0.05, o)), 0);
  o.fill_obstacle_area = 0.1;  // chairs are 0.04 m^2
  b = geometricBlobs(free, 0.05, o);
  cv::minMaxLoc(b, nullptr, &mx);
  EXPECT_EQ(mx, 2.0);
  EXPECT_EQ(b.at<int>(19, 19), 0);  // a chair cell is in no blob
  EXPECT_EQ(cv::countNonZero(b), cv::countNonZero(free));
}

TEST(BlobVote, VoteInBlobsBeforeCorrection) {
  const cv::Mat l = confusedFloorPlan();
  const cv::Mat probs = probsOf(l);
  const places::Lattice lat = cellLattice(l.size());
  BlobVoteOptions o;
  o.enabled = true;
  o.neck_width = 1.3, o.grow_limit = 0, o.min_share = 0.5;
  // Left room: 48 rows room (0.6 / 0.3), 32 rows corridor (0.3 / 0.6): room 3072 vs corridor 2688, share 0.533.
  const cv::Mat v = voteInGeometricBlobs(l, 0.05, o, lat, probs);
  EXPECT_EQ(v.at<unsigned char>(20, 60), R);
  EXPECT_EQ(v.at<unsigned char>(95, 60), D);   // doorways keep their labels
  EXPECT_EQ(v.at<unsigned char>(120, 200), C);
  EXPECT_EQ(cv::countNonZero(v != l), 80 * 32);
  // The votes are probability sums: with the corridor strip twice as confident, the room turns corridor.
  cv::Mat p2 = probs.clone();
  p2(cv::Rect(20, 10, 80, 32)).setTo(cv::Scalar(0.0, 1.0, 0.0));
  p2(cv::Rect(20, 42, 80, 48)).setTo(cv::Scalar(0.5, 0.4, 0.1));  // room 1920, corridor 2560 + 1536
  EXPECT_EQ(voteInGeometricBlobs(l, 0.05, o, lat, p2).at<unsigned char>(60, 60), C);
  // min_share: a 53 % majority is not enough for 0.6.
  o.min_share = 0.6;
  EXPECT_EQ(cv::countNonZero(voteInGeometricBlobs(l, 0.05, o, lat, probs) != l), 0);
  // In buildTopology: step 7b runs before the correction rules, and needs the probabilities.
  o.min_share = 0.5;
  TopologyOptions topo;
  topo.blob_vote = o;
  places::LabellingResult labelling;  // what the blob vote reads of it: the lattice and the relaxed probabilities
  labelling.lattice = lat;
  labelling.probs = probs;
  const TopologyResult t = buildTopology(l, 0.05, topo, &labelling);
  EXPECT_EQ(t.labels_blob_vote.at<unsigned char>(20, 60), R);
  EXPECT_EQ(t.labels.at<unsigned char>(20, 60), R);
  EXPECT_EQ(t.regions.regions.size(), 7u);  // three rooms, three doors, the corridor
  EXPECT_THROW(buildTopology(l, 0.05, topo), std::invalid_argument);
  topo.blob_vote.enabled = false;
  const TopologyResult off = buildTopology(l, 0.05, topo);
  EXPECT_TRUE(off.labels_blob_vote.empty());
  EXPECT_EQ(off.labels.at<unsigned char>(20, 60), C);
}

TEST(BlobVote, IniKeys) {
  const fs::path p = gridtopo::test::scratchPath("blob_vote_test.ini");
  {
    std::ofstream f(p);
    f << "[topology]\nblob_vote = true\nblob_vote_neck_width = 2.0\nblob_vote_min_core_area = 1.5\n"
         "blob_vote_fill_obstacle_area = 0\nblob_vote_min_share = 0.7\n";
  }
  const TopologyOptions t = loadTopologyOptions(p.string());
  EXPECT_TRUE(t.blob_vote.enabled);
  EXPECT_DOUBLE_EQ(t.blob_vote.neck_width, 2.0);
  EXPECT_DOUBLE_EQ(t.blob_vote.min_core_area, 1.5);
  EXPECT_DOUBLE_EQ(t.blob_vote.fill_obstacle_area, 0.0);
  EXPECT_DOUBLE_EQ(t.blob_vote.min_share, 0.7);
  EXPECT_FALSE(loadTopologyOptions("").blob_vote.enabled);  // off by default
  {
    std::ofstream f(p);
    f << "[topology]\nblob_vote_min_share = 0.3\n";
  }
  EXPECT_THROW(loadTopologyOptions(p.string()), InputError);
  fs::remove(p);
}
