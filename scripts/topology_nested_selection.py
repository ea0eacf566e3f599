#!/usr/bin/env python3
"""Nested (honest) choice of an inference option from a sweep of gridtopo-topology-eval runs.

Each argument is the --json output of one run (same fold models, one option value per run). For every held-out
map, the run with the best pooled accuracy on the *other* maps is chosen, and the held-out map is scored with it;
the pooled accuracy over all maps of these choices estimates what the option is worth when it is not chosen on
the maps that score it (doc/topology.md, Round 5).

usage: topology_nested_selection.py [--stage corrected|blob_vote|after] RUN.json [RUN.json ...]
"""
import argparse
import json

KEYS = {"corrected": "accuracy_corrected", "blob_vote": "accuracy_blob_vote", "after": "accuracy_after"}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--stage", choices=sorted(KEYS), default="corrected",
                    help="which per-map accuracy to select and score on (runs without the blob vote use "
                         "accuracy_after for blob_vote)")
    ap.add_argument("runs", nargs="+")
    a = ap.parse_args()
    runs = {}
    for path in a.runs:
        per_map = json.load(open(path))["labels"]["per_map"]
        key = KEYS[a.stage]
        runs[path] = {m["map"]: (m.get(key, m["accuracy_after"]), m["after_relaxation"]["cells"]) for m in per_map}
    maps = list(next(iter(runs.values())))
    for r in runs.values():
        if sorted(r) != sorted(maps):
            raise SystemExit("all runs must cover the same maps")

    def pooled(run, ms):
        cells = sum(runs[run][m][1] for m in ms)
        return sum(runs[run][m][0] * runs[run][m][1] for m in ms) / cells

    correct = cells = 0
    for m in maps:
        best = max(runs, key=lambda r: pooled(r, [x for x in maps if x != m]))
        acc, n = runs[best][m]
        correct += acc * n
        cells += n
        print(f"{m}: chosen on the other maps {best} -> {100 * acc:.1f} %")
    best_in = max(runs, key=lambda r: pooled(r, maps))
    print(f"nested selection, pooled: {100 * correct / cells:.2f} %")
    print(f"best run chosen on all maps (in-sample): {best_in} {100 * pooled(best_in, maps):.2f} %")


if __name__ == "__main__":
    main()
