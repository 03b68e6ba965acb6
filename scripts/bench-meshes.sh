# SPDX-License-Identifier: GPL-3.0-or-later
# The CGAL demo meshes the benchmarks run on, by role: one list that scripts/bench and
# scripts/bench-targets both source, so that their tables are on the same inputs.
# shellcheck shell=bash disable=SC2034

# Organic meshes for morphology by octahedra and balls (issue 47's target 1).
bench_organic_meshes=(cow elephant knot1 bull fandisk camel man armadillo)
# The validity check's real inputs, smooth and CAD (target 2), and those it also runs under a
# rational rotation (coordinates that are not doubles, as every Boolean's output).
bench_check_smooth_meshes=(armadillo bunny00 refined_elephant turbine)
bench_check_cad_meshes=(cheese fandisk)
bench_check_rotated_meshes=(bunny00 armadillo cheese fandisk)

# bench_demo_paths DIR NAME...: DIR/NAME.off for each NAME whose file is there, one per line.
bench_demo_paths() {
  local dir=$1 name
  shift
  for name in "$@"; do
    [ -f "$dir/$name.off" ] && echo "$dir/$name.off"
  done
  return 0
}
