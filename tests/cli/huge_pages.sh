#!/usr/bin/env bash
# `morphex` restarts once with glibc's malloc asking for transparent huge pages
# (morphex/internal/huge_pages.h) where that pays: the build uses glibc's malloc ($4 = glibc), the
# kernel gives huge pages only when asked ("madvise") and the input files add up to 512 KiB or
# more, 16 KiB for a morphology.
# Otherwise, and when the user's GLIBC_TUNABLES already says glibc.malloc.hugetlb, the process runs
# as started. Either way the command sees its arguments and its standard input unchanged.
set -u
morphex=$1 data=$2 dir=$3 allocator=$4
rm -rf "$dir" && mkdir -p "$dir"
mode=$(cat /sys/kernel/mm/transparent_hugepage/enabled 2>/dev/null || echo none)
restarts=no
[ "$allocator" = glibc ] && [[ "$mode" == *"[madvise]"* ]] && restarts=yes
echo "allocator $allocator, transparent huge pages: $mode, restart expected: $restarts"
# Valid meshes of more than 1 MiB and of about 20 KiB: the unit cube with a long comment after it.
big="$dir/big_cube.off" medium="$dir/medium_cube.off"
{ cat "$data/unit_cube.off"; for i in $(seq 20000); do
  echo "# a comment line long enough to make this file weigh more than one mebibyte"; done; } >"$big"
{ cat "$data/unit_cube.off"; for i in $(seq 260); do
  echo "# a comment line long enough to make this file weigh more than one mebibyte"; done; } >"$medium"
fail() { echo "FAIL: $*"; exit 1; }
# The variables this test is about, from environment_while_reading's line.
shown() { grep -o -E 'GLIBC_TUNABLES=[^:]*(:glibc[^:]*)*|MORPHEX_RESTARTED[^:]*' <<<"$1" | tr '\n' ' '; }

# Runs `morphex check FILE -` (or, with a third argument, `morphex minkowski FILE - -o SUM`) with
# the given GLIBC_TUNABLES ("unset" for none) while it waits for its standard input; prints the
# environment of the process as it then runs, its strings joined by ':' between leading and
# trailing ones (glibc ends each tunable's value in place with a NUL as it reads it, so its
# separators show as either), and checks that the mesh given afterwards is read and used.
environment_while_reading() {
  local tunables=$1 file=$2 command=${3:-check} fifo="$dir/stdin" pid state="" i
  local args=(check "$file" -)
  [ "$command" = minkowski ] && args=(minkowski "$file" - -o "$dir/sum.off") && rm -f "$dir/sum.off"
  rm -f "$fifo" && mkfifo "$fifo"
  exec 3<>"$fifo"  # held open for writing, so that the reader's open does not block
  if [ "$tunables" = unset ]; then
    env -u GLIBC_TUNABLES -u MORPHEX_RESTARTED_FOR_HUGE_PAGES "$morphex" "${args[@]}" \
      <"$fifo" 3>&- \
      >"$dir/out" 2>&1 &
  else
    env -u MORPHEX_RESTARTED_FOR_HUGE_PAGES GLIBC_TUNABLES="$tunables" "$morphex" "${args[@]}" \
      <"$fifo" 3>&- >"$dir/out" 2>&1 &
  fi
  pid=$!
  # Blocked reading its standard input: sleeping with morphex's command line.
  for i in $(seq 100); do
    state=$(awk '{print $3}' "/proc/$pid/stat" 2>/dev/null)
    if [ "$state" = S ] && tr '\0' ' ' <"/proc/$pid/cmdline" | grep -q " ${args[*]} "; then break; fi
    sleep 0.05
  done
  sleep 0.2
  { printf ':' && tr '\0' ':' <"/proc/$pid/environ"; } >"$dir/environ"
  [ "$(tr '\0' ' ' <"/proc/$pid/cmdline")" = "$morphex ${args[*]} " ] ||
    fail "command line changed: $(tr '\0' ' ' <"/proc/$pid/cmdline")"
  cat "$data/unit_cube.off" >&3
  exec 3>&-
  wait "$pid" || fail "morphex ${args[*]} failed: $(cat "$dir/out")"
  if [ "$command" = minkowski ]; then
    head -1 "$dir/sum.off" | grep -q OFF || fail "no sum written: $(cat "$dir/out")"
  else
    [ "$(grep -c "valid closed solid" "$dir/out")" = 2 ] ||
      fail "file or standard input not read: $(cat "$dir/out")"
  fi
  cat "$dir/environ"
  echo
}

