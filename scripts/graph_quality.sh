#!/usr/bin/env bash
# Graph quality against the labelled plans (doc/topology.md, "Graph quality against the plan" and "G3"): labels each
# labelled plan of datasets/places (the *_original image its labels were drawn on) with the shipped model, and each
# given SLAM map of the Intel lab, with gridtopo-topology; scores labels, room segmentation and graph with
# gridtopo-topology-compare against the plan; prints one row per map (with a SLAM map's trajectory.txt beside it,
# also the plan doors the trajectory crossed found as doorway nodes and the spurious room / corridor changes along it). The plans are in the model's training set:
# the rows measure the steps after labelling, not the classifier. lab_d is skipped (its labelled image is 992 x 800,
# its room ground truth 840 x 581).
#   usage: scripts/graph_quality.sh [-b build-dir] [-c topology.ini] [-m model.yml] [-o out-dir] [INTEL_SLAM_map.yaml ...]
# (-m: the place model, default datasets/models/places_model.yml; with another model the plans' rows no longer hold
# only maps of its training set)
#   e.g.   scripts/graph_quality.sh out/intel/slam/map.yaml
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/labelled_plans.sh
BUILD=build INI=config-ini/topology.ini OUT= MODEL=datasets/models/places_model.yml
while getopts "b:c:m:o:" f; do
  case $f in b) BUILD=$OPTARG ;; c) INI=$OPTARG ;; m) MODEL=$OPTARG ;; o) OUT=$OPTARG ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
BIN=$BUILD/bin P=datasets/places
if [ -z "$OUT" ]; then OUT=$(mktemp -d); trap 'rm -rf "$OUT"' EXIT; fi

row() {  # name map reference-map reference-labels reference-segmentation
  local d=$OUT/$1
  mkdir -p "$d"
  # A SLAM map's trajectory.txt beside it goes to the map preparation (which free cells are places), the door
  # passages, and the compare's graph along the trajectory (doc/topology-trajectory.md).
  local traj=()
  [ -f "$(dirname "$2")/trajectory.txt" ] && traj=(-t "$(dirname "$2")/trajectory.txt")
  "$BIN/gridtopo-topology" "$2" "${traj[@]}" -m "$MODEL" -c "$INI" -o "$d/topology" -q > "$d.log" 2>&1
  "$BIN/gridtopo-topology-compare" "$2" "$d/topology" -c "$INI" "${traj[@]}" --reference-map "$3" \
    --reference-labels "$4" --reference-segmentation "$5" -j "$d/compare.json" > /dev/null
  python3 - "$d/compare.json" "$1" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); g = d['graph']; c = d['graph_of_plan_labels']; s = d['segmentation']
r = d['labels']['recall']; t = d['trajectory']
doors = (f"{t['doors_found']} / {t['doors_crossed']} | {t['spurious_label_changes']}" if t['has_trajectory']
         else "– | –")
print(f"| {sys.argv[2]} | {100 * d['cell_accuracy']:.1f} % | {100 * r[1]:.1f} / {100 * r[2]:.1f} % "
      f"| {100 * s['recall']:.1f} / {100 * s['precision']:.1f} % | {g['one_room_node']} | {g['attached']} / {g['plan_rooms']} "
      f"| {g['loops_closed']} / {g['plan_loops']} | {c['attached']} / {c['plan_rooms']}, {c['loops_closed']} / {c['plan_loops']} "
      f"| {doors} |")
PY
}

echo "| map | cell acc. | corridor / doorway recall | rooms R / P | one room node | rooms attached | loops closed | ceiling: attached, loops | doors crossed found | spurious room / corridor changes |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for m in "$@"; do
  row "$(basename "$(dirname "$m")")" "$m" $P/maps/lab_intel.png $P/labelled/training_intel.png \
    $P/groundtruth/lab_intel_gt_segmentation.png
done
while read -r name map labels gt; do
  row "$name" $P/maps/$map $P/maps/$map $P/labelled/$labels $P/groundtruth/$gt
done < <(labelled_plans)
