#!/usr/bin/env bash
# The libraries only some commands need are loaded when one of those runs, not at every start:
# lib3mf when a 3MF file is met, cpp-httplib (with OpenSSL and brotli) in the module
# morphex_serve_http.so that `serve` loads, Open MPI in the module morphex_mpi.so that an MPI run
# loads. The modules are found beside the executable or in the installed layout (bin/../SUBDIR),
# and a command whose module is missing says which and where it looked, with exit code 1.
# Usage: lazy_libraries.sh MORPHEX DATA DIR MODULE_SUBDIR HAVE_3MF HAVE_MPI
set -u
morphex=$1 data=$2 dir=$3 subdir=$4 have_3mf=$5 have_mpi=$6
rm -rf "$dir" && mkdir -p "$dir"
fail() { echo "FAIL: $*"; exit 1; }
lazy='lib3MF|libcpp-httplib|libssl|libcrypto|libbrotli|libmpi|libopen-rte|libopen-pal'
modules=$(dirname "$morphex")

# Not among the executable's needed libraries...
needed=$(readelf -d "$morphex" | grep NEEDED) || fail "readelf -d $morphex"
grep -E "$lazy" <<<"$needed" && fail "linked at start: $(grep -E -o "$lazy" <<<"$needed" | tr '\n' ' ')"
# ...nor loaded by a command that does not need them (the loader's own account of what it opens).
LD_DEBUG=files "$morphex" check "$data/unit_cube.off" >"$dir/check.out" 2>"$dir/check.ld" ||
  fail "check: $(cat "$dir/check.out")"
grep -E "file=[^ ]*($lazy)" "$dir/check.ld" && fail "a plain check loaded the libraries above"
grep -q "file=libgmp" "$dir/check.ld" || fail "LD_DEBUG=files shows nothing: the test cannot see"

if [ "$have_3mf" = ON ]; then
  LD_DEBUG=files "$morphex" dilate "$data/unit_cube.off" --se cube:r=1/4 -o "$dir/d.3mf" \
    >"$dir/3mf.out" 2>"$dir/3mf.ld" || fail "writing 3MF: $(cat "$dir/3mf.out")"
  grep -q "file=lib3MF.so" "$dir/3mf.ld" || fail "lib3mf was not loaded to write 3MF"
  "$morphex" check "$dir/d.3mf" | grep -q "valid closed solid" || fail "the 3MF does not read back"
fi

# serve: an index to serve, then the executable alone (no module beside it or in bin/../SUBDIR).
"$morphex" index "$data/unit_cube.off" --db "$dir/index.sqlite" --quiet >/dev/null ||
  fail "index for serve"
mkdir -p "$dir/alone/bin" && cp "$morphex" "$dir/alone/bin/"
"$dir/alone/bin/morphex" serve --db "$dir/index.sqlite" --port 0 >"$dir/alone.out" 2>&1
code=$?
[ $code -eq 1 ] || fail "serve without its module: exit code $code, expected 1: $(cat "$dir/alone.out")"
grep -q "morphex_serve_http.so: morphex serve cannot start its HTTP server: not found (looked in $dir/alone/bin" \
  "$dir/alone.out" || fail "serve without its module: $(cat "$dir/alone.out")"
# The installed layout: the module in bin/../SUBDIR is found; the server starts and is stopped.
mkdir -p "$dir/alone/$subdir" && cp "$modules/morphex_serve_http.so" "$dir/alone/$subdir/"
"$dir/alone/bin/morphex" serve --db "$dir/index.sqlite" --port 0 >"$dir/installed.out" 2>&1 &
pid=$!
for _ in $(seq 100); do grep -q "^serving http" "$dir/installed.out" && break; sleep 0.1; done
kill -TERM $pid 2>/dev/null
wait $pid
grep -q "^serving http://127.0.0.1:" "$dir/installed.out" ||
  fail "serve with its module in bin/../$subdir: $(cat "$dir/installed.out")"

if [ "$have_mpi" = ON ]; then
  # As if a launcher had started two processes: the session needs MPI, whose module is missing.
  OMPI_COMM_WORLD_SIZE=2 "$dir/alone/bin/morphex" index "$data/unit_cube.off" \
    --db "$dir/mpi.sqlite" --quiet >"$dir/mpi.out" 2>&1
  code=$?
  [ $code -eq 1 ] || fail "MPI without its module: exit code $code: $(cat "$dir/mpi.out")"
  grep -q "morphex_mpi.so: MPI is not available: not found" "$dir/mpi.out" ||
    fail "MPI without its module: $(cat "$dir/mpi.out")"
  [ ! -e "$dir/mpi.sqlite" ] || fail "an index was written by a run that could not start"
fi
echo PASS
