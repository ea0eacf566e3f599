#!/usr/bin/env python3
"""The tables of doc/slam-bench.md from the runs of config-ini/experiments/bench_slam.ini.

    python3 scripts/slam_bench_tables.py out/experiments/bench-slam > tables.md

Per log and loop-closure setting: mean and worst seed of the all-relations translational error, the local (at most
50 s apart) and revisit means, median CPU and wall time, largest peak RSS; then every seed's error.
"""
import glob
import json
import statistics
import sys

NAMES = {"intel": "Intel", "aces": "ACES", "mit-csail": "MIT CSAIL", "fr079": "Freiburg building 079",
         "fr-clinic": "Freiburg hospital"}


def main(root):
    runs = [json.load(open(p)) for p in glob.glob(root + "/runs/*/result.json")]
    groups = {}
    for r in runs:
        if r.get("status") != "ok":
            continue
        key = (r["dataset"], r["params"].get("loop_closure.enabled", "true"))
        groups.setdefault(key, {})[int(r["params"]["seed"])] = r
    order = [d for d in NAMES if any(k[0] == d for k in groups)]
    print("| log | loop closure | seeds | mean (m) | worst seed (m) | local mean (m) | revisit mean (m) | revisit / local |"
          " CPU median (s) | wall median (s) | peak RSS max (MB) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for d in order:
        for lc in ("true", "false"):
            g = groups.get((d, lc))
            if not g:
                continue
            rs = list(g.values())
            mean = statistics.mean(r["trans_mean_m"] for r in rs)
            worst = max(r["trans_mean_m"] for r in rs)
            loc = statistics.mean(r["trans_local_mean_m"] for r in rs)
            rev = statistics.mean(r["trans_revisit_mean_m"] for r in rs)
            cpu = statistics.median(r["cpu_s"] for r in rs)
            wall = statistics.median(r["wall_s"] for r in rs)
            rss = max(r["peak_rss_mb"] for r in rs)
            print(f"| {NAMES[d]} | {'on' if lc == 'true' else 'off'} | {len(rs)} | {mean:.4f} | {worst:.4f} | {loc:.4f} |"
                  f" {rev:.4f} | {rev / loc:.1f} | {cpu:.1f} | {wall:.1f} | {rss:.0f} |")
    seeds = sorted({s for g in groups.values() for s in g})
    print()
    print("| log | loop closure | " + " | ".join(str(s) for s in seeds) + " |")
    print("|---|---|" + "---|" * len(seeds))
    for d in order:
        for lc in ("true", "false"):
            g = groups.get((d, lc))
            if not g:
                continue
            cells = [f"{g[s]['trans_mean_m']:.4f}" if s in g else "" for s in seeds]
            print(f"| {NAMES[d]} | {'on' if lc == 'true' else 'off'} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/experiments/bench-slam")
