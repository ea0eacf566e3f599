#!/usr/bin/env python3
"""The tables of doc/slam-bench.md from the runs of config-ini/experiments/bench_slam.ini.

    python3 scripts/slam_bench_tables.py out/experiments/bench-slam > tables.md

Per log, loop-closure setting and value of any other swept option (e.g. config-ini/experiments/match_refinements.ini:
a column "variant" then names it): mean and worst seed of the all-relations translational error, the local (at most
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
        p = r["params"]
        variant = ", ".join(f"{k} = {v}" for k, v in sorted(p.items())
                            if k not in ("dataset", "seed", "loop_closure.enabled"))
        key = (r["dataset"], p.get("loop_closure.enabled", "true"), variant)
        groups.setdefault(key, {})[int(p["seed"])] = r
    order = [d for d in NAMES if any(k[0] == d for k in groups)]
    variants = sorted({k[2] for k in groups})
    vcol = variants != [""]
    keys = [(d, lc, v) for d in order for lc in ("true", "false") for v in variants if (d, lc, v) in groups]
    head = lambda k: f"| {NAMES[k[0]]} | {'on' if k[1] == 'true' else 'off'} |" + (f" {k[2]} |" if vcol else "")
    print("| log | loop closure |" + (" variant |" if vcol else "") + " seeds | mean (m) | worst seed (m) |"
          " local mean (m) | revisit mean (m) | revisit / local | CPU median (s) | wall median (s) | peak RSS max (MB) |")
    print("|---|---|" + ("---|" if vcol else "") + "---|---|---|---|---|---|---|---|---|")
    for k in keys:
        g = groups[k]
        rs = list(g.values())
        mean = statistics.mean(r["trans_mean_m"] for r in rs)
        worst = max(r["trans_mean_m"] for r in rs)
        loc = statistics.mean(r["trans_local_mean_m"] for r in rs)
        rev = statistics.mean(r["trans_revisit_mean_m"] for r in rs)
        cpu = statistics.median(r["cpu_s"] for r in rs)
        wall = statistics.median(r["wall_s"] for r in rs)
        rss = max(r["peak_rss_mb"] for r in rs)
        print(head(k) + f" {len(rs)} | {mean:.4f} | {worst:.4f} | {loc:.4f} |"
              f" {rev:.4f} | {rev / loc:.1f} | {cpu:.1f} | {wall:.1f} | {rss:.0f} |")
    seeds = sorted({s for g in groups.values() for s in g})
    print()
    print("| log | loop closure |" + (" variant |" if vcol else "") + " " + " | ".join(str(s) for s in seeds) + " |")
    print("|---|---|" + ("---|" if vcol else "") + "---|" * len(seeds))
    for k in keys:
        g = groups[k]
        cells = [f"{g[s]['trans_mean_m']:.4f}" if s in g else "" for s in seeds]
        print(head(k) + " " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/experiments/bench-slam")
