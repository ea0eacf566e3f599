#!/usr/bin/env bash
# The main job: builds gridtopo, then on the bundled Intel Research Lab log
#   1. gridtopo-slam      builds the occupancy grid map and the trajectory of every scan (RBPF, informed proposal)
#   2. gridtopo-eval      scores the trajectory against the Freiburg benchmark's ground-truth relations
#   3. gridtopo-topology  labels the map's places (room / corridor / doorway) and builds the topological graph
#   4. gridtopo-topology-compare  scores those labels and rooms against the labelled lab_intel floor plan (the same
#                         building drawn in another frame; aligned automatically), and the graph along the
#                         trajectory: the plan doors it crossed found as doorway nodes (doc/topology-trajectory.md)
# Results land in out/intel/ (override with GRIDTOPO_OUT). Extra arguments go to gridtopo-slam
# (e.g. -p 8 -s 3).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
BIN=${GRIDTOPO_BUILD_DIR:-build}/bin
OUT=${GRIDTOPO_OUT:-out/intel}
LOG=datasets/slam/intel.clf.gz
mkdir -p "$OUT"

echo "== 1/4 SLAM: $LOG -> $OUT/slam"
"$BIN/gridtopo-slam" -i "$LOG" -c config-ini/slam.ini -o "$OUT/slam" "$@"

echo "== 2/4 accuracy against datasets/slam/intel.relations.gz"
"$BIN/gridtopo-eval" -r datasets/slam/intel.relations.gz -l "$LOG" -t "$OUT/slam/trajectory.txt" \
  -j "$OUT/slam/eval.json" | tee "$OUT/slam/eval.txt" | grep -E "error:"

echo "== 3/4 places and topology: $OUT/slam/map.yaml -> $OUT/topology"
"$BIN/gridtopo-topology" "$OUT/slam/map.yaml" -t "$OUT/slam/trajectory.txt" -m datasets/models/places_model.yml \
  -c config-ini/topology.ini -o "$OUT/topology"

echo "== 4/4 topology against the labelled lab_intel floor plan (datasets/places)"
P=datasets/places
"$BIN/gridtopo-topology-compare" "$OUT/slam/map.yaml" "$OUT/topology" -c config-ini/topology.ini \
  -t "$OUT/slam/trajectory.txt" \
  --reference-map $P/maps/lab_intel.png --reference-labels $P/labelled/training_intel.png \
  --reference-segmentation $P/groundtruth/lab_intel_gt_segmentation.png -j "$OUT/topology/compare.json" \
  --overlay "$OUT/topology/compare_segmentation.png" --errors "$OUT/topology/compare_label_errors.png"

echo "run_intel: map $OUT/slam/map.png (with trajectory: map_trajectory.png), trajectory $OUT/slam/trajectory.txt,"
echo "           topology $OUT/topology/overlay.png, graph $OUT/topology/topology.graphml,"
echo "           scores against lab_intel $OUT/topology/compare.json"
