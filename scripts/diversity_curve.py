#!/usr/bin/env python3
"""The particle set's diversity along a run (issue 23, lever 1): how much history the filter still holds.

For every processed scan of one or more gridtopo-slam output directories: the metres the robot travelled since the
particles' most recent common ancestor (the `coalescence` column of stats.txt, in processed scans, turned into
travel along the run's trajectory.txt). With -o, one gnuplot PNG with a curve per run (time since the start on x,
metres of history held on y; the curves' data in a temporary directory, removed afterwards).

  python3 scripts/diversity_curve.py -o doc/img/slam-diversity.png LABEL=OUT_DIR [LABEL=OUT_DIR ...]

Prints per run: processed scans, resamplings per metre, the mean and largest history held (m).
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile


def read_trajectory(path):
    poses = []
    with open(path) as f:
        for n, line in enumerate(f, 1):
            if line.startswith('#') or not line.strip():
                continue
            w = line.split()
            if len(w) < 4:
                sys.exit(f'{path}:{n}: expected "timestamp x y theta"')
            poses.append((float(w[0]), float(w[1]), float(w[2])))
    travel = [0.0]
    for a, b in zip(poses, poses[1:]):
        travel.append(travel[-1] + math.hypot(b[1] - a[1], b[2] - a[2]))
    return poses, travel


def read_steps(path):
    steps = []
    with open(path) as f:
        header = f.readline().split()
        if header[:1] != ['#'] or 'coalescence' not in header:
            sys.exit(f'{path}:1: no coalescence column (a stats.txt of gridtopo-slam before 2026-12-04?)')
        cols = header[1:]
        ci, si, ri = cols.index('coalescence'), cols.index('scan_index'), cols.index('resampled')
        for n, line in enumerate(f, 2):
            if line.startswith('#'):
                continue
            w = line.split()
            if len(w) < len(cols):
                sys.exit(f'{path}:{n}: expected {len(cols)} columns')
            steps.append((int(w[si]), int(w[ci]), int(w[ri])))
    return steps


def curve(out_dir):
    poses, travel = read_trajectory(os.path.join(out_dir, 'trajectory.txt'))
    steps = read_steps(os.path.join(out_dir, 'stats.txt'))
    rows = []
    for k, (scan, coal, _) in enumerate(steps):
        ancestor_scan = steps[max(0, k - coal)][0]
        rows.append((poses[scan][0] - poses[0][0], travel[scan] - travel[ancestor_scan]))
    resamplings = sum(r for _, _, r in steps)
    return rows, resamplings, travel[-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('runs', nargs='+', help='LABEL=OUT_DIR')
    ap.add_argument('-o', '--png', help='write the curves to this PNG (gnuplot)')
    ap.add_argument('--title', default='history the particle set holds')
    a = ap.parse_args()
    tmp_dir = tempfile.TemporaryDirectory()
    tmp = tmp_dir.name
    plots = []
    for i, spec in enumerate(a.runs):
        label, sep, out_dir = spec.partition('=')
        if not sep:
            sys.exit(f'{spec}: expected LABEL=OUT_DIR')
        rows, resamplings, length = curve(out_dir)
        held = [m for _, m in rows]
        print(f'{label}: {len(rows)} processed scans, {length:.0f} m, {resamplings / max(length, 1e-9):.2f} '
              f'resamplings per metre, history held mean {sum(held) / len(held):.1f} m, max {max(held):.1f} m')
        data = os.path.join(tmp, f'{i}.dat')
        with open(data, 'w') as f:
            for t, m in rows:
                f.write(f'{t:.1f} {m:.2f}\n')
        plots.append(f"'{data}' using 1:2 with lines lw 1.5 title '{label}'")
    if a.png:
        script = (f"set terminal pngcairo size 1100,420 font 'sans,10' noenhanced\nset output '{a.png}'\n"
                  f"set title '{a.title}'\nset xlabel 'time since the start (s)'\n"
                  "set ylabel 'metres of history held (since the common ancestor)'\nset key top left\nset grid\n"
                  "plot " + ', '.join(plots) + '\n')
        subprocess.run(['gnuplot'], input=script, text=True, check=True)


if __name__ == '__main__':
    main()
