#!/usr/bin/env bash
# The index as a collection manager: absolute paths, failed meshes skipped until --retry-failed,
# a changed file described again, `ls` (text, --failed, --json), `rm` by name and by path (an
# unknown or ambiguous name removes nothing, exit 2), --quiet and --json.
# Usage: index_manage.sh MORPHEX PIPELINE DATA_DIR DIR
set -u
morphex=$1 pipeline=$2 data=$3 dir=$4
rm -rf "$dir" && mkdir -p "$dir/a" "$dir/b"
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # fail, expect
cp "$data/unit_cube.off" "$dir/a/cube.off"
cp "$data/third_cube_exact.off" "$dir/b/cube.off"  # same name, another folder
cp "$data/open_cube.off" "$dir/a/open.off"
cd "$dir" || exit 1
db=index.sqlite

# Relative inputs are recorded by absolute path; a failure is recorded and reported (exit 1).
expect 1 "indexed 2 meshes \(0 already up to date, 1 failed\)" \
  "$morphex" index a/cube.off b/cube.off a/open.off --db $db --pipeline "$pipeline" --no-repair
expect 0 "cube +ok +12 +no .* $dir/a/cube.off" "$morphex" ls --db $db
expect 0 "open +failed .*$dir/a/open.off" "$morphex" ls --db $db
# A re-run skips the failure (exit 0, says so); --retry-failed describes it again (exit 1).
expect 0 "indexed 0 meshes \(2 already up to date, 0 failed\).*1 meshes failed before" \
  "$morphex" index a/*.off b/*.off --db $db --pipeline "$pipeline" --no-repair
expect 1 "indexed 0 meshes \(2 already up to date, 1 failed\)" \
  "$morphex" index a/*.off b/*.off --db $db --pipeline "$pipeline" --no-repair --retry-failed
expect 0 "error: pipeline\[0\] \(read\).*not closed" "$morphex" ls --db $db --failed
[ "$("$morphex" ls --db $db --failed --json | wc -l)" -eq 1 ] || fail "ls --failed --json: one line"
# A changed file is described again, and only it.
echo "# edited" >> a/cube.off
expect 0 "indexed 1 meshes \(1 already up to date, 0 failed\)" \
  "$morphex" index a/cube.off b/cube.off --db $db --pipeline "$pipeline" --no-repair
# --quiet prints no progress; --json gives the summary as one object.
out=$("$morphex" index a/cube.off --db $db --pipeline "$pipeline" --no-repair --quiet 2>&1 >/dev/null)
[ -z "$out" ] || fail "--quiet printed: $out"
expect 0 '^\{"db":"index.sqlite".*"indexed":0.*"skipped":1' \
  "$morphex" index a/cube.off --db $db --pipeline "$pipeline" --no-repair --json --quiet
# rm: an ambiguous name or an unknown one removes nothing (exit 2); a path or a unique name does.
expect 2 "cube: 2 indexed meshes have this name \(give the path\)" "$morphex" rm --db $db cube
expect 2 "nosuch: no indexed mesh has this name or path" "$morphex" rm --db $db open nosuch
expect 0 "open +failed" "$morphex" ls --db $db
expect 0 "removed 2 meshes" "$morphex" rm --db $db b/cube.off open
out=$("$morphex" ls --db $db --json)
[ "$(echo "$out" | wc -l)" -eq 1 ] && echo "$out" | grep -q "\"path\":\"$dir/a/cube.off\"" ||
  fail "after rm, only a/cube.off should remain: $out"
echo "PASS"
