#!/usr/bin/env bash
# The topology along simulated robot runs through the labelled plans, leave-one-map-out (issue 35: "plans with
# simulated runs"; doc/topology-trajectory.md, "Simulated runs through the plans"). For each plan of datasets/places,
# its simulated SLAM-like map (datasets/places/derived[/slam]/NAME_sim_map.png, pixel-aligned with the plan) is read
# as a ROS map (a YAML beside it in OUT, the thresholds of gridtopo-slam's map.yaml) with the run's trajectory
# (NAME_sim_trajectory.txt), labelled by gridtopo-topology with the fold model that never saw the plan's building, and
# scored by gridtopo-topology-compare -t against the plan: cells, room segmentation, rooms attached, the plan doors
# the run crossed found as doorway nodes between the right spaces, spurious node changes along the path.
# lab_d is left out (scripts/labelled_plans.sh).
#   usage: scripts/bench_topology_runs.sh [-b build-dir] [-c topology.ini] [-v exact|slam] [-k model-cache]
#                                         [-o out-dir] [-j threads]
# -k: the fold models (fold_NAME.yml); missing ones are trained first by gridtopo-topology-eval --model-cache with
#     the shipped model's decision-list order (room, corridor, doorway), about 4 min on 2 cores. Default
#     out/topology-fold-models.
#   e.g.   scripts/bench_topology_runs.sh -v slam -o out/topology-runs-slam
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/labelled_plans.sh
BUILD=build INI=config-ini/topology.ini VARIANT=exact CACHE=out/topology-fold-models OUT= THREADS=2
while getopts "b:c:v:k:o:j:" f; do
  case $f in b) BUILD=$OPTARG ;; c) INI=$OPTARG ;; v) VARIANT=$OPTARG ;; k) CACHE=$OPTARG ;; o) OUT=$OPTARG ;;
    j) THREADS=$OPTARG ;; *) exit 2 ;; esac
done
BIN=$BUILD/bin P=datasets/places
case $VARIANT in exact) SIM=$P/derived ;; slam) SIM=$P/derived/slam ;;
  *) echo "bench_topology_runs.sh: -v must be exact or slam, got '$VARIANT'" >&2; exit 2 ;; esac
if [ -z "$OUT" ]; then OUT=$(mktemp -d); trap 'rm -rf "$OUT"' EXIT; fi
mkdir -p "$OUT"
PLANS=$(labelled_plans | cut -d' ' -f1)

missing=0
for n in $PLANS; do [ -f "$CACHE/fold_$n.yml" ] || missing=1; done
if [ $missing = 1 ]; then
  echo "training the fold models into $CACHE (gridtopo-topology-eval --model-cache) ..." >&2
  "$BIN/gridtopo-topology-eval" -d $P -c "$INI" --fold-order room,corridor,doorway --model-cache "$CACHE" \
    --no-segmentation -j "$OUT/lomo.json" > "$OUT/lomo.log" 2>&1
fi

while read -r name plan labels gt; do
  d=$OUT/$name
  mkdir -p "$d"
  # The sim map as gridtopo-slam's map.yaml would describe it: a probabilistic map (map preparation, grid
  # thresholds), origin at the plan's lower-left corner, the frame of the trajectory.
  printf 'image: %s\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n' \
    "$(realpath "$SIM/${name}_sim_map.png")" > "$d/map.yaml"
  traj=$SIM/${name}_sim_trajectory.txt
  /usr/bin/time -f "%e %M" -o "$d/time.txt" "$BIN/gridtopo-topology" "$d/map.yaml" -t "$traj" \
    -m "$CACHE/fold_$name.yml" -c "$INI" --threads "$THREADS" -o "$d/topology" -q > "$d/topology.log" 2>&1
  "$BIN/gridtopo-topology-compare" "$d/map.yaml" "$d/topology" -c "$INI" -t "$traj" \
    --same-frame --reference-map "$P/maps/$plan" --reference-labels "$P/labelled/$labels" \
    --reference-segmentation "$P/groundtruth/$gt" -j "$d/compare.json" > "$d/compare.log" 2>&1 || {
    cat "$d/compare.log" >&2; exit 1; }
done < <(labelled_plans)

python3 - "$OUT" "$VARIANT" $PLANS <<'PY'
import json, sys
out, variant, names = sys.argv[1], sys.argv[2], sys.argv[3:]
print(f"Simulated runs ({variant} variant), leave-one-map-out fold models, {out}")
print("| plan | align. | cells | corridor / doorway recall | rooms R / P | rooms attached | doors crossed found "
      "| doorway node at the door | spurious splits (room / corridor) |")
print("|---|---|---|---|---|---|---|---|---|")
tot = dict(correct=0, cells=0, att=0, rooms=0, found=0, crossed=0, node=0, spur=0, spur_lc=0)
for n in names:
    d = json.load(open(f"{out}/{n}/compare.json"))
    lab, s, g, t = d['labels'], d['segmentation'], d['graph'], d['trajectory']
    cells = lab['cells']; correct = lab['accuracy'] * cells
    r = lab['recall']
    print(f"| {n} | {d['alignment']['correlation']:.3f} | {100 * d['cell_accuracy']:.1f} % "
          f"| {100 * r[1]:.1f} / {100 * r[2]:.1f} % | {100 * s['recall']:.1f} / {100 * s['precision']:.1f} % "
          f"| {g['attached']} / {g['plan_rooms']} | {t['doors_found']} / {t['doors_crossed']} "
          f"| {t['doors_with_doorway_node']} | {t['spurious_splits']} ({t['spurious_label_changes']}) |")
    tot['correct'] += correct; tot['cells'] += cells; tot['att'] += g['attached']; tot['rooms'] += g['plan_rooms']
    tot['found'] += t['doors_found']; tot['crossed'] += t['doors_crossed']; tot['node'] += t['doors_with_doorway_node']
    tot['spur'] += t['spurious_splits']; tot['spur_lc'] += t['spurious_label_changes']
print(f"| **all** | | {100 * tot['correct'] / max(tot['cells'], 1):.1f} % (pooled) | | "
      f"| {tot['att']} / {tot['rooms']} | {tot['found']} / {tot['crossed']} "
      f"({100 * tot['found'] / max(tot['crossed'], 1):.1f} %) | {tot['node']} | {tot['spur']} ({tot['spur_lc']}) |")
PY
