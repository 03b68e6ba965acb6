#!/usr/bin/env bash
# `morphex index` killed with SIGKILL midway keeps every mesh it committed; the re-run indexes only
# the rest. Waits until at least one mesh is queryable, then kills the indexer.
set -u
morphex=$1 pipeline=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir"
"$morphex" generate "$dir/coll" --per-class 1 --seed 5 > /dev/null || exit 1
"$morphex" index "$dir/coll/*.off" --db "$dir/index.sqlite" --pipeline "$pipeline" > /dev/null 2>&1 &
pid=$!
committed=""
for _ in $(seq 1 600); do
  for name in bar-0 ell-0 tee-0 plus-0 frame-0 steps-0; do
    if "$morphex" query --db "$dir/index.sqlite" "$name" -k 1 --json > /dev/null 2>&1; then
      committed=$name
      break 2
    fi
  done
  sleep 0.1
done
kill -9 $pid 2> /dev/null
wait $pid 2> /dev/null
[ -n "$committed" ] || { echo "nothing was committed"; exit 1; }
out=$("$morphex" index "$dir/coll/*.off" --db "$dir/index.sqlite" --pipeline "$pipeline")
echo "$out"
indexed=$(echo "$out" | sed -n 's/.*indexed \([0-9]*\) meshes (\([0-9]*\) already up to date, 0 failed).*/\1 \2/p')
[ -n "$indexed" ] || { echo "unexpected summary"; exit 1; }
set -- $indexed
[ "$2" -ge 1 ] && [ $(($1 + $2)) -eq 6 ] || { echo "expected the committed meshes to be kept"; exit 1; }
echo "kept $2 committed meshes, indexed the other $1"
