// The leave-one-map-out reports from hand-made scores: every number of the JSON and the Markdown table.
#include "gridtopo/eval/lomo_report.h"

#include <gtest/gtest.h>

using namespace gridtopo;
using namespace gridtopo::eval;

namespace {

// A confusion matrix with `right` cells of each label predicted right and `wrong` rooms predicted corridor.
ConfusionMatrix matrix(long long right, long long wrong) {
  ConfusionMatrix m;
  for (int l = 0; l < 3; ++l) m.count[l][l] = right;
  m.count[0][1] = wrong;
  return m;
}

LomoResult result() {
  LomoResult r;
  r.mode = "leave-one-map-out";
  r.segmentation = true;
  r.threads = 2;
  for (int i = 0; i < 2; ++i) {
    MapLabelScores s;
    s.map = i ? "b" : "a";
    s.order = "doorway,room,corridor";
    s.relaxation_iterations = 7 + i;
    s.before = matrix(10, 10);         // 30 / 40
    s.after = matrix(10, i ? 0 : 10);  // a: 30 / 40, b: 30 / 30
    s.corrected = s.segment_vote = s.after;
    s.oracle_region_vote = s.oracle_region_vote_keep_doorways = s.blob_oracle = matrix(10, 0);
    r.pooled.add(s);
    r.maps.push_back(s);
    SegmentationScore p;
    p.segments = 3 + i, p.rooms = 4, p.precision = 0.9 + 0.1 * i, p.recall = 0.5, p.precision_weighted = 1,
    p.recall_weighted = 0.8;
    r.plain.push_back({"m" + std::to_string(i), p, 1.0 + i});
    r.furnished.push_back({"m" + std::to_string(i) + "_furnitures", p, 3.0});
  }
  return r;
}

}  // namespace

TEST(LomoReport, MeanStdAndPercent) {
  EXPECT_EQ(percent(0.8754), "87.5");
  EXPECT_DOUBLE_EQ(mean({1, 2, 3}), 2.0);
  EXPECT_DOUBLE_EQ(sampleStd({1, 2, 3}), 1.0);
  EXPECT_EQ(sampleStd({5}), 0.0);
  EXPECT_EQ(mean({}), 0.0);
}

TEST(LomoReport, MapLineHasEveryStage) {
  const auto r = result();
  EXPECT_EQ(mapScoreLine(r.maps[0], false, false),
            "a: order doorway,room,corridor acc before 75.0 after 75.0 corrected 75.0 oracle region vote 100.0 "
            "(keeping doorways 100.0) blob oracle 100.0 door recall 100.0/100.0");
  EXPECT_NE(mapScoreLine(r.maps[1], true, false).find("after 100.0 corrected 100.0 vote 100.0 oracle"),
            std::string::npos);
}

TEST(LomoReport, MarkdownPoolsTheMapsAndAveragesTheBenchmark) {
  const std::string md = lomoMarkdown(result());
  // Pooled after relaxation: 60 right of 70.
  EXPECT_NE(md.find("| cell accuracy after relaxation (pooled) | 85.7 % |"), std::string::npos) << md;
  // Mean of 75 % and 100 % over maps, std 17.7.
  EXPECT_NE(md.find("| cell accuracy after relaxation, mean ± std over maps | 87.5 ± 17.7 % |"), std::string::npos);
  EXPECT_NE(md.find("| segmentation unfurnished: recall / precision (mean ± std over maps) | 50.0 ± 0.0 / 95.0 ± 7.1 % |"),
            std::string::npos);
  EXPECT_NE(md.find("| segments / ground-truth rooms (sum over maps), unfurnished; furnished | 7 / 8; 7 / 8 |"),
            std::string::npos);
  EXPECT_NE(md.find("| seconds per benchmark map (labelling + topology, 2 threads) | 1.5 (plain), 3 (furnished) |"),
            std::string::npos);
  EXPECT_EQ(md.find("segment vote"), std::string::npos);  // the vote rows only when the vote is on
}

TEST(LomoReport, JsonHasPooledPerMapAndBenchmarkScores) {
  LomoResult r = result();
  const std::string js = lomoJson(r);
  EXPECT_EQ(js.rfind("{\n  \"mode\": \"leave-one-map-out\",\n  \"labels\": {\n    \"before_relaxation\": ", 0), 0u);
  EXPECT_NE(js.find("\"oracle_region_vote_accuracy\": 1,"), std::string::npos);
  EXPECT_NE(js.find("{\"map\": \"b\", \"order\": \"doorway,room,corridor\", \"relaxation_iterations\": 8, "
                    "\"accuracy_before\": 0.75, \"accuracy_after\": 1, \"accuracy_corrected\": 1, "
                    "\"oracle_region_vote_accuracy\": 1"),
            std::string::npos)
      << js;
  EXPECT_NE(js.find("\"segmentation_plain\": {\"precision_mean\": 0.95, \"precision_std\": 0.0707107, "
                    "\"recall_mean\": 0.5, \"recall_std\": 0, \"seconds_mean\": 1.5, \"maps\": ["),
            std::string::npos)
      << js;
  r.segment_vote = true;
  EXPECT_NE(lomoJson(r).find("\"accuracy_segment_vote\": 1.000000"), std::string::npos);
  r.segmentation = false;
  EXPECT_EQ(lomoJson(r).find("segmentation_plain"), std::string::npos);
  const std::string tail = "    ]\n  }\n}\n", no_seg = lomoJson(r);
  EXPECT_EQ(no_seg.substr(no_seg.size() - tail.size()), tail);
}

TEST(LomoReport, NamesAreJsonEscaped) {
  // A map file named with a quote, a backslash and a tab stays one valid JSON string.
  LomoResult r = result();
  r.maps[0].map = "Fr\"52\\x\t";
  r.plain[0].map = "m\"0";
  const std::string js = lomoJson(r);
  EXPECT_NE(js.find("{\"map\": \"Fr\\\"52\\\\x\\t\", \"order\": \"doorway,room,corridor\""), std::string::npos) << js;
  EXPECT_NE(js.find("{\"map\": \"m\\\"0\", \"score\": "), std::string::npos) << js;
  EXPECT_EQ(js.find('\t'), std::string::npos);
}
