#!/usr/bin/env bash
# `morphex describe` runs the describe stage (read, solidify unless --no-repair, describe): its
# description equals the describe stage's report in `morphex run` on the same pipeline, curve for
# curve and vector for vector (issue 45), for a valid solid and for a mesh solidify repairs.
# Usage: describe_stage.sh MORPHEX DATA_DIR DIR
set -u
morphex=$1 data=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir"
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # fail, expect
cd "$dir" || exit 1

for mesh in unit_cube crossing_cubes; do
  cat > p.json <<JSON
{"pipeline": [{"type": "read", "path": "\${input}"}, {"type": "solidify"},
              {"type": "describe", "scales": 3, "d2_samples": 1000, "d2_bins": 16}]}
JSON
  "$morphex" describe --json --scales 3 --d2-samples 1000 --d2-bins 16 "$data/$mesh.off" \
    > described.json || fail "describe $mesh"
  "$morphex" run p.json --input "$data/$mesh.off" --report report.json > /dev/null ||
    fail "run $mesh"
  python3 - described.json report.json <<'PY' || fail "$mesh: describe and the describe stage differ"
import json, sys
described = json.load(open(sys.argv[1]))
stages = json.load(open(sys.argv[2]))["inputs"][0]["stages"]
stage = stages[-1]
assert stage["type"] == "describe", stage["type"]
assert described["vectors"] == stage["descriptors"], "vectors"
assert described["settings"] == stage["descriptor_settings"], "settings"
for key in ("scale_length", "thickness", "filtered_facets", "simplified", "open_radii",
            "close_radii", "granulometry", "pattern_spectrum", "anti_granulometry",
            "opening_residue", "closing_residue", "components", "d2"):
    assert described[key] == stage[key], key
solidify = stages[1]["solidify"]
assert described.get("solidify") == (solidify if solidify["changed"] else None), "solidify"
PY
done
echo ok
