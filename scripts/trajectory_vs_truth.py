#!/usr/bin/env python3
"""Draws gridtopo-slam trajectories over a ground-truth trajectory (gnuplot, PNG) and prints their errors.

Usage: trajectory_vs_truth.py -o OUT.png TRUTH LABEL=TRAJECTORY [LABEL=TRAJECTORY ...]

TRUTH: `timestamp x y theta` per line (gzip or plain), e.g. datasets/slam/freiburg-campus-drift.gt.txt.gz.
TRAJECTORY: a gridtopo-slam trajectory.txt. Poses are paired by timestamp (to the millisecond); each trajectory is
moved onto the truth by the rigid 2D transform that fits them best (least squares over all poses), then drawn
(one panel per trajectory, truth in grey, the seconds since the first pose written along the truth every 100 s).
Printed per trajectory: poses paired, mean and largest position error after the fit, and the steps whose heading
change differs from the truth's by more than 10 degrees (the filter's wrong modes).
"""
import argparse
import gzip
import math
import os
import subprocess
import sys
import tempfile


def read_poses(path):
    opener = gzip.open if path.endswith(".gz") else open
    poses = {}
    with opener(path, "rt") as f:
        for n, line in enumerate(f, 1):
            if not line.strip() or line.startswith("#"):
                continue
            w = line.split()
            try:
                t, x, y, th = map(float, w[:4])
            except ValueError:
                sys.exit(f"{path}:{n}: expected 'timestamp x y theta', found '{line.strip()}'")
            poses[round(t, 3)] = (x, y, th)
    return poses


def fit(pairs):
    """The rigid transform (angle, tx, ty) that moves the estimates onto the truth (least squares)."""
    n = len(pairs)
    mx = sum(e[0] for e, _ in pairs) / n
    my = sum(e[1] for e, _ in pairs) / n
    gx = sum(g[0] for _, g in pairs) / n
    gy = sum(g[1] for _, g in pairs) / n
    sxx = sum((e[0] - mx) * (g[0] - gx) + (e[1] - my) * (g[1] - gy) for e, g in pairs)
    sxy = sum((e[0] - mx) * (g[1] - gy) - (e[1] - my) * (g[0] - gx) for e, g in pairs)
    a = math.atan2(sxy, sxx)
    c, s = math.cos(a), math.sin(a)
    return a, gx - (c * mx - s * my), gy - (s * mx + c * my)


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("truth")
    ap.add_argument("runs", nargs="+", metavar="LABEL=TRAJECTORY")
    a = ap.parse_args()
    truth = read_poses(a.truth)
    t0 = min(truth)
    tmp = tempfile.mkdtemp()
    panels = []
    for k, run in enumerate(a.runs):
        label, _, path = run.partition("=")
        if not path:
            sys.exit(f"expected LABEL=TRAJECTORY, found '{run}'")
        est = read_poses(path)
        times = sorted(t for t in est if t in truth)
        if len(times) < 2:
            sys.exit(f"{path}: fewer than two poses at the truth's timestamps")
        ang, tx, ty = fit([(est[t], truth[t]) for t in times])
        c, s = math.cos(ang), math.sin(ang)
        data = os.path.join(tmp, f"run{k}.dat")
        errors, wrong = [], 0
        with open(data, "w") as out:
            for i, t in enumerate(times):
                x, y, _ = est[t]
                ax, ay = c * x - s * y + tx, s * x + c * y + ty
                errors.append(math.hypot(ax - truth[t][0], ay - truth[t][1]))
                out.write(f"{t - t0:.1f} {ax:.3f} {ay:.3f}\n")
                if i > 0:
                    p = times[i - 1]
                    d_est = wrap(est[t][2] - est[p][2])
                    d_true = wrap(truth[t][2] - truth[p][2])
                    wrong += abs(math.degrees(wrap(d_est - d_true))) > 10.0
        print(f"{label}: {len(times)} poses, position error after the fit mean {sum(errors) / len(errors):.3f} m, "
              f"largest {max(errors):.3f} m; steps whose heading change is off by more than 10 deg: {wrong}")
        panels.append((label, data))
    truth_dat = os.path.join(tmp, "truth.dat")
    with open(truth_dat, "w") as out:
        for t in sorted(truth):
            out.write(f"{t - t0:.1f} {truth[t][0]:.3f} {truth[t][1]:.3f}\n")
    script = [f"set terminal pngcairo size {900 * len(panels)},760 font ',10'", f"set output '{a.output}'",
              f"set multiplot layout 1,{len(panels)}", "set size ratio -1", "set key top right"]
    for label, data in panels:
        script.append(f"set title '{label}'")
        script.append(f"plot '{truth_dat}' u 2:3 w l lc rgb '#999999' lw 2 t 'truth', "
                      f"'{data}' u 2:3 w l lc rgb '#d62728' t 'gridtopo-slam', "
                      f"'{truth_dat}' u 2:3:(int($1) % 100 == 0 ? sprintf('%d', $1) : '') w labels font ',7' t ''")
    script.append("unset multiplot")
    subprocess.run(["gnuplot"], input="\n".join(script), text=True, check=True)


if __name__ == "__main__":
    main()
