#!/usr/bin/env python3
"""The tables of doc/slam-bench.md from the runs of config-ini/experiments/bench_slam.ini.

    python3 scripts/slam_bench_tables.py out/experiments/bench-slam > tables.md

Per log, loop-closure setting and value of any other swept option (e.g. config-ini/experiments/match_refinements.ini:
a column "variant" then names it): mean and worst seed of the all-relations translational error, the local (at most
50 s apart) and revisit means, median CPU and wall time, largest peak RSS; then every seed's error; then, for the
runs with the loop closure on, its closures from the summary line of each run's stats.txt (kept with keep_maps = true):
medians over the seeds of the closures proposed (matches that entered the pose graph), accepted, switched off (the
outlier test), the global search's matches proposed / accepted / dropped, and the largest correction; and, per log,
the loop closure against the filter alone seed by seed (issue 34: on at most 10 % + 1 cm worse than off).
"""
import glob
import json
import os
import re
import statistics
import sys

NAMES = {"intel": "Intel", "aces": "ACES", "mit-csail": "MIT CSAIL", "fr079": "Freiburg building 079",
         "fr-clinic": "Freiburg hospital", "campus": "Freiburg campus (drifting odometry)"}


def closure_summary(run):
    """The loop closure's summary line of a run's stats.txt as a dict of numbers (None without one)."""
    path = os.path.join(run["dir"], "out", "stats.txt")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        for line in f:
            if line.startswith("# loop_closure:"):
                return {k: float(v) for k, v in re.findall(r"(\w+) ([-+0-9.eE]+)", line[len("# loop_closure:"):])}
    return None


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
    rows = []
    for k in keys:
        if k[1] != "true":
            continue
        sums = [c for c in (closure_summary(r) for r in groups[k].values()) if c]
        if not sums:
            continue
        med = lambda f: statistics.median(f(c) for c in sums)
        rows.append(head(k) + f" {len(sums)} | {med(lambda c: c['closures'] + c['rejected']):.0f} |"
                    f" {med(lambda c: c['closures']):.0f} | {med(lambda c: c['rejected']):.0f} |"
                    f" {med(lambda c: c.get('global_proposed', 0)):.0f} | {med(lambda c: c.get('global_accepted', 0)):.0f} |"
                    f" {med(lambda c: c.get('global_dropped', 0)):.0f} |"
                    f" {med(lambda c: c.get('largest_correction_xy', 0)):.2f} |"
                    f" {max(c.get('largest_correction_xy', 0) for c in sums):.2f} |")
    # The loop closure against the filter alone, seed by seed: on at most 10 % + 1 cm worse than off (issue 34).
    pairs = []
    for d in order:
        for v in variants:
            on, off = groups.get((d, "true", v)), groups.get((d, "false", v))
            if not on or not off:
                continue
            common = sorted(set(on) & set(off))
            worse = [s for s in common if on[s]["trans_mean_m"] > 1.1 * off[s]["trans_mean_m"] + 0.01]
            ratio = max(on[s]["trans_mean_m"] / off[s]["trans_mean_m"] for s in common)
            better = sum(on[s]["trans_mean_m"] < off[s]["trans_mean_m"] for s in common)
            cpu = statistics.median(on[s]["cpu_s"] / off[s]["cpu_s"] for s in common)
            pairs.append(f"| {NAMES[d]} |" + (f" {v} |" if vcol else "") + f" {len(common)} | {better} | {ratio:.2f} |"
                         f" {', '.join(str(s) for s in worse) if worse else 'none'} | {cpu:.2f} |")
    if pairs:
        print()
        print("| log |" + (" variant |" if vcol else "") + " seeds | on better than off | largest on / off |"
              " seeds where on > 1.1 × off + 1 cm | CPU on / off (median) |")
        print("|---|" + ("---|" if vcol else "") + "---|---|---|---|---|")
        print("\n".join(pairs))
    if rows:
        print()
        print("| log | loop closure |" + (" variant |" if vcol else "") + " seeds | proposed | accepted | switched off |"
              " global proposed | global accepted | global dropped | largest correction median (m) |"
              " largest correction max (m) |")
        print("|---|---|" + ("---|" if vcol else "") + "---|" * 9)
        print("\n".join(rows))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/experiments/bench-slam")
