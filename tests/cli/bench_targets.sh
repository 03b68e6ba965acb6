#!/usr/bin/env bash
# scripts/bench-targets' summary (scripts/bench_targets_summary.py) on the files the benchmarks
# themselves write, on small inputs: it reads their keys, computes each figure and says "met" or
# "MISSED" against issue 47's targets. Timings are not asserted; the verdicts on made-up times are.
# Usage: bench_targets.sh BUILD_TOOLS_DIR SOURCE_DIR WORK_DIR
set -u
tools=$1 src=$2 work=$3
. "$(dirname "$0")/lib.sh"
summary="$src/scripts/bench_targets_summary.py"
rm -rf "$work" && mkdir -p "$work/t3" || fail "cannot make $work"

# Nothing run: every target says so, and none is met.
expect 0 "octahedron: not run.*check: not run.*bool union: not run.*target 3: MISSED.*target 4: MISSED" \
  python3 "$summary" "$work"
! echo "$out" | grep -q ": met" || fail "a target met with nothing run: $out"

# Target 1 from bench_morph's own JSON: one mesh, four operations.
"$tools/bench_morph" --threads 1 --se octahedron:r=1/4 --ops dilate,erode,open,close \
  --json "$work/t1-octahedron.json" l-shape >/dev/null || fail "bench_morph failed"
expect 0 "octahedron \(octahedron:r=1/4;.*dilate  1 meshes: ms/facet median.*close   1 meshes.*target 1: MISSED" \
  python3 "$summary" "$work"
# Openings and closings run apart on more meshes (t1-SE-chained-*.json) join the same rows.
"$tools/bench_morph" --threads 1 --se octahedron:r=1/4 --ops open \
  --json "$work/t1-octahedron-chained-2.json" icosphere:1 >/dev/null || fail "bench_morph failed"
expect 0 "dilate  1 meshes.*open    2 meshes: ms/facet median.*close   1 meshes" \
  python3 "$summary" "$work"
# Beside target 1, a zonoball's rows against the octahedron's on the same mesh and operations.
"$tools/bench_morph" --threads 1 --se zonoball:r=1/4,level=0 --ops dilate,erode \
  --json "$work/t1-zonoball0.json" l-shape >/dev/null || fail "bench_morph failed"
expect 0 "target 1: MISSED.*Beside target 1.*zonoball0 \(zonoball:r=1/4,level=0;.*against octahedron:.*dilate  1 meshes: ms/facet median [0-9.]+.*octahedron/zonoball0 time median [0-9.]+x.*erode   1 meshes" \
  python3 "$summary" "$work"
! echo "$out" | grep -q "zonoball0.*open " || fail "a zonoball opening appeared from nowhere: $out"
# Target 2's check from bench_check's JSON: a fanned prism counts as CAD, an icosphere as smooth.
"$tools/bench_check" --threads 1 --no-peer --runs 1 --json "$work/t2-check.json" fan-prism:40 \
  icosphere:2 >/dev/null || fail "bench_check failed"
expect 0 "check, smooth: 1 inputs, s/M median.*check, CAD: 1 inputs, s/M median" \
  python3 "$summary" "$work"

# Target 3's figures and verdict from made-up times (id, facets, seconds, peak KiB).
printf '1 100 5.0 1024\n2 100 12.0 2048\n3 100 61.0 4096\n' >"$work/t3/times-0.txt"
expect 0 "full: 3 meshes, s/mesh median 12.00, mean 26.00, p90 61.00, max 61.00 \(mesh 3\), peak 4 MiB.*target 3: MISSED" \
  python3 "$summary" "$work"
printf '1 100 5.0 1024\n2 100 9.0 2048\n3 100 59.0 4096\n' >"$work/t3/times-0.txt"
expect 0 "median 9.00.*max 59.00 \(mesh 3\).*target 3: met" python3 "$summary" "$work"
# Target 4 from scripts/bench-build's table; a failed step ("!") never meets it.
printf '%s\n' "rev demo-build rest tests sanitizer total" \
  "HEAD 1:41.0 2:31.3 0:36.4 7:24.2 12:12.9" >"$work/t4-build.txt"
expect 0 "the test command \(all four\) 12:12.9.*target 4: met" python3 "$summary" "$work"
printf '%s\n' "rev demo-build rest tests sanitizer total" \
  "HEAD 1:41.0 2:31.3 0:36.4! 7:24.2 12:12.9" >"$work/t4-build.txt"
expect 0 "target 4: MISSED" python3 "$summary" "$work"
printf '%s\n' "rev demo-build rest tests sanitizer total" \
  "HEAD 6:01.0 2:31.3 0:36.4 4:24.2 13:32.9" >"$work/t4-build.txt"
expect 0 "target 4: MISSED" python3 "$summary" "$work"
# The inputs' kinds from scripts/bench-targets' list file win over their names: here an
# icosphere listed as CAD is counted as CAD.
printf 'icosphere:2\tCAD\n' >"$work/t2-check-kinds.txt"
expect 0 "check, CAD: 2 inputs, s/M median" python3 "$summary" "$work"
! echo "$out" | grep -q "check, smooth:" || fail "the listed kind was not used: $out"
rm "$work/t2-check-kinds.txt"

# scripts/bench-targets refuses a misspelt target or mesh name before running anything.
expect 2 "--open-close: 'elefant' is not one of target 1's meshes \\(cow elephant" \
  "$src/scripts/bench-targets" --open-close cow,elefant --out "$work/refused"
expect 2 "--targets: no target '5'" "$src/scripts/bench-targets" --targets 1,5 --out "$work/refused"
[ ! -e "$work/refused" ] || fail "bench-targets made its output directory before refusing"

# The rows as Markdown tables for docs/benchmarks.md.
expect 0 "\| l-shape \([0-9]+\) \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \| [0-9.]+ \|.*zonoball0, zonoball:r=1/4,level=0.*octahedron/zonoball0.*\| l-shape \([0-9]+\) \| [0-9.]+ \| [0-9.]+ \| - \| - \| [0-9.]+ / [0-9.]+ / - / - \|.*\| fan-prism:40 \| CAD \|" \
  python3 "$summary" "$work" --markdown
echo PASS
