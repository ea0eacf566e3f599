#!/usr/bin/env bash
# Regenerates the paper's results into doc/paper.md: every claim with our figure, the paper's, and a verdict.
#   1. (full, core) retrains the Fr101 + Fr52 place model and says whether it equals the shipped
#      datasets/models/places_model_fr101_fr52.yml (the experiments use the shipped one);
#   2. the particle experiment: success rate vs particles for the informed, Hähnel and odometry proposals
#      (config-ini/experiments/paper_particles.ini: 630 runs, about 5 hours of CPU on 2 cores; --core:
#      paper_particles_core.ini, 171 runs, about 1.5 hours; --quick: paper_quick_particles.ini, 8 runs);
#   3. the map experiment: Intel with 15 particles, seeds 1-3, and its topology with the Freiburg model against the
#      labelled lab_intel plan (paper_maps.ini; --quick: the plan itself, paper_quick_maps.ini);
#   4. Fig. 2: the 1 cm cut-out around the first loop closure of seed 1, from its trajectory (gridtopo-render), and
#      the same window from a failed Hähnel run;
#   5. doc/paper.md (scripts/paper_report.py) with the pictures in doc/img/paper/.
# The experiments resume: an interrupted run continues where it stopped (gridtopo-experiment skips finished runs).
#
# Usage: scripts/reproduce_paper.sh [--quick | --core] [--out DIR] [--doc FILE] [-j N] [--no-retrain]
#   --out DIR   results (default out/paper, --quick: out/paper-quick)
#   --doc FILE  the page (default doc/paper.md; --quick: DIR/paper.md, pictures in DIR/img)
#   -j N        runs at a time (default: gridtopo-experiment's, cores / threads per run)
#   --no-retrain  skip step 1 (the shipped Freiburg model is used either way)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${GRIDTOPO_BUILD_DIR:-build}/bin
MODE=full
OUT=
DOC=
JOBS=()
RETRAIN=1
while [ $# -gt 0 ]; do
  case $1 in
    --quick) MODE=quick; shift ;;
    --core) MODE=core; shift ;;
    --out) OUT=$2; shift 2 ;;
    --doc) DOC=$2; shift 2 ;;
    -j) JOBS=(-j "$2"); shift 2 ;;
    --no-retrain) RETRAIN=0; shift ;;
    -h|--help) sed -n 2,20p "$0"; exit 0 ;;
    *) echo "reproduce_paper: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
for b in gridtopo-experiment gridtopo-slam gridtopo-render gridtopo-train gridtopo-topology gridtopo-topology-compare; do
  [ -x "$BIN/$b" ] || { echo "reproduce_paper: $BIN/$b missing: build first (scripts/build.sh)" >&2; exit 1; }
done
command -v python3 > /dev/null || { echo "reproduce_paper: needs python3" >&2; exit 1; }
E=config-ini/experiments
case $MODE in
  full) PART=$E/paper_particles.ini; MAPS=$E/paper_maps.ini ;;
  core) PART=$E/paper_particles_core.ini; MAPS=$E/paper_maps.ini ;;
  quick) PART=$E/paper_quick_particles.ini; MAPS=$E/paper_quick_maps.ini ;;
esac
if [ "$MODE" = quick ]; then
  OUT=${OUT:-out/paper-quick}
  DOC=${DOC:-$OUT/paper.md}
else
  OUT=${OUT:-out/paper}
  DOC=${DOC:-doc/paper.md}
fi
IMG=$(dirname "$DOC")/img/paper
[ "$MODE" = quick ] && IMG=$(dirname "$DOC")/img
mkdir -p "$OUT" "$IMG"
T0=$(date +%s)
P=datasets/places

# 1. The place model of Fig. 3, trained on the two Freiburg plans only (as the paper did).
TRAIN_NOTE="datasets/models/places_model_fr101_fr52.yml (gridtopo-train -c config-ini/topology_train.ini -p $P/labelled/training_Fr101.png:$P/maps/Fr101_original.png -p $P/labelled/training_Fr52.png:$P/maps/Fr52_original.png)"
if [ "$MODE" != quick ] && [ "$RETRAIN" = 1 ]; then
  echo "== 1/5 place model: Fr101 + Fr52 -> $OUT/places_model_fr101_fr52.yml"
  "$BIN/gridtopo-train" -c config-ini/topology_train.ini -p $P/labelled/training_Fr101.png:$P/maps/Fr101_original.png \
    -p $P/labelled/training_Fr52.png:$P/maps/Fr52_original.png -o "$OUT/places_model_fr101_fr52.yml" > "$OUT/train.log" 2>&1
  if cmp -s "$OUT/places_model_fr101_fr52.yml" datasets/models/places_model_fr101_fr52.yml; then
    TRAIN_NOTE="$TRAIN_NOTE; retrained by this run: identical"
  else
    TRAIN_NOTE="$TRAIN_NOTE; retrained by this run: **differs** from the shipped model ($OUT/places_model_fr101_fr52.yml): the figures below use the shipped one"
  fi
