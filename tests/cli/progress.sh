#!/usr/bin/env bash
# Progress of one long operation: on a terminal (a pseudo-terminal from script(1)) a bar with the
# share done and the step, then cleared; in a log (stderr a file) nothing; the result is the same.
# Usage: progress.sh MORPHEX DATA_DIR WORK_DIR
set -u
mx=$1 data=$2 work=$3
. "$(dirname "$0")/lib.sh"
rm -rf "$work" && mkdir -p "$work" || fail "cannot make $work"
command -v script >/dev/null || fail "script(1) (bsdutils) is missing"

# Delay 0: the bar shows at once, whatever the machine's speed.
run="MORPHEX_PROGRESS_AFTER=0 $mx open $data/unit_cube.off --se octahedron:r=1/4 -o $work/tty.off"
script -qfec "$run" /dev/null >"$work/tty.log" 2>&1 || fail "open under a terminal failed"
grep -aq 'open \[' "$work/tty.log" || fail "no bar on the terminal: $(cat -v "$work/tty.log")"
grep -aEq '100%' "$work/tty.log" || fail "the bar never reached 100%: $(cat -v "$work/tty.log")"
grep -aEq 'erosion|dilation' "$work/tty.log" || fail "the bar does not name the step: $(cat -v "$work/tty.log")"
# Cleared at the end: the last thing on the line is the erase sequence, not a bar.
tail -c 20 "$work/tty.log" | grep -aq $'\033\[K' || fail "the bar was not cleared"

# In a log: nothing on stderr, the same result.
MORPHEX_PROGRESS_AFTER=0 "$mx" open "$data/unit_cube.off" --se octahedron:r=1/4 \
  -o "$work/log.off" 2>"$work/stderr.log" || fail "open in a log failed"
[ ! -s "$work/stderr.log" ] || fail "progress in a log: $(cat -v "$work/stderr.log")"
cmp -s <(grep -v "^#" "$work/tty.off") <(grep -v "^#" "$work/log.off") ||
  fail "the result differs with a terminal"

# The default delay: a quick operation shows no bar even on a terminal.
script -qfec "$mx bool union $data/unit_cube.off $data/third_cube_exact.off -o $work/u.off" \
  /dev/null >"$work/quick.log" 2>&1 || fail "bool under a terminal failed"
! grep -aq 'union \[' "$work/quick.log" || fail "a bar for a quick operation: $(cat -v "$work/quick.log")"
echo "PASS"
