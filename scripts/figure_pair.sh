#!/usr/bin/env bash
# Two PNG pictures in one figure, side by side or one above the other, each with a title: the before / after figures
# of doc/ (e.g. doc/img/places_prep_hospital.png). gnuplot reads and scales the PNGs (any size: the hospital's
# overlays are 17956 x 9082), so no ImageMagick is needed.
#   usage: scripts/figure_pair.sh [-v] [-s WxH] -o OUT.png A.png "title A" B.png "title B"
#   -v: one above the other (default: side by side); -s: the figure's size in pixels (default 1400x760, 1400x1480 with -v)
#   e.g.   scripts/figure_pair.sh -v -o doc/img/places_prep_hospital.png before/overlay.png before after/overlay.png after
set -euo pipefail
VERTICAL=0 SIZE= OUT=
while getopts "vs:o:" f; do
  case $f in v) VERTICAL=1 ;; s) SIZE=$OPTARG ;; o) OUT=$OPTARG ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
if [ $# -ne 4 ] || [ -z "$OUT" ]; then sed -n '2,7p' "$0" >&2; exit 2; fi
command -v gnuplot > /dev/null || { echo "figure_pair: needs gnuplot (apt-get install gnuplot)" >&2; exit 2; }
for f in "$1" "$3"; do [ -f "$f" ] || { echo "figure_pair: $f: no such file" >&2; exit 2; }; done
if [ -z "$SIZE" ]; then [ $VERTICAL = 1 ] && SIZE=1400x1480 || SIZE=1400x760; fi
LAYOUT="1,2"; [ $VERTICAL = 1 ] && LAYOUT="2,1"
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
q() { printf "%s" "$1" | sed "s/'/''/g"; }  # a gnuplot single-quoted string
gnuplot <<GP
set terminal pngcairo size ${SIZE/x/,} noenhanced
set output '$(q "$TMP/out.png")'
set multiplot layout $LAYOUT
unset key; unset tics; unset border; set size ratio -1
set margins 0,0,0,2
set title '$(q "$2")'
plot '$(q "$1")' binary filetype=png with rgbimage
set title '$(q "$4")'
plot '$(q "$3")' binary filetype=png with rgbimage
unset multiplot
GP
mv "$TMP/out.png" "$OUT"
