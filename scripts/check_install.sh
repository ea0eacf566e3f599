#!/usr/bin/env bash
# Proves gridtopo installs like any MRPT library (issue 37; doc/install.md), from a built tree:
#  1. `cmake --install` into a temporary prefix: apps, public shared libraries, headers, the CMake package, the
#     place model and INI files are there; the internal libraries are neither installed nor exported; the installed
#     apps load the libraries of the prefix (RPATH), not the build tree's;
#  2. the example examples/mrpt_builder configures with find_package(gridtopo) (CMAKE_PREFIX_PATH = the prefix),
#     builds, and runs on the first 1000 scans of the bundled Intel log (an MRPT rawlog made by the installed
#     gridtopo-import): its map, path and graph are checked (sizes, seen cells, nodes, edges);
#  3. the installed gridtopo-topology, started from a folder outside the checkout with its default model (found in
#     the prefix's share/gridtopo), gives the same graph on the example's map as the example's topology builder;
#  4. `cpack -G DEB` makes gridtopo and gridtopo-dev .debs whose contents (dpkg-deb -c) and Depends are checked;
#     the runtime package, unpacked, runs gridtopo-topology with its own libraries and model.
# Usage: scripts/check_install.sh        GRIDTOPO_BUILD_DIR selects the build folder (default build).
# About 2 minutes on 2 busy cores (the example's build 20-40 s; cpack 60-90 s, of which ~30 s is its
# 'preinstall' step checking that the whole tree is built). Exit 0 when every check passes.
set -euo pipefail
SRC=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$(cd "${GRIDTOPO_BUILD_DIR:-$SRC/build}" && pwd)
W=$(mktemp -d /tmp/gridtopo_check_install.XXXXXX)
trap 'rm -rf "$W"' EXIT
P=$W/prefix
T0=$EPOCHREALTIME
say() { awk -v a="$EPOCHREALTIME" -v b="$T0" -v m="$*" 'BEGIN { printf "check_install: %6.1f s  %s\n", a - b, m }'; }
fail() { echo "check_install: FAILED: $*" >&2; exit 1; }
unset GRIDTOPO_DATA_DIR
LIBDIR=$(sed -n 's/^CMAKE_INSTALL_LIBDIR:PATH=//p' "$BUILD/CMakeCache.txt")
[ -n "$LIBDIR" ] || fail "no CMAKE_INSTALL_LIBDIR in $BUILD/CMakeCache.txt"

# 1. The prefix.
cmake --install "$BUILD" --prefix "$P" > "$W/install.log"
for f in bin/gridtopo-slam bin/gridtopo-topology bin/gridtopo-map bin/gridtopo-import \
         "$LIBDIR/libgridtopo_slam.so" "$LIBDIR/libgridtopo_mapping.so" "$LIBDIR/libgridtopo_core.so.0.1" \
         include/gridtopo/mapping/rbpf_map_builder.h include/gridtopo/mapping/topology_builder.h \
         include/gridtopo/core/error.h "$LIBDIR/cmake/gridtopo/gridtopoConfig.cmake" \
         "$LIBDIR/cmake/gridtopo/gridtopoConfigVersion.cmake" "$LIBDIR/cmake/gridtopo/gridtopoTargets.cmake" \
         share/gridtopo/datasets/models/places_model.yml share/gridtopo/config-ini/slam.ini \
         share/gridtopo/config-ini/run-map.ini share/gridtopo/datasets/README.md; do
  [ -e "$P/$f" ] || fail "not installed: $f"
done
for m in eval experiment session sim simtrain; do
  if compgen -G "$P/$LIBDIR/libgridtopo_$m*" > /dev/null || [ -e "$P/include/gridtopo/$m" ]; then
    fail "internal library $m installed"
  fi
  ! grep -q "gridtopo::$m\b" "$P/$LIBDIR/cmake/gridtopo/gridtopoTargets.cmake" || fail "internal library $m exported"
done
exported=$(grep -o 'add_library(gridtopo::[a-z_]*' "$P/$LIBDIR/cmake/gridtopo/gridtopoTargets.cmake" |
           sed 's/add_library(//' | sort | tr '\n' ' ')
[ "$exported" = "gridtopo::core gridtopo::io gridtopo::io_core gridtopo::mapping gridtopo::places gridtopo::slam gridtopo::slam_core gridtopo::topology " ] ||
  fail "exported targets: $exported"
