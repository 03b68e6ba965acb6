#!/usr/bin/env bash
# Index files are untrusted input (issue 44, items 7-10): a stored pipeline runs only descriptor
# stages; a file that is not a morphex index (another program's database, an empty or non-SQLite
# file) or a damaged one is refused with exit 2 and left unchanged; read-only commands never
# write; meshes described under different settings are not compared; non-finite stored
# descriptors are refused.
# Usage: index_untrusted.sh MORPHEX PIPELINE DATA_DIR DIR
set -u
morphex=$1 pipeline=$2 data=$3 dir=$4
rm -rf "$dir" && mkdir -p "$dir"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }  # go on: every case is reported
expect() {  # expect CODE REGEX COMMAND...: exit code and a match in stdout+stderr
  local code=$1 regex=$2; shift 2
  out=$("$@" 2>&1); local got=$?
  [ "$got" -eq "$code" ] || { fail "exit $got (expected $code): $*"$'\n'"$out"; return; }
  echo "$out" | grep -Ezq -- "$regex" || fail "no /$regex/ in the output of: $*"$'\n'"$out"
}
unchanged() {  # unchanged FILE HASH: the file's bytes are as before, and nothing was logged
  # (a reader of an index in WAL mode may leave SQLite's empty -wal and -shm files)
  [ "$(sha256sum < "$1")" = "$2" ] || fail "$1 was changed"
  [ ! -s "$1-wal" ] && [ ! -e "$1-journal" ] || fail "$1 got a journal"
}
sql() { sqlite3 "$@" || fail "sqlite3 $*"; }
cd "$dir" || exit 1
command -v sqlite3 > /dev/null || { echo "sqlite3 (the SQLite shell) is needed"; exit 1; }
cp "$data/unit_cube.off" cube.off
cp "$data/third_cube_exact.off" third.off
expect 0 "indexed 2 meshes" "$morphex" index cube.off third.off --db good.sqlite --pipeline "$pipeline"

# 7: a stored pipeline with a write stage is refused before anything runs (no file written).
cp good.sqlite crafted.sqlite
sql crafted.sqlite "UPDATE meta SET value = '{\"pipeline\": [{\"type\": \"read\", \"path\": \"\${input}\"}, {\"type\": \"write\", \"path\": \"$dir/pwned.off\"}, {\"type\": \"describe\", \"scales\": 2, \"closings\": false, \"d2_samples\": 256}]}' WHERE key = 'pipeline'"
expect 2 "stored pipeline is refused.*'write' is not one" "$morphex" query --db crafted.sqlite cube.off
[ ! -e pwned.off ] || fail "the stored pipeline wrote a file"
# ... so is a read of another file than the query's mesh
sql crafted.sqlite "UPDATE meta SET value = '{\"pipeline\": [{\"type\": \"read\", \"path\": \"/etc/passwd\"}, {\"type\": \"describe\"}]}' WHERE key = 'pipeline'"
expect 2 "reads only" "$morphex" query --db crafted.sqlite cube.off
# and `index` refuses such a pipeline from the start
cat > writes.json <<'JSON'
{"pipeline": [{"type": "read", "path": "${input}"}, {"type": "write", "path": "copy.off"},
              {"type": "describe", "scales": 2}]}
JSON
expect 2 "'write' is not one" "$morphex" index cube.off --db never.sqlite --pipeline writes.json
[ ! -e copy.off ] && [ ! -e never.sqlite ] || fail "a refused pipeline wrote"

# 8: another program's database with a `meshes` table, an empty file, a text file.
sql foreign.sqlite "CREATE TABLE meshes(id INTEGER PRIMARY KEY, name TEXT, path TEXT)"
sql foreign.sqlite "INSERT INTO meshes(name, path) VALUES ('a', 'b')"
hash=$(sha256sum < foreign.sqlite)
for command in ls "query cube" "evaluate --labels $data/unindexed-labels.cla" "rm cube"; do
  # shellcheck disable=SC2086
  expect 2 "foreign.sqlite: not a morphex index" "$morphex" $command --db foreign.sqlite
  unchanged foreign.sqlite "$hash"
done
expect 2 "foreign.sqlite: not a morphex index" "$morphex" index cube.off --db foreign.sqlite
unchanged foreign.sqlite "$hash"
sql other.sqlite "PRAGMA application_id = 42; CREATE TABLE t(x)"
expect 2 "not a morphex index \(an SQLite database of another program" "$morphex" ls --db other.sqlite
: > empty.sqlite
expect 2 "empty.sqlite: not a morphex index \(an empty file\)" "$morphex" ls --db empty.sqlite
[ ! -s empty.sqlite ] || fail "ls wrote into an empty file"
echo "not a database at all, just some text that is long enough to be read as a header....." > text.sqlite
expect 2 "text.sqlite: not a morphex index" "$morphex" ls --db text.sqlite
expect 2 "text.sqlite: not a morphex index" "$morphex" index cube.off --db text.sqlite
# ls of a sound index leaves it as it was
cp good.sqlite copy.sqlite && rm -f copy.sqlite-wal copy.sqlite-shm
hash=$(sha256sum < copy.sqlite)
expect 0 "cube +ok" "$morphex" ls --db copy.sqlite
expect 0 "third" "$morphex" query --db copy.sqlite cube -k 1
unchanged copy.sqlite "$hash"

