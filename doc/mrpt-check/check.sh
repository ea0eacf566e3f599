#!/usr/bin/env bash
# Manual check that MRPT's own tools accept what gridtopo-import writes (needs the mrpt-apps package, which is
# NOT a project dependency: it pulls in ROS libraries). Results are described in doc/formats.md.
# Usage: doc/mrpt-check/check.sh [workdir]   (from the repository's top directory, after building)
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
work=${1:-/tmp/gridtopo_mrpt_check}
import="$repo/build/bin/gridtopo-import"
for tool in rawlog-edit rbpf-slam; do
  command -v "$tool" >/dev/null || { echo "$tool not found: apt-get install mrpt-apps" >&2; exit 1; }
done
mkdir -p "$work"
cd "$work"
"$import" -i "$repo/datasets/slam/intel.clf.gz" -o intel_sf.rawlog
"$import" -q -i "$repo/datasets/slam/intel.clf.gz" --layout obs --odometry odom -o intel_obs.rawlog.gz
"$import" -q -i "$repo/datasets/slam/aces.clf.gz" -o aces_sf.rawlog
for f in intel_sf.rawlog intel_obs.rawlog.gz aces_sf.rawlog; do
  echo "== rawlog-edit --info -i $f"
  rawlog-edit --info -i "$f" 2>&1 | sed -n '/Overall number/,$p'
done
# rbpf-slam on the first 2000 scans (rawlog-edit --cut also reads our file); FULL=1 for the whole log. Its
# memory is capped: when MRPT's pose estimate runs away the particles' grids grow without bound (one full run
# reached 11 GB at step 12025).
rawlog=intel_sf.rawlog
if [[ "${FULL:-0}" != 1 ]]; then
  rawlog-edit --cut --to-index 3999 -i intel_sf.rawlog -o intel_sf_2000.rawlog -w >/dev/null 2>&1
  rawlog=intel_sf_2000.rawlog
fi
echo "== rbpf-slam on $rawlog (single thread, memory capped at 6 GB)"
(ulimit -v 6000000; time rbpf-slam "$repo/doc/mrpt-check/rbpf-slam-intel.ini" "$rawlog" </dev/null >rbpf-slam.log 2>&1) ||
  echo "rbpf-slam failed (exit $?), see $work/rbpf-slam.log"
tail -1 rbpf-slam.log
echo "map: $work/rbpf_intel_out/finalMap_mrpt__maps__COccupancyGridMap2D_00.png"
