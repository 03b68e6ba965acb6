#!/usr/bin/env bash
# scripts/bench-check-ab: two bench_check builds alternately (here one build twice, on small
# generated inputs). Timings are not asserted; the table, the JSON rows and the refusals are.
# Usage: bench_check_ab.sh BUILD_TOOLS_DIR SOURCE_DIR WORK_DIR
set -u
tools=$1 src=$2 work=$3
. "$(dirname "$0")/lib.sh"
ab="$src/scripts/bench-check-ab"
rm -rf "$work" && mkdir -p "$work" || fail "cannot make $work"

expect 0 "fan-prism:40 +156 .*icosphere:1 +80 .*median new/old [0-9.]+ over 2 inputs" \
  python3 "$ab" --rounds 2 --runs 1 --json "$work/ab.json" "$tools/bench_check" \
  "$tools/bench_check" fan-prism:40 icosphere:1
python3 - "$work/ab.json" <<'PY' || fail "ab.json: unexpected rows"
import json, sys
rows = json.load(open(sys.argv[1]))["rows"]
assert [r["input"] for r in rows] == ["fan-prism:40", "icosphere:1"], rows
assert all(len(r["old_rounds"]) == 2 and len(r["new_rounds"]) == 2 for r in rows), rows
assert all(r["old_seconds"] == min(r["old_rounds"]) > 0 for r in rows), rows
assert all(abs(r["new_over_old"] - r["new_seconds"] / r["old_seconds"]) < 1e-12 for r in rows)
PY
[ ! -e "$work/ab.json.partial" ] || fail "a partial JSON file was left behind"
# --whole: the whole check (validity and the exact volume), said so in the JSON.
expect 0 "icosphere:1 +80 .*median new/old [0-9.]+ over 1 inputs" \
  python3 "$ab" --whole --rounds 1 --runs 1 --json "$work/whole.json" "$tools/bench_check" \
  "$tools/bench_check" icosphere:1
python3 - "$work/ab.json" "$work/whole.json" <<'PY' || fail "the JSON files do not say what they timed"
import json, sys
assert json.load(open(sys.argv[1]))["measure"] == "validity"
assert json.load(open(sys.argv[2]))["measure"] == "whole check"
PY
# A build that is not there: exit 2 and its name, before anything runs.
expect 2 "bench-check-ab: $work/none: no such bench_check" \
  python3 "$ab" "$work/none" "$tools/bench_check" fan-prism:40
# --json naming an input: refused before anything runs, the input left as it was.
cp "$src/tests/data/unit_cube.off" "$work/cube.off"
expect 2 "bench-check-ab: --json $work/cube.off is also an input" \
  python3 "$ab" --json "$work/cube.off" "$tools/bench_check" "$tools/bench_check" "$work/cube.off"
cmp -s "$work/cube.off" "$src/tests/data/unit_cube.off" || fail "the input was changed"
echo PASS
