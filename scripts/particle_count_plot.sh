#!/usr/bin/env bash
# The particle count per processed scan of gridtopo-slam runs (stats.txt's `particles` column against the log's
# time since its first scan), one panel per run, with the run's mean count in its title: the adaptive particle set
# (`min_particles`, doc/slam.md) at a glance. Grey: N_eff (stats.txt's `neff`), which triggers each resampling.
#   usage: scripts/particle_count_plot.sh -o OUT.png RUN_DIR "title" [RUN_DIR "title" ...]
#   e.g.   scripts/particle_count_plot.sh -o doc/img/slam-particle-count.png /tmp/kld-intel "Intel, seed 1"
set -euo pipefail
OUT=
while getopts "o:" f; do
  case $f in o) OUT=$OPTARG ;; *) exit 2 ;; esac
done
shift $((OPTIND - 1))
if [ $# -lt 2 ] || [ $(($# % 2)) -ne 0 ] || [ -z "$OUT" ]; then sed -n '2,6p' "$0" >&2; exit 2; fi
command -v gnuplot > /dev/null || { echo "particle_count_plot: needs gnuplot (apt-get install gnuplot)" >&2; exit 2; }
TMP=$(mktemp -d); trap 'rm -rf "$TMP"' EXIT
q() { printf "%s" "$1" | sed "s/'/''/g"; }  # a gnuplot single-quoted string
n=0 plots=
while [ $# -gt 0 ]; do
  stats=$1/stats.txt title=$2
  shift 2
  [ -f "$stats" ] || { echo "particle_count_plot: $stats: no such file" >&2; exit 2; }
  # Columns by name from the header line (# step scan_index timestamp ... neff resampled particles ...).
  awk -v out="$TMP/$n.dat" '
    /^# step / { for (i = 2; i <= NF; ++i) col[$i] = i - 1; next }
    /^#/ || NF == 0 { next }
    { if (!("particles" in col)) { print "stats.txt has no particles column" > "/dev/stderr"; exit 2 }
      if (t0 == "") t0 = $col["timestamp"]
      print $col["timestamp"] - t0, $col["particles"], $col["neff"] > out
      sum += $col["particles"]; ++rows }
    END { if (rows) printf "%.1f\n", sum / rows }' "$stats" > "$TMP/$n.mean"
  plots+="set title '$(q "$title"), mean $(cat "$TMP/$n.mean") particles'
plot '$TMP/$n.dat' using 1:3 with lines lc rgb '#b0b0b0' title 'N_eff', '' using 1:2 with steps lw 1.5 lc rgb '#1f5fbf' title 'particles'
"
  n=$((n + 1))
done
gnuplot <<GP
set terminal pngcairo size 1200,$((260 * n + 40)) noenhanced
set output '$(q "$TMP/out.png")'
set multiplot layout $n,1
set yrange [0:32]
set ylabel 'count'
set xlabel 'log time (s)'
set key top right horizontal opaque box
$plots
unset multiplot
GP
mv "$TMP/out.png" "$OUT"
echo "particle_count_plot: $OUT"
