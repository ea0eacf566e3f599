#!/usr/bin/env bash
# Issue 26's two-layout check: the MIT CSAIL run in its FLASER conversion (datasets/slam/mit-csail.clf.gz) and in its
# original ROBOTLASER1 layout (datasets/slam/mit-csail-robotlaser.clf.gz) should give the same places. Each log goes
# through gridtopo-slam (default INI, 30 particles, seed SEED) and gridtopo-topology (with its trajectory); then
# gridtopo-topology-compare --reference-topology prints the labels' agreement on the places both have and the places
# each lacks (m^2), and writes OUT/agreement.png (common places with the same label light grey, another label red,
# places of the ROBOTLASER1 map only blue, of the FLASER map only orange). About 1.5 min on 2 cores.
#   usage: scripts/topology_layouts.sh [-b build-dir] [-c topology.ini] [-s seed] [-o out-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=build INI=config-ini/topology.ini SEED=1 OUT=out/topology-layouts
while getopts "b:c:s:o:" f; do
  case $f in b) BUILD=$OPTARG ;; c) INI=$OPTARG ;; s) SEED=$OPTARG ;; o) OUT=$OPTARG ;; *) exit 2 ;; esac
done
BIN=$BUILD/bin MODEL=datasets/models/places_model.yml
for layout in flaser robotlaser; do
  log=datasets/slam/mit-csail.clf.gz
  [ $layout = robotlaser ] && log=datasets/slam/mit-csail-robotlaser.clf.gz
  d=$OUT/$layout
  [ -f "$d/slam/trajectory.txt" ] ||
    "$BIN/gridtopo-slam" -i "$log" -c config-ini/slam.ini -s "$SEED" -t 1 -o "$d/slam" -q > "$OUT.$layout.log" 2>&1 &
done
wait
for layout in flaser robotlaser; do
  d=$OUT/$layout
  "$BIN/gridtopo-topology" "$d/slam/map.yaml" -t "$d/slam/trajectory.txt" -m "$MODEL" -c "$INI" -o "$d/topology" -q
done
"$BIN/gridtopo-topology-compare" "$OUT/robotlaser/slam/map.yaml" "$OUT/robotlaser/topology" -c "$INI" \
  --reference-topology "$OUT/flaser/slam/map.yaml" --reference-topology "$OUT/flaser/topology" \
  -j "$OUT/agreement.json" --overlay "$OUT/agreement.png"