# Every gridtopo library an installed app loads comes from the prefix.
ldd "$P/bin/gridtopo-map" > "$W/ldd.txt"
[ "$(grep -c 'libgridtopo_' "$W/ldd.txt")" -ge 5 ] || fail "gridtopo-map does not load its libraries: $(cat "$W/ldd.txt")"
for lib in $(awk '/libgridtopo_/ { print $3 }' "$W/ldd.txt"); do
  [ "$(dirname "$(realpath "$lib")")" = "$P/$LIBDIR" ] || fail "gridtopo-map loads $lib, outside $P/$LIBDIR"
done
say "installed into $P: $(find "$P" -type f | wc -l) files, $(du -sm "$P" | cut -f1) MB; exported: $exported"

# 2. The example, built against the prefix only.
cmake -S "$SRC/examples/mrpt_builder" -B "$W/example" -DCMAKE_PREFIX_PATH="$P" > "$W/example-configure.log" ||
  { cat "$W/example-configure.log"; fail "the example does not configure"; }
grep -qx "gridtopo_DIR:PATH=$P/$LIBDIR/cmake/gridtopo" "$W/example/CMakeCache.txt" ||
  fail "the example found another gridtopo: $(grep '^gridtopo_DIR' "$W/example/CMakeCache.txt")"
cmake --build "$W/example" -j2 > "$W/example-build.log" || { cat "$W/example-build.log"; fail "the example does not build"; }
say "example configured and built"

# The first 1000 scans of Intel (its first rooms and corridor; 200 scans hold only 15 SLAM steps: the robot starts
# slowly) as an MRPT rawlog (action / sensory-frame layout), by the installed gridtopo-import.
awk '{ print } $1 == "FLASER" && ++n == 1000 { exit }' <(zcat "$SRC/datasets/slam/intel.clf.gz") > "$W/intel1000.clf"
[ "$(grep -c '^FLASER' "$W/intel1000.clf")" = 1000 ] || fail "intel1000.clf does not hold 1000 scans"
(cd "$W" && "$P/bin/gridtopo-import" -q -i intel1000.clf -o intel1000.rawlog.gz)
printf '[slam]\nparticles = 10\nthreads = 2\n\n[topology_builder]\nupdate_every = 100\n' > "$W/example.ini"
(cd "$W" && ./example/mrpt_builder intel1000.rawlog.gz out example.ini) > "$W/example.txt" ||
  { cat "$W/example.txt"; fail "the example failed"; }
cat "$W/example.txt"
line=$(cat "$W/example.txt")
num() { sed -n "s/.*[^0-9]$1.*/\\1/p" <<< "$line"; }
entries=$(num '\([0-9]*\) rawlog entries'); frames=$(num '(\([0-9]*\) frames'); scans=$(num '\([0-9]*\) scans in the map')
cols=$(num 'map \([0-9]*\) x'); rows=$(num 'map [0-9]* x \([0-9]*\) cells'); known=$(num 'cells, \([0-9]*\) known')
nodes=$(num 'graph \([0-9]*\) nodes'); edges=$(num '\([0-9]*\) edges'); updates=$(num '\([0-9]*\) topology updates')
rooms=$(num '(\([0-9]*\) rooms'); corridors=$(num '\([0-9]*\) corridors'); doorways=$(num '\([0-9]*\) doorways')
# 1000 scans = 1000 action / frame pairs; the filter processes a scan after enough motion (measured: 176 of them,
# a 578 x 567 map with 90019 seen cells, 7 rooms, 1 corridor, 6 doorways, 21 edges with 10 particles, seed 1).
[ "$entries" = 2000 ] && [ "$frames" = 1000 ] || fail "rawlog entries $entries, frames $frames (expected 2000, 1000)"
[ "$scans" -ge 120 ] && [ "$scans" -le 250 ] || fail "scans in the map: $scans"
# update_every = 100: once at 100 processed scans, once at the end.
[ "$updates" = 2 ] || fail "topology updates: $updates (expected 2)"
# At 5 cm cells: 90019 seen cells are 225 m2 of the lab's first rooms and corridor.
[ "$known" -ge 60000 ] && [ "$known" -le 150000 ] && [ "$known" -lt $((cols * rows)) ] ||
  fail "known cells $known of $cols x $rows"
