#!/usr/bin/env bash
# The README's data-flow picture (log -> SLAM map -> places -> rooms -> graph), made from the outputs of
# scripts/run_intel.sh (run it first) with ImageMagick: doc/img/dataflow.png.
set -euo pipefail
cd "$(dirname "$0")/.."
S=out/intel/slam T=out/intel/topology
for f in $S/map_trajectory.png $T/labels.png $T/segmentation_colour.png $T/overlay.png; do
  [ -f "$f" ] || { echo "dataflow_picture: $f missing: run scripts/run_intel.sh first" >&2; exit 1; }
done
command -v montage >/dev/null || { echo "dataflow_picture: needs ImageMagick (apt-get install imagemagick)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Place labels: the label codes (room 77, corridor 115, doorway 179) in the overlay's colours, other cells white.
convert $T/labels.png -fill white -opaque 'gray(0)' -fill '#4f81bd' -opaque 'gray(77)' -fill '#2ca02c' \
  -opaque 'gray(115)' -fill '#d62728' -opaque 'gray(179)' "$tmp/labels.png"
convert $T/overlay.png -resize 50% "$tmp/graph.png"
montage -label '1. log -> SLAM: map + trajectory' $S/map_trajectory.png \
        -label '2. places: room / corridor / doorway' "$tmp/labels.png" \
        -label '3. regions -> rooms' $T/segmentation_colour.png \
        -label '4. topological graph' "$tmp/graph.png" \
        -tile 4x1 -geometry 300x283+6+4 -pointsize 15 -background white "$tmp/strip.png"
mkdir -p doc/img
convert "$tmp/strip.png" -depth 8 doc/img/dataflow.png
echo "dataflow_picture: wrote doc/img/dataflow.png"