# 9: on read-only storage (a folder another user cannot write, when run as root) an index in WAL
# mode can still be listed, queried and evaluated. The other user gets copies in a folder of its
# own reach: the build tree may sit under a private folder (a 0700 home or temporary folder).
if [ "$(id -u)" -eq 0 ] && command -v setpriv > /dev/null; then
  shared=$(mktemp -d) && chmod 755 "$shared" && mkdir "$shared/readonly" || fail "mktemp"
  cp good.sqlite "$shared/readonly/" && cp "$morphex" "$shared/morphex" &&
    cp "$data/unindexed-labels.cla" "$shared/labels.cla" || fail "copies for nobody"
  chmod 755 "$shared/readonly" "$shared/morphex" && chmod 644 "$shared/readonly/good.sqlite" \
    "$shared/labels.cla"
  as_nobody() { (cd "$shared/readonly" && setpriv --reuid=65534 --regid=65534 --clear-groups "$@"); }
  expect 0 "cube +ok" as_nobody "$shared/morphex" ls --db good.sqlite
  expect 0 "third" as_nobody "$shared/morphex" query --db good.sqlite cube -k 1
  expect 2 "none of its 2 models is in the index" \
    as_nobody "$shared/morphex" evaluate --db good.sqlite --labels "$shared/labels.cla"
  rm -rf "$shared"
fi

# 9: a damaged index (garbage pages, a damaged header, a truncated file): exit 2, unchanged.
cp good.sqlite damaged.sqlite && sql damaged.sqlite "PRAGMA journal_mode = DELETE" > /dev/null
size=$(stat -c %s damaged.sqlite)
[ "$size" -ge 8192 ] || fail "the index is too small to damage ($size bytes)"
head -c 4096 /dev/urandom | dd of=damaged.sqlite bs=4096 seek=1 conv=notrunc status=none
hash=$(sha256sum < damaged.sqlite)
for command in ls "rm cube" "evaluate --labels $data/unindexed-labels.cla"; do
  # shellcheck disable=SC2086
  expect 2 "damaged.sqlite: .*damaged" "$morphex" $command --db damaged.sqlite
  unchanged damaged.sqlite "$hash"
done
expect 2 "damaged.sqlite: .*damaged" "$morphex" index cube.off --db damaged.sqlite
unchanged damaged.sqlite "$hash"
cp good.sqlite header.sqlite && sql header.sqlite "PRAGMA journal_mode = DELETE" > /dev/null
printf 'garbage garbage!' | dd of=header.sqlite bs=1 seek=0 conv=notrunc status=none
expect 2 "header.sqlite: not a morphex index" "$morphex" ls --db header.sqlite
cp good.sqlite truncated.sqlite && sql truncated.sqlite "PRAGMA journal_mode = DELETE" > /dev/null
truncate -s 5000 truncated.sqlite
expect 2 "truncated.sqlite: .*(damaged|not a morphex index)" "$morphex" ls --db truncated.sqlite

# 10: meshes described under other settings are not mixed: the second run refuses (nothing
# written), and an index that mixes them (a crafted one) is refused by query and evaluate.
cat > other.json <<'JSON'
{"pipeline": [{"type": "read", "path": "${input}"},
              {"type": "describe", "scales": 3, "closings": false, "d2_samples": 256}]}
JSON
cp good.sqlite mixed.sqlite
expect 2 "1 indexed meshes \(first .*third.off\) were described under other settings" \
  "$morphex" index cube.off --db mixed.sqlite --pipeline other.json
expect 0 "cube +ok" "$morphex" ls --db mixed.sqlite
# every mesh described again under the new settings: allowed
expect 0 "indexed 2 meshes" "$morphex" index cube.off third.off --db mixed.sqlite --pipeline other.json
sql mixed.sqlite "UPDATE meshes SET settings = 'crafted' WHERE name = 'cube'"
expect 2 "described under 2 different settings" "$morphex" query --db mixed.sqlite third
expect 2 "described under 2 different settings" "$morphex" query --db mixed.sqlite cube.off
# NaN stored as a descriptor is refused, not ranked first
cp good.sqlite nan.sqlite
sql nan.sqlite "UPDATE descriptors SET vector = CAST(X'000000000000F87F' || substr(vector, 9) AS BLOB) WHERE kind = 'combined' AND mesh_id = (SELECT id FROM meshes WHERE name = 'third')"
expect 2 "nan.sqlite: .*'combined' descriptor of third holds a value that is not a finite number" \
  "$morphex" query --db nan.sqlite cube -k 1
[ "$failures" -eq 0 ] || { echo "$failures failures"; exit 1; }
echo "PASS"