marker=":MORPHEX_RESTARTED_FOR_HUGE_PAGES=1:"
env_now=$(environment_while_reading unset "$big") || { echo "$env_now"; exit 1; }
if [ $restarts = yes ]; then
  [[ "$env_now" == *":GLIBC_TUNABLES=glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=33554432:glibc.malloc.top_pad=16777216:"* ]] ||
    fail "not restarted: $(shown "$env_now")"
  [[ "$env_now" == *"$marker"* ]] || fail "no restart marker: $(shown "$env_now")"
else
  [[ "$env_now" != *GLIBC_TUNABLES* && "$env_now" != *"$marker"* ]] || fail "restarted: $(shown "$env_now")"
fi

# Other tunables are kept, ours appended.
env_now=$(environment_while_reading glibc.malloc.arena_max=4 "$big") || { echo "$env_now"; exit 1; }
if [ $restarts = yes ]; then
  [[ "$env_now" == *":GLIBC_TUNABLES=glibc.malloc.arena_max=4:glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=33554432:"* ]] ||
    fail "tunables not kept: $(shown "$env_now")"
else
  [[ "$env_now" == *":GLIBC_TUNABLES=glibc.malloc.arena_max=4:"* && "$env_now" != *hugetlb* ]] ||
    fail "tunables changed: $(shown "$env_now")"
fi

# The user's own choice stands.
env_now=$(environment_while_reading glibc.malloc.hugetlb=0 "$big") || { echo "$env_now"; exit 1; }
[[ "$env_now" == *":GLIBC_TUNABLES=glibc.malloc.hugetlb=0:"* && "$env_now" != *"$marker"* ]] ||
  fail "the user's glibc.malloc.hugetlb=0 overridden: $(shown "$env_now")"

# Small inputs: the restart would cost more than it saves.
env_now=$(environment_while_reading unset "$data/unit_cube.off") || { echo "$env_now"; exit 1; }
[[ "$env_now" != *"$marker"* ]] || fail "restarted for a small input: $(shown "$env_now")"
env_now=$(environment_while_reading unset "$medium") || { echo "$env_now"; exit 1; }
[[ "$env_now" != *"$marker"* ]] || fail "restarted to check 20 KiB: $(shown "$env_now")"
# A morphology touches far more memory per input byte: 20 KiB pays.
env_now=$(environment_while_reading unset "$medium" minkowski) || { echo "$env_now"; exit 1; }
if [ $restarts = yes ]; then
  [[ "$env_now" == *"$marker"* ]] || fail "not restarted for a morphology of 20 KiB: $(shown "$env_now")"
else
  [[ "$env_now" != *"$marker"* ]] || fail "restarted: $(shown "$env_now")"
fi

# A file command's result and exit code are those of a process that was not restarted.
"$morphex" check "$big" >"$dir/a" 2>&1
a=$?
GLIBC_TUNABLES=glibc.malloc.hugetlb=0 "$morphex" check "$big" >"$dir/b" 2>&1
b=$?
[ $a -eq 0 ] && [ $b -eq 0 ] && cmp -s "$dir/a" "$dir/b" || fail "results differ: $(cat "$dir/a" "$dir/b")"
"$morphex" check "$data/open_cube.off" >/dev/null 2>&1
[ $? -eq 1 ] || fail "exit code of an invalid mesh changed"
echo PASS
