#!/usr/bin/env bash
# `mpirun -n 3 morphex index` stores exactly the rows a single-process run stores (descriptors bit
# for bit), resumes an index another run started, and skips what is up to date.
# Usage: index_mpi.sh MORPHEX MPIEXEC PIPELINE DIR
set -u
morphex=$1 mpiexec=$2 pipeline=$3 dir=$4
rm -rf "$dir" && mkdir -p "$dir"
# Open MPI refuses to start as root without these (CI containers run as root).
if [ "$(id -u)" -eq 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
# Under AddressSanitizer, Open MPI's runtime keeps allocations until exit that LeakSanitizer would
# report (outside morphex): leak checks are off for the MPI runs only.
mpi() { ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" "$mpiexec" --oversubscribe -n 3 "$@"; }
fail() { echo "FAIL: $*"; exit 1; }
# The rows without what differs between runs (wall times and timestamps).
rows() { "$morphex" ls --db "$1" --json --descriptors | sed -E 's/"(indexed_at|seconds)":[^,]*,//g'; }

"$morphex" generate "$dir/coll" --per-class 2 --seed 7 > /dev/null || fail "generate"
"$morphex" index "$dir/coll/*.off" --db "$dir/one.sqlite" --pipeline "$pipeline" --quiet \
  > "$dir/one.txt" || fail "single-process index: $(cat "$dir/one.txt")"
out=$(mpi "$morphex" index "$dir/coll/*.off" --db "$dir/mpi.sqlite" --pipeline "$pipeline" --quiet --json) \
  || fail "mpirun index: $out"
echo "$out"
echo "$out" | grep -q '"indexed":12' || fail "expected 12 meshes indexed"
echo "$out" | grep -q '"processes":3' || fail "expected 3 processes"
[ "$(rows "$dir/one.sqlite")" = "$(rows "$dir/mpi.sqlite")" ] || {
  diff <(rows "$dir/one.sqlite") <(rows "$dir/mpi.sqlite") | head -5
  fail "the MPI index differs from the single-process one"
}
[ "$(rows "$dir/mpi.sqlite" | grep -c '"descriptors":{"combined"')" -eq 12 ] || fail "descriptors missing"

# An index started by one process (4 meshes) is finished by three; a re-run has nothing to do.
"$morphex" index "$dir/coll/bar-*.off" "$dir/coll/ell-*.off" --db "$dir/resume.sqlite" \
  --pipeline "$pipeline" --quiet > /dev/null || fail "partial index"
out=$(mpi "$morphex" index "$dir/coll/*.off" --db "$dir/resume.sqlite" --pipeline "$pipeline" --quiet) \
  || fail "mpirun resume: $out"
echo "$out" | grep -q "indexed 8 meshes (4 already up to date, 0 failed)" || fail "resume: $out"
[ "$(rows "$dir/one.sqlite")" = "$(rows "$dir/resume.sqlite")" ] || fail "the resumed index differs"
out=$(mpi "$morphex" index "$dir/coll/*.off" --db "$dir/resume.sqlite" --pipeline "$pipeline" --quiet)
echo "$out" | grep -q "indexed 0 meshes (12 already up to date, 0 failed)" || fail "re-run: $out"
# One MPI process stores what a plain run stores (it takes the single-process path).
out=$(ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" "$mpiexec" -n 1 "$morphex" index "$dir/coll/*.off" \
  --db "$dir/single.sqlite" --pipeline "$pipeline" --quiet) || fail "mpirun -n 1: $out"
echo "$out" | grep -q "indexed 12 meshes (0 already up to date, 0 failed)" || fail "-n 1: $out"
[ "$(rows "$dir/one.sqlite")" = "$(rows "$dir/single.sqlite")" ] || fail "the -n 1 index differs"

# An index rank 0 cannot open stops every rank (none is left waiting) with the error.
out=$(timeout 120 env ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" "$mpiexec" --oversubscribe -n 3 "$morphex" index "$dir/coll/*.off" \
  --db "$dir/no/such/folder/x.sqlite" --pipeline "$pipeline" --quiet 2>&1)
code=$?
[ $code -ne 0 ] && [ $code -ne 124 ] || fail "an unopenable index: exit $code (124: a rank hung)"
echo "$out" | grep -q "x.sqlite: cannot open the index database" || fail "no error message: $out"
echo "PASS: 3 MPI ranks stored the single-process rows; resume and re-run as expected"
