#!/usr/bin/env bash
# Speed of two gridtopo-slam binaries on the same logs, alternated (A B A B ...) so that the shared machine's drift
# falls on both alike (issue 24). Per log and binary: wall, CPU (user + system) and peak RSS from GNU time, and the
# relations error of the first repetition's trajectory (gridtopo-eval of binary B). Prints a markdown table of the
# medians with the ratio B / A, and checks that A and B gave the same trajectory (a speed change should not move
# the result; "differs" says when it did).
#   usage: scripts/bench_speed.sh [-r REPS] [-t THREADS] [-p PARTICLES] [-s SEED] [-c INI] [-C A_INI] [-o OUT] A_BIN_DIR B_BIN_DIR [LOG ...]
# -C: binary A's own INI (an older binary with another default INI, e.g. a worktree's config-ini/slam.ini; default -c's).
#   e.g.   mkdir /tmp/old; cp -r build/bin build/lib /tmp/old; (change, rebuild);
#          scripts/bench_speed.sh /tmp/old/bin build/bin intel aces
# A binary's libraries are taken from the lib folder beside its bin folder when there is one (the build's RUNPATH
# names build/lib by its absolute path: a copied bin alone would run with the new libraries).
# LOG is a name under datasets/slam (intel, aces, mit-csail, fr079, fr-clinic; default: all five) or a path to a
# .clf(.gz) with a .relations(.gz) beside it. Not a test: a run of the five logs with 3 repetitions takes about
# 30 minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
REPS=3 THREADS=2 PARTICLES=30 SEED=1 INI=config-ini/slam.ini A_INI= OUT=
while getopts "r:t:p:s:c:C:o:" f; do
  case $f in
    r) REPS=$OPTARG ;; t) THREADS=$OPTARG ;; p) PARTICLES=$OPTARG ;; s) SEED=$OPTARG ;; c) INI=$OPTARG ;;
    C) A_INI=$OPTARG ;; o) OUT=$OPTARG ;; *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
if [ $# -lt 2 ]; then
  sed -n '2,15p' "$0" >&2
  exit 2
fi
A=$1 B=$2
shift 2
A_INI=${A_INI:-$INI}
for ini in "$INI" "$A_INI"; do
  [ -f "$ini" ] || { echo "bench_speed: $ini: no such INI" >&2; exit 2; }
done
for bin in "$A" "$B"; do
  [ -x "$bin/gridtopo-slam" ] || { echo "bench_speed: $bin/gridtopo-slam: not an executable" >&2; exit 2; }
done
[ -x "$B/gridtopo-eval" ] || { echo "bench_speed: $B/gridtopo-eval: not an executable" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "bench_speed: needs GNU time (/usr/bin/time, Debian package 'time')" >&2; exit 2; }
LOGS=("$@")
[ ${#LOGS[@]} -gt 0 ] || LOGS=(intel aces mit-csail fr079 fr-clinic)
if [ -z "$OUT" ]; then OUT=$(mktemp -d); trap 'rm -rf "$OUT"' EXIT; fi
mkdir -p "$OUT"

median() { sort -g | awk '{v[NR] = $1} END {if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "| log | A wall (s) | B wall (s) | B/A wall | A CPU (s) | B CPU (s) | B/A CPU | A peak RSS (MB) | B peak RSS (MB) | error B (m) | trajectories |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for name in "${LOGS[@]}"; do
  if [ -f "$name" ]; then log=$name; else log=datasets/slam/$name.clf.gz; fi
  [ -f "$log" ] || { echo "bench_speed: $log: no such log" >&2; exit 2; }
  rel=${log%.clf.gz}; rel=${rel%.clf}.relations.gz
  [ -f "$rel" ] || rel=${rel%.gz}
  tag=$(basename "${log%%.clf*}")
  for ((r = 1; r <= REPS; ++r)); do
    for side in A B; do
      bin=$A ini=$A_INI; [ $side = B ] && bin=$B ini=$INI
      dir=$OUT/$tag-$side-$r
      libs=${LD_LIBRARY_PATH:-}
      [ -d "$bin/../lib" ] && libs=$(cd "$bin/../lib" && pwd)${libs:+:$libs}
      LD_LIBRARY_PATH=$libs /usr/bin/time -f "%e %U %S %M" -o "$dir.time" "$bin/gridtopo-slam" -i "$log" -c "$ini" -p "$PARTICLES" \
        -s "$SEED" -t "$THREADS" -o "$dir" -q > "$dir.log" 2>&1 || { echo "bench_speed: $bin on $log failed: $dir.log" >&2; exit 1; }
    done
  done
  col() { for ((r = 1; r <= REPS; ++r)); do awk -v c="$2" '{print (c == "cpu") ? $2 + $3 : (c == "rss") ? $4 / 1024 : $1}' "$OUT/$tag-$1-$r.time"; done; }
  aw=$(col A wall | median) bw=$(col B wall | median) ac=$(col A cpu | median) bc=$(col B cpu | median)
  ar=$(col A rss | sort -g | tail -1) br=$(col B rss | sort -g | tail -1)
  err=–
  if [ -f "$rel" ]; then
    err=$("$B/gridtopo-eval" -r "$rel" -t "$OUT/$tag-B-1/trajectory.txt" 2>/dev/null | awk '/^translational error:/ {print $3}')
  fi
  same=same
  cmp -s "$OUT/$tag-A-1/trajectory.txt" "$OUT/$tag-B-1/trajectory.txt" || same=differs
  awk -v t="$tag" -v aw="$aw" -v bw="$bw" -v ac="$ac" -v bc="$bc" -v ar="$ar" -v br="$br" -v e="$err" -v s="$same" \
    'BEGIN {printf "| %s | %.1f | %.1f | %.2f | %.1f | %.1f | %.2f | %.0f | %.0f | %s | %s |\n", t, aw, bw, bw / aw, ac, bc, bc / ac, ar, br, e, s}'
done
echo
a_ini=; [ "$A_INI" != "$INI" ] && a_ini=" (A: -c $A_INI)"
echo "($REPS repetitions each, alternated A B; -p $PARTICLES -s $SEED -t $THREADS -c $INI$a_ini; medians; A = $A, B = $B)"
