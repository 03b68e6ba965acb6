#!/usr/bin/env bash
# The repair's work budget (issue 44, item 5): a soup of 500 crossing tetrahedra (149 KB, made
# here) is refused by `morphex repair` at once (exit 2, "repair would exceed its budget") instead
# of taking gigabytes; `index`, which repairs by default, records it as failed and goes on.
# Usage: repair_budget.sh MORPHEX PIPELINE DATA_DIR DIR [CAP]   (CAP: "--max-memory-mb N", or empty)
set -u
morphex=$1 pipeline=$2 data=$3 dir=$4 cap=${5:-}
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || exit 1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # fail, expect
# 500 tetrahedra of random doubles in one box, each closed: faces meet ~100 others each.
awk 'BEGIN {
  srand(7); n = 500; print "OFF"; print 4 * n, 4 * n, 0
  for (t = 0; t < n; ++t) {
    x = rand(); y = rand(); z = rand(); s = 1 + 3 * rand()
    for (k = 0; k < 4; ++k) printf "%.17g %.17g %.17g\n", x + s * rand(), y + s * rand(), z + s * rand()
  }
  for (t = 0; t < n; ++t) {
    v = 4 * t
    print 3, v, v + 2, v + 1; print 3, v, v + 1, v + 3; print 3, v + 1, v + 2, v + 3; print 3, v, v + 3, v + 2
  }
}' > soup.off
cp "$data/unit_cube.off" cube.off
# The cap: should the budget fail, the test fails quickly instead of swapping.
expect 2 "soup.off: cannot repair: repair would exceed its budget: .* pairs of its 2000 faces" \
  "$morphex" $cap repair soup.off -o repaired.off
[ ! -e repaired.off ] || fail "a refused repair wrote its output"
expect 1 "soup.off: .*repair would exceed its budget.*indexed 1 meshes \(0 already up to date, 1 failed\)" \
  "$morphex" $cap index soup.off cube.off --db index.sqlite --pipeline "$pipeline"
expect 0 "soup +failed" "$morphex" ls --db index.sqlite
echo "PASS"
