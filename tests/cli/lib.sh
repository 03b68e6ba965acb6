# Helpers the command-line test scripts share (sourced, not run): fail stops the script with a
# message; expect CODE REGEX COMMAND... checks a command's exit code and that its stdout+stderr
# (newlines included) match REGEX, and leaves that output in $out.
fail() { echo "FAIL: $*"; exit 1; }
expect() {
  local code=$1 regex=$2; shift 2
  out=$("$@" 2>&1); local got=$?
  [ "$got" -eq "$code" ] || fail "exit $got (expected $code): $*"$'\n'"$out"
  echo "$out" | grep -Ezq -- "$regex" || fail "no /$regex/ in the output of: $*"$'\n'"$out"
}
