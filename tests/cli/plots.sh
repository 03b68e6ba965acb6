#!/usr/bin/env bash
# Plots as files (issue 46): `evaluate --plot` writes the precision-recall curves of every stored
# descriptor and `describe --plot` a description's curves, as SVG that an XML parser reads, with one
# line per series and the legend's names; --per-class adds the classes' tables; outputs are checked
# before any work like every other output.
# Usage: plots.sh MORPHEX PIPELINE DATA_DIR DIR
set -u
morphex=$1 pipeline=$2 data=$3 dir=$4
rm -rf "$dir" && mkdir -p "$dir"
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # fail, expect
cd "$dir" || exit 1

# check_svg FILE CHARTS LINES NAMES...: well-formed SVG with CHARTS panels, LINES line paths and
# these names in its text.
check_svg() {
  python3 - "$@" <<'EOF' || fail "$1: not the SVG expected"
import sys, xml.etree.ElementTree as ET
path, charts, lines, names = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
ns = {"s": "http://www.w3.org/2000/svg"}
root = ET.parse(path).getroot()
assert root.tag == "{http://www.w3.org/2000/svg}svg", root.tag
assert root.get("viewBox") == "0 0 %s %s" % (root.get("width"), root.get("height"))
found = root.findall(".//s:g[@class='chart']", ns)
assert len(found) == charts, "%d charts" % len(found)
paths = root.findall(".//s:path[@class='line']", ns)
assert len(paths) == lines, "%d lines" % len(paths)
text = " ".join("".join(t.itertext()) for t in root.iter("{http://www.w3.org/2000/svg}text"))
for name in names:
    assert name in text, "no %r in %r" % (name, text)
EOF
}

expect 0 "wrote 12 meshes" "$morphex" generate coll --per-class 2 --seed 5
expect 0 "indexed 12 meshes" "$morphex" index coll --db index.sqlite --pipeline "$pipeline" --quiet

# evaluate --plot: one curve per stored descriptor, named in the legend; the table is unchanged
expect 0 "combined .*d2 .*12 labelled models.*wrote pr.svg" \
  "$morphex" evaluate --db index.sqlite --labels coll/labels.cla --plot pr.svg
check_svg pr.svg 1 6 combined morphology granulometry pattern_spectrum spatial d2 recall
before=$(cat pr.svg)
"$morphex" evaluate --db index.sqlite --labels coll/labels.cla --plot pr.svg >/dev/null
[ "$(cat pr.svg)" = "$before" ] || fail "the same evaluation wrote another SVG"
# --plot - writes the SVG on stdout instead of the table
"$morphex" evaluate --db index.sqlite --labels coll/labels.cla --plot - > stdout.svg ||
  fail "evaluate --plot -"
[ "$(cat stdout.svg)" = "$before" ] || fail "--plot - differs from the file"

# --per-class: a table per descriptor in text, per_class (with the class sizes) in JSON, and the
# precision-recall curve in JSON always
expect 0 "per class, combined:.*class \(models\) +Nearest Neighbor.*bar \(2\) .*tee \(2\) " \
  "$morphex" evaluate --db index.sqlite --labels coll/labels.cla --per-class
"$morphex" evaluate --db index.sqlite --labels coll/labels.cla --per-class --json > e.json ||
  fail "evaluate --per-class --json"
python3 - e.json <<'EOF' || fail "evaluate --per-class --json: $(cat e.json)"
import json, sys
j = json.load(open(sys.argv[1]))
d = j["descriptors"]["morphology"]
assert set(d["per_class"]) == {"bar", "ell", "frame", "plus", "steps", "tee"}, d["per_class"]
assert all(c["models"] == 2 and c["queries"] == 2 for c in d["per_class"].values())
pr = d["precision_recall"]
assert pr["recall"] == [k / 20 for k in range(21)] and len(pr["precision"]) == 21
assert all(a >= b for a, b in zip(pr["precision"], pr["precision"][1:]))  # interpolated
EOF

# describe --plot: granulometry, anti-granulometry, pattern spectrum, D2 (no closings: three)
expect 0 "granulometry +1 1 1.*wrote cube.svg" \
  "$morphex" describe "$data/unit_cube.off" --scales 3 --d2-samples 500 --plot cube.svg
check_svg cube.svg 4 2 "unit_cube" Granulometry Anti-granulometry "Pattern spectrum" D2 \
  "opening cube half side r / L"
expect 0 '"plot":"open.svg"' "$morphex" describe "$data/unit_cube.off" --scales 2 --no-closings \
  --d2-samples 500 --plot open.svg --json
check_svg open.svg 3 1 Granulometry "Pattern spectrum"

# refused before any work: over an input, in a missing folder, and --plot - with --json
expect 2 "refusing to overwrite the input .*unit_cube.off \(--plot\)" \
  "$morphex" describe "$data/unit_cube.off" --plot "$data/unit_cube.off"
expect 2 "refusing to overwrite the labels coll/labels.cla \(--plot\)" \
  "$morphex" evaluate --db index.sqlite --labels coll/labels.cla --plot coll/labels.cla
expect 2 "nosuch/pr.svg: cannot write in the folder nosuch: it does not exist" \
  "$morphex" evaluate --db index.sqlite --labels coll/labels.cla --plot nosuch/pr.svg
expect 2 "--plot - and --json both write to stdout" \
  "$morphex" evaluate --db index.sqlite --labels coll/labels.cla --plot - --json
echo "plots: all checks passed"