[ "$cols" -ge 400 ] && [ "$cols" -le 800 ] && [ "$rows" -ge 400 ] && [ "$rows" -le 800 ] || fail "map $cols x $rows"
[ "$rooms" -ge 3 ] && [ "$corridors" -ge 1 ] && [ "$doorways" -ge 2 ] && [ "$edges" -ge $((nodes - 1)) ] ||
  fail "graph: $rooms rooms, $corridors corridors, $doorways doorways, $edges edges"
# The observation-only layout (CObservationOdometry + CObservation2DRangeScan) goes through processObservation.
(cd "$W" && "$P/bin/gridtopo-import" -q -i intel1000.clf --layout obs -o intel1000obs.rawlog.gz &&
  ./example/mrpt_builder intel1000obs.rawlog.gz out-obs example.ini) > "$W/example-obs.txt" ||
  { cat "$W/example-obs.txt"; fail "the example failed on the observation-only layout"; }
grep -Eq '2000 rawlog entries \(0 frames, 2000 observations\), (1[2-9][0-9]|2[0-4][0-9]) scans in the map' \
  "$W/example-obs.txt" || fail "observation-only layout: $(cat "$W/example-obs.txt")"
for f in map.gridmap.gz map.png path.txt topology.json topology.graphml; do
  [ -s "$W/out/$f" ] || fail "the example wrote no $f"
done
python3 - "$W/out" "$cols" "$rows" "$nodes" "$edges" "$scans" <<'PY' || fail "the example's files disagree with its summary"
import json, struct, sys
out, cols, rows, nodes, edges, scans = sys.argv[1], *map(int, sys.argv[2:])
with open(f"{out}/map.png", "rb") as f:
    head = f.read(24)
assert head[:8] == b"\x89PNG\r\n\x1a\n", "map.png is not a PNG"
w, h = struct.unpack(">II", head[16:24])
assert (w, h) == (cols, rows), f"map.png {w} x {h}, map {cols} x {rows}"
g = json.load(open(f"{out}/topology.json"))
assert len(g["nodes"]) == nodes and len(g["edges"]) == edges, (len(g["nodes"]), len(g["edges"]))
path = [l for l in open(f"{out}/path.txt") if l.strip() and not l.startswith("#")]
assert len(path) == scans, f"path.txt: {len(path)} poses, {scans} scans"
print(f"check_install: map.png {w} x {h}, topology.json {nodes} nodes {edges} edges, path.txt {len(path)} poses")
PY
say "example ran: $scans scans, map $cols x $rows, $known known cells, $nodes nodes, $edges edges"

# 3. An installed app outside the checkout, with its default model from the prefix.
mkdir -p "$W/elsewhere"
(cd "$W/elsewhere" && "$P/bin/gridtopo-topology" -q "$W/out/map.gridmap.gz" -t "$W/out/path.txt" -o topo) ||
  fail "the installed gridtopo-topology failed"
grep -qx "model = $P/share/gridtopo/datasets/models/places_model.yml" "$W/elsewhere/topo/options.ini" ||
  fail "gridtopo-topology did not take the prefix's model: $(grep '^model' "$W/elsewhere/topo/options.ini")"
cmp -s "$W/elsewhere/topo/topology.json" "$W/out/topology.json" ||
  fail "gridtopo-topology's graph differs from the example's"
# gridtopo-slam starts without MRPT's maps and loads the prefix's libgridtopo_io (a rawlog) and libgridtopo_slam (the
# outputs) when it needs them (gridtopo/core/lazy_library.h).
for input in intel1000.clf intel1000.rawlog.gz; do
  (cd "$W/elsewhere" && LD_DEBUG=files "$P/bin/gridtopo-slam" -q -p 3 -t 1 -i "$W/$input" -o "slam-$input") \
    > "$W/slam-$input.txt" 2>&1 || { tail -20 "$W/slam-$input.txt"; fail "the installed gridtopo-slam failed on $input"; }
  [ -s "$W/elsewhere/slam-$input/map.gridmap.gz" ] && [ -s "$W/elsewhere/slam-$input/map.simplemap" ] ||
    fail "the installed gridtopo-slam wrote no MRPT map for $input"
  grep -Eq "file=$P/[^ ]*/libgridtopo_slam\.so\.0\.1 .*dynamically loaded" "$W/slam-$input.txt" ||
    fail "gridtopo-slam did not load the prefix's libgridtopo_slam on $input"
