#!/usr/bin/env bash
# Benchmark of gridtopo-slam (issue 3): Intel and ACES accuracy (Freiburg relations, gridtopo-eval), wall time,
# CPU time and peak RSS (/usr/bin/time -v), error vs particle count for the informed and the odometry proposal,
# Intel with 30 particles over seeds 1-10, with 8 particles over seeds 1-10, ACES with 30 particles over seeds 1-5
# (config-ini/slam.ini and config-ini/slam-aces.ini).
# Writes the tables to doc/slam-bench.md and the map pictures to doc/img/. Everything in doc/slam-bench.md from the
# line "<!-- hand-written below -->" on (the analyses and experiment rounds) is kept; the part above it is replaced.
# Usage: scripts/bench_slam.sh [--quick]   (--quick: skips the particle sweep and the seed study and writes
#                                          doc/slam-bench-quick.md instead)
# Run it on an otherwise idle machine: the timings are wall-clock.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${GRIDTOPO_BUILD_DIR:-build}
BIN=$BUILD/bin
OUT=${GRIDTOPO_BENCH_OUT:-out/bench-slam}
QUICK=${1:-}
# --quick writes its two rows to a file of its own, so it never replaces the full tables of doc/slam-bench.md.
DOC=doc/slam-bench.md
[ "$QUICK" = "--quick" ] && DOC=doc/slam-bench-quick.md
THREADS=${GRIDTOPO_BENCH_THREADS:-2}
mkdir -p "$OUT" doc/img
MARK='<!-- hand-written below -->'
FINAL=$DOC
DOC=$(mktemp)
trap 'rm -f "$DOC"' EXIT
[ -x "$BIN/gridtopo-slam" ] && [ -x "$BIN/gridtopo-eval" ] || { echo "build first (scripts/build.sh)"; exit 1; }

# run <name> <log> <relations> <extra slam args...>: prints "trans_mean trans_std rot_mean rot_std wall_s rss_mb cpu_s"
run() {
  local name=$1 log=$2 rel=$3
  shift 3
  local dir=$OUT/$name
  /usr/bin/time -v -o "$dir.time" "$BIN/gridtopo-slam" -i "$log" -o "$dir" -c "${INI:-config-ini/slam.ini}" -t "$THREADS" -q "$@" \
    2> "$dir.log" || { echo "gridtopo-slam failed, see $dir.log" >&2; exit 1; }
  "$BIN/gridtopo-eval" -r "$rel" -l "$log" -t "$dir/trajectory.txt" -j "$dir.json" > "$dir.eval"
  python3 - "$dir.json" "$dir.time" <<'PY'
import json, re, sys
j = json.load(open(sys.argv[1]))
t = open(sys.argv[2]).read()
wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", t)
h = float(wall.group(1) or 0); m = float(wall.group(2)); s = float(wall.group(3))
rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", t).group(1)) / 1024
cpu = float(re.search(r"User time \(seconds\): ([\d.]+)", t).group(1)) + float(re.search(r"System time \(seconds\): ([\d.]+)", t).group(1))
tr, ro = j["translational_m"], j["rotational_deg"]
print("%.4f %.4f %.3f %.3f %.1f %.0f %.1f" % (tr["mean"], tr["std"], ro["mean"], ro["std"], 3600 * h + 60 * m + s, rss, cpu))
PY
}

INTEL=datasets/slam/intel.clf.gz
INTEL_REL=datasets/slam/intel.relations.gz
ACES=datasets/slam/aces.clf.gz
ACES_REL=datasets/slam/aces.relations.gz
{
  echo "# gridtopo-slam benchmark"
  echo
  echo "Produced by \`scripts/bench_slam.sh $QUICK\` on $(date -u +%Y-%m-%d) ($(nproc) cores, $THREADS threads," \
       "commit $(git rev-parse --short HEAD), load average at start: $(cut -d" " -f1-3 /proc/loadavg)). Errors: Freiburg relations metric (gridtopo-eval), mean ± std."
  echo
  echo "| log | particles | proposal | translational (m) | rotational (deg) | wall (s) | CPU (s) | load before | peak RSS (MB) |"
  echo "|---|---|---|---|---|---|---|---|---|"
  l=$(cut -d" " -f1 /proc/loadavg)
  read -r tm ts rm rs w m c < <(run intel-30 "$INTEL" "$INTEL_REL" -p 30)
  echo "| Intel | 30 | informed | $tm ± $ts | $rm ± $rs | $w | $c | $l | $m |"
  l=$(cut -d" " -f1 /proc/loadavg)
  read -r tm ts rm rs w m c < <(run aces-30 "$ACES" "$ACES_REL" -p 30)
  echo "| ACES (slam.ini) | 30 | informed | $tm ± $ts | $rm ± $rs | $w | $c | $l | $m |"
  l=$(cut -d" " -f1 /proc/loadavg)
  read -r tm ts rm rs w m c < <(INI=config-ini/slam-aces.ini run aces-30-acesini "$ACES" "$ACES_REL" -p 30)
  echo "| ACES (slam-aces.ini) | 30 | informed | $tm ± $ts | $rm ± $rs | $w | $c | $l | $m |"
} > "$DOC"
cp "$OUT/intel-30/map_trajectory.png" doc/img/slam-intel.png
cp "$OUT/aces-30-acesini/map_trajectory.png" doc/img/slam-aces.png

