#!/usr/bin/env python3
"""Splits gridtopo-eval per-relation errors into short and long relations, and compares the reference relations
with the raw odometry of a CARMEN log (the analysis behind doc/slam-bench.md, "Round 4: ACES experiments").

Usage:
  scripts/slam_relations_report.py errors LIMIT_S ERRORS.txt [ERRORS.txt ...]
      per file: mean translational error of the relations spanning <= LIMIT_S seconds ("short") and of the
      others ("long"), and the overall mean. ERRORS.txt is written by `gridtopo-eval ... -e ERRORS.txt`.
  scripts/slam_relations_report.py odometry LIMIT_S LOG.clf[.gz] RELATIONS[.gz]
      for the relations spanning <= LIMIT_S seconds: |reference - odometry| (translation, in the frame of the
      first pose), counted by multiples of 5 cm, and the mean of the odometry's error. Relation timestamps must
      be the logs' FLASER ipc timestamps (true for the Freiburg relations of the shipped logs).
  scripts/slam_relations_report.py steps LIMIT_S LOG.clf[.gz] RELATIONS[.gz] TRAJECTORY.txt
      as `odometry`, and for each class of |reference - odometry| the mean error of the estimate TRAJECTORY.txt
      (gridtopo-slam's: one pose per laser scan, same timestamps) and its mean distance from the odometry.
"""
import gzip
import math
import sys
from collections import Counter


def open_text(path):
    return gzip.open(path, "rt") if path.endswith(".gz") else open(path)


def errors_report(limit, paths):
    for path in paths:
        short, long_ = [], []
        for line in open_text(path):
            if line.startswith("#") or not line.strip():
                continue
            f = line.split()
            (short if float(f[1]) - float(f[0]) <= limit else long_).append(float(f[2]))
        every = short + long_
        print("%s: short (<= %g s) %.4f m (n = %d), long %.4f m (n = %d), all %.4f m"
              % (path, limit, sum(short) / len(short), len(short),
                 sum(long_) / max(1, len(long_)), len(long_), sum(every) / len(every)))


def load_trajectory(path):
    poses = {}
    for line in open_text(path):
        if line.startswith("#") or not line.strip():
            continue
        f = line.split()
        poses[float(f[0])] = (float(f[1]), float(f[2]), float(f[3]))
    return poses


def relative_xy(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx + s * dy, -s * dx + c * dy


def odometry_report(limit, log_path, rel_path, traj_path=None):
    odo = {}
    for line in open_text(log_path):
        f = line.split()
        if not f or f[0] != "FLASER":
            continue
        n = int(f[1])
        # FLASER n ranges... x y theta odom_x odom_y odom_theta ipc_timestamp host logger_timestamp
        odo[float(f[n + 8])] = (float(f[n + 5]), float(f[n + 6]), float(f[n + 7]))
    est = load_trajectory(traj_path) if traj_path else None
    counts = Counter()
    by_class = {}
    errs = []
    missing = 0
    for line in open_text(rel_path):
        f = line.split()
        if not f:
            continue
        t1, t2 = float(f[0]), float(f[1])
        if t2 - t1 > limit:
            continue
        if t1 not in odo or t2 not in odo:
            missing += 1
            continue
        ox, oy = relative_xy(odo[t1], odo[t2])
        e = math.hypot(ox - float(f[2]), oy - float(f[3]))
        errs.append(e)
        k = e / 0.05
        key = "%g x 5 cm" % (round(k * 2) / 2) if abs(k - round(k * 2) / 2) < 0.04 else "other"
        counts[key] += 1
        if est is not None:
            sx, sy = relative_xy(est[t1], est[t2])
            by_class.setdefault(key, []).append((math.hypot(sx - float(f[2]), sy - float(f[3])),
                                                 math.hypot(sx - ox, sy - oy)))
    print("relations <= %g s: %d (%d without a FLASER line at their timestamps)" % (limit, len(errs), missing))
    print("odometry error: mean %.4f m" % (sum(errs) / len(errs)))
    if est is not None:
        every = [v[0] for vs in by_class.values() for v in vs]
        print("estimate error: mean %.4f m" % (sum(every) / len(every)))
    for key, n in sorted(counts.items(), key=lambda kv: (kv[0] == "other", kv[0])):
        line = "  |reference - odometry| = %s: %d" % (key, n)
        if est is not None:
            v = by_class[key]
            line += "; estimate: error %.4f m, |estimate - odometry| %.4f m" % (
                sum(x[0] for x in v) / len(v), sum(x[1] for x in v) / len(v))
        print(line)


def main():
    if len(sys.argv) < 4 or sys.argv[1] not in ("errors", "odometry", "steps"):
        sys.exit(__doc__)
    limit = float(sys.argv[2])
    if sys.argv[1] == "errors":
        errors_report(limit, sys.argv[3:])
    elif sys.argv[1] == "odometry":
        if len(sys.argv) != 5:
            sys.exit(__doc__)
        odometry_report(limit, sys.argv[3], sys.argv[4])
    else:
        if len(sys.argv) != 6:
            sys.exit(__doc__)
        odometry_report(limit, sys.argv[3], sys.argv[4], sys.argv[5])


if __name__ == "__main__":
    main()
