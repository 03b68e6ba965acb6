#!/usr/bin/env bash
# SIGINT during `morphex run`: exit 130, the message, no output and no temporary file left.
set -u
morphex=$1 data=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir"
cat > "$dir/slow.json" <<JSON
{"pipeline": [{"type": "read", "path": "$data/unit_cube.off"},
  {"type": "dilate", "se": "ball:r=1/10,level=3"},
  {"type": "open", "se": "ball:r=1/10,level=3"},
  {"type": "write", "path": "$dir/out.off"}]}
JSON
"$morphex" run "$dir/slow.json" 2> "$dir/stderr" &
pid=$!
sleep 2
kill -INT $pid
wait $pid
code=$?
[ "$code" -eq 130 ] || { echo "exit code $code, expected 130"; cat "$dir/stderr"; exit 1; }
grep -q "interrupted; no partial output was left" "$dir/stderr" || { echo "no message"; exit 1; }
[ ! -e "$dir/out.off" ] || { echo "output written"; exit 1; }
leftover=$(find "$dir" -name '.*.tmp.*' | wc -l)
[ "$leftover" -eq 0 ] || { echo "temporary files left"; exit 1; }
echo "interrupted cleanly"