if [ "$QUICK" != "--quick" ]; then
  {
    echo
    echo "## Error vs particle count, Intel (seed 1)"
    echo
    echo "| particles | informed: trans (m) | informed: rot (deg) | informed: wall (s) | odometry: trans (m) | odometry: rot (deg) | odometry: wall (s) |"
    echo "|---|---|---|---|---|---|---|"
    for n in 4 8 15 30 60; do
      read -r tm ts rm rs w m c < <(run intel-inf-$n "$INTEL" "$INTEL_REL" -p $n --proposal informed)
      read -r om os orm ors ow omm oc < <(run intel-odo-$n "$INTEL" "$INTEL_REL" -p $n --proposal odometry)
      echo "| $n | $tm ± $ts | $rm | $w | $om ± $os | $orm | $ow |"
    done
    echo
    echo "## Intel, 30 particles, seeds 1–10 (default INI)"
    echo
    echo "| seed | trans (m) | rot (deg) | ≤ 0.040 m | wall (s) | CPU (s) | load before | peak RSS (MB) |"
    echo "|---|---|---|---|---|---|---|---|"
    ok=0
    for s in 1 2 3 4 5 6 7 8 9 10; do
      l=$(cut -d" " -f1 /proc/loadavg)
      read -r tm ts rm rs w m c < <(run intel-30-s$s "$INTEL" "$INTEL_REL" -p 30 -s $s)
      y=$(python3 -c "print('yes' if $tm <= 0.040 else 'no')")
      [ "$y" = yes ] && ok=$((ok + 1))
      echo "| $s | $tm ± $ts | $rm | $y | $w | $c | $l | $m |"
    done
    echo
    echo "Seeds with ≤ 0.040 m: $ok / 10."
    echo
    echo "## Intel, 8 particles, seeds 1–10 (default INI)"
    echo
    echo "| seed | trans (m) | rot (deg) | consistent (≤ 0.08 m) |"
    echo "|---|---|---|---|"
    ok=0
    for s in 1 2 3 4 5 6 7 8 9 10; do
      read -r tm ts rm rs w m c < <(run intel-8-s$s "$INTEL" "$INTEL_REL" -p 8 -s $s)
      y=$(python3 -c "print('yes' if $tm <= 0.08 else 'no')")
      [ "$y" = yes ] && ok=$((ok + 1))
      echo "| $s | $tm ± $ts | $rm | $y |"
    done
    echo
    echo "Consistent maps: $ok / 10."
    echo
    echo "## ACES, 30 particles, seeds 1–5"
    echo
    echo "| seed | slam.ini: trans (m) | rot (deg) | slam-aces.ini: trans (m) | rot (deg) | slam-aces.ini ≤ 0.045 m | slam-aces.ini CPU (s) |"
    echo "|---|---|---|---|---|---|---|"
    for s in 1 2 3 4 5; do
      read -r tm ts rm rs w m c < <(run aces-30-s$s "$ACES" "$ACES_REL" -p 30 -s $s)
      read -r am as arm ars aw amm ac < <(INI=config-ini/slam-aces.ini run aces-30-acesini-s$s "$ACES" "$ACES_REL" -p 30 -s $s)
      y=$(python3 -c "print('yes' if $am <= 0.045 else 'no')")
      echo "| $s | $tm ± $ts | $rm | $am ± $as | $arm | $y | $ac |"
    done
  } >> "$DOC"
fi
# Keep the hand-written part of the existing document.
if [ -f "$FINAL" ] && grep -qxF "$MARK" "$FINAL"; then
  { echo; sed -n "/^$MARK\$/,\$p" "$FINAL"; } >> "$DOC"
fi
cp "$DOC" "$FINAL"
echo "bench_slam: wrote $FINAL"
cat "$FINAL"
