#!/usr/bin/env bash
# Benchmark of gridtopo-slam on the four bundled real logs (Intel, ACES, MIT CSAIL, Freiburg hospital): every log
# with the one default INI (config-ini/slam.ini), 30 particles, 2 threads, seeds 1..N, for each proposal.
# Per run: Freiburg relations error (gridtopo-eval), wall and CPU time, peak RSS (GNU time); per log and proposal:
# mean, worst and per-seed error. Writes doc/slam-bench.md (the generated tables; the analyses live in doc/slam.md)
# and, for seed 1 of the informed proposal, the maps with their trajectories as doc/img/slam-<log>.png.
#
# Usage: scripts/bench_slam.sh [--seeds N] [--first-seed K] [--logs "intel aces mit-csail fr-clinic"] [--proposals "informed mode-only"]
#                              [--particles P] [--out DIR] [--doc FILE] [--resume]
# --resume keeps the runs already recorded in DIR/runs.tsv (same particles and build assumed) and runs only the
# missing ones, so a long benchmark can be done in parts; the table covers every recorded run.
# Seeds K..N are run (K = 1 unless --first-seed). Defaults: 10 seeds, the four logs, both proposals, 30 particles, out/bench-slam, doc/slam-bench.md.
# It takes about (seeds x proposals) x 2.5 minutes on the 2-core machine. Run it on an otherwise idle machine: the
# timings are wall-clock. Needs python3 and GNU time (Debian packages python3 time); imagemagick to scale the pictures.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${GRIDTOPO_BUILD_DIR:-build}
BIN=$BUILD/bin
SEEDS=10
FIRST_SEED=1
LOGS="intel aces mit-csail fr-clinic"
PROPOSALS="informed mode-only"
PARTICLES=30
OUT=out/bench-slam
DOC=doc/slam-bench.md
THREADS=${GRIDTOPO_BENCH_THREADS:-2}
RESUME=0
while [ $# -gt 0 ]; do
  case $1 in
    --seeds) SEEDS=$2; shift 2 ;;
    --first-seed) FIRST_SEED=$2; shift 2 ;;
    --logs) LOGS=$2; shift 2 ;;
    --proposals) PROPOSALS=$2; shift 2 ;;
    --particles) PARTICLES=$2; shift 2 ;;
    --out) OUT=$2; shift 2 ;;
    --doc) DOC=$2; shift 2 ;;
    --resume) RESUME=1; shift ;;
    -h|--help) sed -n 2,16p "$0"; exit 0 ;;
    *) echo "bench_slam: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$BIN/gridtopo-slam" ] && [ -x "$BIN/gridtopo-eval" ] || { echo "build first (scripts/build.sh)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "bench_slam: needs GNU time (apt-get install time)" >&2; exit 1; }
mkdir -p "$OUT" doc/img
ROWS=$OUT/runs.tsv
[ "$RESUME" = 1 ] && [ -f "$ROWS" ] || : > "$ROWS"
total=0
for log in $LOGS; do for p in $PROPOSALS; do total=$((total + SEEDS - FIRST_SEED + 1)); done; done
done_runs=0
for log in $LOGS; do
  LOGF=datasets/slam/$log.clf.gz
  REL=datasets/slam/$log.relations.gz
  [ -f "$LOGF" ] && [ -f "$REL" ] || { echo "bench_slam: missing $LOGF or $REL" >&2; exit 1; }
  for p in $PROPOSALS; do
    for s in $(seq "$FIRST_SEED" "$SEEDS"); do
      dir=$OUT/$log-$p-s$s
      if grep -q "^$log	$p	$s	" "$ROWS"; then done_runs=$((done_runs + 1)); continue; fi
      load=$(cut -d" " -f1 /proc/loadavg)
      if ! /usr/bin/time -v -o "$dir.time" "$BIN/gridtopo-slam" -i "$LOGF" -o "$dir" -c config-ini/slam.ini \
          -p "$PARTICLES" -s "$s" -t "$THREADS" --proposal "$p" -q 2> "$dir.log"; then
        echo "bench_slam: gridtopo-slam failed on $log ($p, seed $s), see $dir.log" >&2
        exit 1
      fi
      "$BIN/gridtopo-eval" -r "$REL" -l "$LOGF" -t "$dir/trajectory.txt" -j "$dir.json" > "$dir.eval"
      python3 - "$log" "$p" "$s" "$dir" "$load" >> "$ROWS" <<'PY'
import json, re, sys
log, p, s, d, load = sys.argv[1:6]
j = json.load(open(d + ".json"))
t = open(d + ".time").read()
w = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", t)
wall = 3600 * float(w.group(1) or 0) + 60 * float(w.group(2)) + float(w.group(3))
rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", t).group(1)) / 1024
cpu = float(re.search(r"User time \(seconds\): ([\d.]+)", t).group(1)) + \
      float(re.search(r"System time \(seconds\): ([\d.]+)", t).group(1))
steps = sum(1 for l in open(d + "/stats.txt") if not l.startswith("#"))
tr, ro = j["translational_m"], j["rotational_deg"]
print("\t".join(map(str, [log, p, s, tr["mean"], tr["max"], ro["mean"], wall, cpu, rss, steps, load])))
PY
      done_runs=$((done_runs + 1))
      echo "bench_slam: $done_runs / $total ($log, $p, seed $s): $(tail -1 "$ROWS" | cut -f4 | xargs printf '%.4f') m" >&2
      if [ "$s" = 1 ] && [ "$p" = informed ]; then
        # At most 1200 px wide or high for the documentation (the hospital's map is 8 641 × 4 134 cells).
        if command -v convert > /dev/null; then convert "$dir/map_trajectory.png" -resize '1200x1200>' "doc/img/slam-$log.png"
        else cp "$dir/map_trajectory.png" "doc/img/slam-$log.png"; echo "bench_slam: no ImageMagick, picture kept full size" >&2; fi
      fi
    done
  done
done

python3 - "$ROWS" "$DOC" "$PARTICLES" "$THREADS" "$(git rev-parse --short HEAD)" "$(date -u +%Y-%m-%d)" <<'PY'
import collections, statistics, sys
rows_path, doc, particles, threads, commit, day = sys.argv[1:7]
names = {"intel": "Intel", "aces": "ACES", "mit-csail": "MIT CSAIL", "fr-clinic": "Freiburg hospital"}
groups = collections.OrderedDict()
for line in open(rows_path):
    log, p, s, tm, tmax, rm, wall, cpu, rss, steps, load = line.rstrip("\n").split("\t")
    groups.setdefault((log, p), []).append(dict(seed=int(s), t=float(tm), tmax=float(tmax), r=float(rm),
        wall=float(wall), cpu=float(cpu), rss=float(rss), steps=int(steps)))
intel_cost = {}
for (log, p), rs in groups.items():
    if log == "intel":
        intel_cost[p] = statistics.median(r["cpu"] / r["steps"] for r in rs) / int(particles)
out = []
out.append("# gridtopo-slam benchmark\n")
out.append(f"Produced by `scripts/bench_slam.sh` on {day} (commit {commit}, {threads} threads, {particles} particles, "
           "`config-ini/slam.ini` for every log). Error: Freiburg relations metric (`gridtopo-eval`), mean over "
           "the relations; per log and proposal the mean, the worst seed and each seed. Times are medians over "
           "the seeds. CPU per step and particle: CPU time / processed scans / particles, relative to Intel's "
           "with the same proposal. Analyses: [slam.md](slam.md).\n")
out.append("| log | proposal | seeds | mean trans (m) | worst seed (m) | mean rot (deg) | wall (s) | CPU (s) | "
           "CPU / step / particle (ms, × Intel) | peak RSS (MB, max) |")
out.append("|---|---|---|---|---|---|---|---|---|---|")
for (log, p), rs in groups.items():
    t = [r["t"] for r in rs]
    cps = statistics.median(r["cpu"] / r["steps"] for r in rs) / int(particles)
    rel = f"{cps / intel_cost[p]:.2f}" if p in intel_cost else "–"
    out.append(f"| {names.get(log, log)} | {p} | {len(rs)} | {statistics.mean(t):.4f} | {max(t):.4f} | "
               f"{statistics.mean(r['r'] for r in rs):.3f} | {statistics.median(r['wall'] for r in rs):.1f} | "
               f"{statistics.median(r['cpu'] for r in rs):.1f} | {1000 * cps:.2f} ({rel}) | "
               f"{max(r['rss'] for r in rs):.0f} |")
out.append("\n## Per seed (translational error, m)\n")
seeds = sorted({r["seed"] for rs in groups.values() for r in rs})
out.append("| log | proposal | " + " | ".join(str(s) for s in seeds) + " |")
out.append("|---|---|" + "---|" * len(seeds))
for (log, p), rs in groups.items():
    by = {r["seed"]: r["t"] for r in rs}
    out.append(f"| {names.get(log, log)} | {p} | " + " | ".join(f"{by[s]:.4f}" if s in by else "–" for s in seeds) + " |")
out.append("\nMaps of seed 1 with the informed proposal: " +
           ", ".join(f"[{names.get(l, l)}](img/slam-{l}.png)" for l in dict.fromkeys(k[0] for k in groups)) + ".\n")
open(doc, "w").write("\n".join(out))
print(f"bench_slam: wrote {doc}")
PY
cat "$DOC"