fi

# 2-3. The two experiments (exit 1 = some run failed: the tables say which; go on).
echo "== 2/5 particle experiment: $PART -> $OUT/particles"
"$BIN/gridtopo-experiment" "$PART" -o "$OUT/particles" "${JOBS[@]}" || [ $? -eq 1 ]
echo "== 3/5 map experiment: $MAPS -> $OUT/maps"
"$BIN/gridtopo-experiment" "$MAPS" -o "$OUT/maps" "${JOBS[@]}" || [ $? -eq 1 ]
PLANNED=$("$BIN/gridtopo-experiment" $E/paper_particles.ini --list | wc -l)

# 4. Fig. 2 from the trajectory of seed 1 (quick: the informed 15-particle run of the miniature), and a failed run.
run_dir() { ls -d "$1"/runs/$2_* 2> /dev/null | head -1; }
if [ "$MODE" = quick ]; then
  FIG2=$(run_dir "$OUT/particles" intel_informed_particles-15)
  CONTRAST=$(run_dir "$OUT/particles" intel_hahnel_particles-15)
  CONTRAST_LABEL="Hähnel et al., 15 particles"
  TOPO=$(run_dir "$OUT/maps" intel-plan)
  TOPO_MAP=$P/maps/lab_intel.png
else
  FIG2=$(run_dir "$OUT/maps" intel_seed-1)
  CONTRAST=$(run_dir "$OUT/particles" intel_seed-1_hahnel_particles-15)
  CONTRAST_LABEL="Hähnel et al., 15 particles, seed 1"
  TOPO=$FIG2
  TOPO_MAP=$FIG2/out/map.yaml
fi
[ -n "$FIG2" ] && [ -f "$FIG2/out/trajectory.txt" ] || { echo "reproduce_paper: no trajectory for Fig. 2 in $OUT" >&2; exit 1; }
echo "== 4/5 Fig. 2: 1 cm cut-out from $FIG2/out/trajectory.txt"
"$BIN/gridtopo-render" -i datasets/slam/intel.clf.gz -t "$FIG2/out/trajectory.txt" -c "$FIG2/out/options.ini" \
  --loop-closure --size 8 -o "$IMG/fig2_cutout.png" -j "$OUT/fig2.json"
CONTRAST_ARGS=()
if [ -n "$CONTRAST" ] && [ -f "$CONTRAST/out/trajectory.txt" ]; then
  "$BIN/gridtopo-render" -i datasets/slam/intel.clf.gz -t "$CONTRAST/out/trajectory.txt" -c "$CONTRAST/out/options.ini" \
    --loop-closure --size 8 -o "$IMG/fig2_cutout_contrast.png" -j "$OUT/fig2_contrast.json" || true
  [ -f "$OUT/fig2_contrast.json" ] && CONTRAST_ARGS=(--fig2-contrast "$OUT/fig2_contrast.json" --fig2-contrast-label "$CONTRAST_LABEL")
fi
[ -f "$FIG2/out/map_trajectory.png" ] && cp "$FIG2/out/map_trajectory.png" "$IMG/fig2_map.png"
for plot in success_vs_particles error_vs_particles; do
  [ -f "$OUT/particles/plots/$plot.png" ] && cp "$OUT/particles/plots/$plot.png" "$IMG/$plot.png"
done
[ -n "$TOPO" ] && [ -f "$TOPO/topology/compare.json" ] || { echo "reproduce_paper: no topology comparison in $OUT/maps" >&2; exit 1; }
"$BIN/gridtopo-topology-compare" "$TOPO_MAP" "$TOPO/topology" -c "$TOPO/topology/options.ini" \
  --reference-map $P/maps/lab_intel.png --reference-labels $P/labelled/training_intel.png \
  --reference-segmentation $P/groundtruth/lab_intel_gt_segmentation.png -j "$OUT/fig3_compare.json" \
  --errors "$IMG/fig3_label_errors.png" > /dev/null
cp "$TOPO/topology/overlay.png" "$IMG/fig3_overlay.png"

# 5. The page.
echo "== 5/5 $DOC"
SECS=$(( $(date +%s) - T0 ))
HEADER="Run of $(date -u +%Y-%m-%d) at commit $(git rev-parse --short HEAD 2> /dev/null || echo unknown) on $(nproc) cores ($(uname -n)); this call took ${SECS} s (finished runs of earlier calls are not rerun)."
python3 scripts/paper_report.py --mode "$MODE" --particles "$OUT/particles/results.csv" --planned "$PLANNED" \
  --particles-ini "$PART" --maps "$OUT/maps/results.csv" --maps-ini "$MAPS" --compare "$OUT/fig3_compare.json" \
  --fig2 "$OUT/fig2.json" "${CONTRAST_ARGS[@]}" --img "$(realpath --relative-to="$(dirname "$DOC")" "$IMG")" \
  --train-note "$TRAIN_NOTE" --header "$HEADER" --out "$DOC"
