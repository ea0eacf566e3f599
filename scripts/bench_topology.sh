#!/usr/bin/env bash
# Places / topology benchmark: leave-one-map-out cell accuracy and room segmentation on datasets/places, and the
# wall time of the whole gridtopo-topology pipeline on a ~1000 x 1000 map. Writes doc/topology_bench.md and
# doc/topology_eval.json. Takes a few minutes on 2 cores (9 folds of training).
#   usage: scripts/bench_topology.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
BIN=$BUILD/bin
OUT=doc/topology_bench.md
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# Each fold trains its two classifiers in the decision-list order that gridtopo-train chose by validation for the
# shipped model (FOLD_ORDER=auto re-runs the order validation inside every fold: about 4x slower).
FOLD_ORDER=${FOLD_ORDER:-corridor,doorway,room}
"$BIN/gridtopo-topology-eval" --places-dir datasets/places --ini config-ini/topology.ini \
  --train-ini config-ini/topology_train.ini --fold-order "$FOLD_ORDER" --json doc/topology_eval.json \
  --markdown "$TMP/eval.md" 2> "$TMP/eval.log"

# Whole pipeline (read map, scans, features, classification, relaxation, regions, graph, exports), best of 3.
MAP=datasets/places/maps/office_h_furnitures.png   # 1030 x 1028 cells
best=999
for i in 1 2 3; do
  s=$(date +%s.%N)
  "$BIN/gridtopo-topology" "$MAP" -m datasets/models/places_model.yml -c config-ini/topology.ini --threads 2 \
    -o "$TMP/out" -q 2> "$TMP/topo.log"
  e=$(date +%s.%N)
  t=$(echo "$e - $s" | bc -l)
  best=$(echo "if ($t < $best) $t else $best" | bc -l)
done

{
  echo "<!-- written by scripts/bench_topology.sh on $(date -u +%Y-%m-%dT%H:%MZ), commit $(git rev-parse --short HEAD) -->"
  echo
  cat "$TMP/eval.md"
  printf '| whole pipeline on office_h_furnitures (1030 x 1028 cells), 2 threads, best of 3 | %.2f s wall |\n' "$best"
  echo
  echo "Per map (leave-one-map-out; segmentation uses the fold model that did not see the building):"
  echo
  echo '```'
  grep -v '^|' "$TMP/eval.log" | grep -v '^\s*$' || true
  echo '```'
} > "$OUT"
cat "$OUT"