done
grep -Eq "file=$P/[^ ]*/libgridtopo_io\.so\.0\.1 .*dynamically loaded" "$W/slam-intel1000.rawlog.gz.txt" ||
  fail "gridtopo-slam did not load the prefix's libgridtopo_io for a rawlog"
say "installed gridtopo-topology: default model from the prefix, the example's graph"

# 4. The Debian packages.
(cd "$W" && cpack -G DEB -B "$W/deb" --config "$BUILD/CPackConfig.cmake" > "$W/cpack.log") ||
  { cat "$W/cpack.log"; fail "cpack failed"; }
RUN_DEB=$(ls "$W"/deb/gridtopo_*.deb); DEV_DEB=$(ls "$W"/deb/gridtopo-dev_*.deb)
dpkg-deb -c "$RUN_DEB" | awk '{ print $6 }' > "$W/run.txt"
dpkg-deb -c "$DEV_DEB" | awk '{ print $6 }' > "$W/dev.txt"
for f in ./usr/bin/gridtopo-slam ./usr/bin/gridtopo-topology ./usr/bin/gridtopo-map \
         "./usr/$LIBDIR/libgridtopo_slam.so.0.1" ./usr/share/gridtopo/datasets/models/places_model.yml \
         ./usr/share/gridtopo/config-ini/slam.ini; do
  grep -qxF "$f" "$W/run.txt" || fail "$(basename "$RUN_DEB") lacks $f"
done
for f in ./usr/include/gridtopo/mapping/rbpf_map_builder.h "./usr/$LIBDIR/cmake/gridtopo/gridtopoConfig.cmake"; do
  grep -qxF "$f" "$W/dev.txt" || fail "$(basename "$DEV_DEB") lacks $f"
done
! grep -q '^./usr/include' "$W/run.txt" || fail "headers in the runtime package"
run_depends=$(dpkg-deb -f "$RUN_DEB" Depends); dev_depends=$(dpkg-deb -f "$DEV_DEB" Depends)
# (Debian 12 links Ceres statically: libceres.a through its CMake package; its shared deps come instead.)
# (No libopencv-contrib406: the corridor pieces thin with our own Zhang-Suen, no library links ximgproc.)
for d in libmrpt-slam2.5 libmrpt-maps2.5 libmrpt-obs2.5 libopencv-core406 libopencv-imgproc406; do
  grep -q "\b$d\b" <<< "$run_depends" || fail "gridtopo's Depends lacks $d: $run_depends"
done
for d in "gridtopo (= " libmrpt-slam-dev libmrpt-graphs-dev libopencv-dev libceres-dev libeigen3-dev; do
  grep -qF "$d" <<< "$dev_depends" || fail "gridtopo-dev's Depends lacks $d: $dev_depends"
done
! grep -qE '(^|, )libmrpt-dev\b' <<< "$run_depends, $dev_depends" || fail "depends on the libmrpt-dev metapackage"
# The runtime package's apps work from where it puts them: unpacked (dpkg-deb -x, not installed system-wide), its
# gridtopo-topology loads the package's libraries and takes the package's model.
dpkg-deb -x "$RUN_DEB" "$W/root"
for lib in $(ldd "$W/root/usr/bin/gridtopo-topology" | awk '/libgridtopo_/ { print $3 }'); do
  [ "$(dirname "$(realpath "$lib")")" = "$W/root/usr/$LIBDIR" ] || fail "the packaged gridtopo-topology loads $lib"
done
(cd "$W/elsewhere" && "$W/root/usr/bin/gridtopo-topology" -q "$W/out/map.gridmap.gz" -t "$W/out/path.txt" -o topo-deb) ||
  fail "the packaged gridtopo-topology failed"
grep -qx "model = $W/root/usr/share/gridtopo/datasets/models/places_model.yml" "$W/elsewhere/topo-deb/options.ini" ||
  fail "the packaged gridtopo-topology did not take the package's model"
cmp -s "$W/elsewhere/topo-deb/topology.json" "$W/out/topology.json" || fail "the packaged gridtopo-topology's graph differs"
say "$(basename "$RUN_DEB") ($(wc -l < "$W/run.txt") entries), $(basename "$DEV_DEB") ($(wc -l < "$W/dev.txt") entries)"
echo "check_install: gridtopo Depends: $run_depends"
echo "check_install: OK"
