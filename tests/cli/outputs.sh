#!/usr/bin/env bash
# Issue 44: nothing lost, nothing crashes. Every file a command writes is checked against every
# file it reads and every output folder before any work; failed writes to standard output, deep
# JSON, typos, volumes, help. One group of cases per item of the issue.
# Usage: outputs.sh MORPHEX DATA_DIR DIR ITEM
set -u
morphex=$1 data=$2 dir=$3/$4 item=$4
rm -rf "$dir" && mkdir -p "$dir/sa" "$dir/sb" "$dir/out"
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"  # fail, expect
intact() { cmp -s "$1" "$2" || fail "$1 was changed"; }
cd "$dir" || exit 1
cp "$data/unit_cube.off" a.off
cp "$data/third_cube_exact.off" b.off
cp "$data/unit_cube.off" se.off
ln -s a.off link.off
grow=$data/pipelines/grow.json
case $item in
side_outputs)  # item 1
  expect 2 "morphex: a.off: refusing to overwrite the input a.off \(--stats\)" \
    "$morphex" bool union a.off b.off -o u.off --stats a.off
  intact a.off "$data/unit_cube.off"
  expect 2 "morphex: link.off: refusing to overwrite the input a.off \(--stats\)" \
    "$morphex" bool union a.off b.off -o u.off --stats link.off
  expect 2 "morphex: s.off: --stats and --output name the same file" \
    "$morphex" bool union a.off b.off -o s.off --stats s.off
  [ -e s.off ] && fail "s.off written"
  expect 2 "morphex: se.off: refusing to overwrite the structuring element se.off \(--output\)" \
    "$morphex" dilate a.off --se mesh:path=se.off -o se.off
  intact se.off "$data/unit_cube.off"
  expect 2 "pipeline\[2\].path: would overwrite the structuring element of pipeline\[1\].se" \
    "$morphex" run "$data/pipelines/write_over_se.json" --set se=se.off --input a.off
  intact se.off "$data/unit_cube.off"
  expect 2 "morphex: .*grow.json: --report: refusing to overwrite the input read by pipeline\[0\] \(a.off\)" \
    "$morphex" run "$grow" --set out_dir=out --input a.off --report a.off
  intact a.off "$data/unit_cube.off"
  # one input's write onto another input
  cp a.off sa/b-grown.off
  expect 2 "pipeline\[2\].path: b.off would overwrite the input read by pipeline\[0\] for sa/b-grown.off" \
    "$morphex" run "$grow" --set out_dir=sa --input sa/b-grown.off b.off
  intact sa/b-grown.off "$data/unit_cube.off"
  ;;
same_stem)  # item 2
  cp a.off sa/1.off && cp b.off sb/1.off
  expect 2 "morphex: .*grow.json: pipeline\[2\].path: sa/1.off and sb/1.off would both write out/1-grown.off" \
    "$morphex" run "$grow" --set out_dir=out --input sa/1.off sb/1.off
  [ -e out/1-grown.off ] && fail "ran anyway"
  expect 2 "pipeline\[2\].path: sa/1.off and sb/1.off would both write out/1-grown.off" \
    "$morphex" validate "$grow" --set out_dir=out --input sa/1.off sb/1.off
  ;;
deep_json)  # item 3
  awk 'BEGIN{printf "{\"pipeline\":[{\"type\":\"read\",\"path\":"
    for(i=0;i<20000;i++)printf "["
    for(i=0;i<20000;i++)printf "]"
    printf "}]}"}' > deep.json
  expect 2 "morphex: deep.json:1:[0-9]+: JSON nested deeper than 64 levels" "$morphex" validate deep.json
  expect 2 "morphex: deep.json:1:[0-9]+: JSON nested deeper than 64 levels" \
    "$morphex" run deep.json --input a.off
  expect 2 "deep.json:1:[0-9]+: JSON nested deeper than 64 levels" \
    "$morphex" index a.off --db i.sqlite --pipeline deep.json
  ;;
memory)  # item 4
  # Caps around what a closing needs: each run succeeds or fails cleanly, never aborts (GMP's
  # allocation failure and glibc's unwinder loaded late under the cap aborted with 134).
  # (open and erode at these caps also die of SIGSEGV now and then, in the Boolean's
  # merge_coplanar: an open problem of the library, left out of this test of item 4.)
  for op in close; do
    for mb in $(seq 24 40); do
      out=$("$morphex" --max-memory-mb $mb $op b.off --se ball:r=1/7,level=3 -o c$mb.off 2>&1)
      got=$?
      [ "$got" -eq 0 ] && continue
      [ "$got" -eq 1 ] || fail "$op: exit $got at $mb MB: $out"
      echo "$out" | grep -q "^morphex: out of memory" || fail "$op: no message at $mb MB: $out"
      [ -e c$mb.off ] && fail "$op: output left at $mb MB"
    done
  done
  ;;
stdout_full)  # item 11
  "$morphex" index a.off b.off --db i.sqlite -q --pipeline "$data/pipelines/quick-descriptors.json" \
    > /dev/null || fail "index"
  printf 'PSB 1\n1 2\n\nshapes 0 2\na\nb\n' > labels.cla
  for args in "ls --db i.sqlite" "ls --json --db i.sqlite" "query --db i.sqlite a -k 1" \
      "evaluate --db i.sqlite --labels labels.cla" \
      "index a.off --db i.sqlite --json -q --pipeline $data/pipelines/quick-descriptors.json" \
      "check a.off" "check --json a.off" "describe --json a.off" \
      "bool union a.off b.off -o u.off --stats -" \
      "run $grow --set out_dir=out --input a.off --report -" "stages" "validate $grow --set out_dir=out"; do
    out=$($morphex $args 2>&1 > /dev/full); got=$?
    [ "$got" -eq 1 ] || fail "exit $got (expected 1): $args > /dev/full"$'\n'"$out"
    echo "$out" | grep -q "morphex: standard output: cannot write: No space left on device" ||
      fail "no message: $args > /dev/full"$'\n'"$out"
  done
  ;;
volume)  # item 12
  expect 0 "volume 0\.0370370370370370[0-9]*"$'\n' "$morphex" check "$data/third_cube_exact.off"
  expect 0 "\"volume\":0\.037037037037037" "$morphex" check --json "$data/third_cube_exact.off"
  expect 0 "volume 1/27 " "$morphex" check --exact "$data/third_cube_exact.off"
  expect 0 "\"volume\":0\.037.*\"volume_exact\":\"1/27\"" \
    "$morphex" check --json --exact "$data/third_cube_exact.off"
  expect 0 "\"volume\":0\.962962962962963" \
    "$morphex" bool difference a.off b.off -o d.off --stats -
  expect 0 "\"volume\":0\.96296.*\"volume_exact\":\"26/27\"" \
    "$morphex" bool difference a.off b.off -o d.off --exact --stats -
  out=$("$morphex" check --json "$data/third_cube_exact.off")
  case $out in *volume_exact*) fail "volume_exact without --exact: $out" ;; esac
  ;;
folders)  # item 13
  expect 2 "morphex: nosuch/x.off: cannot write in the folder .*nosuch: it does not exist" \
    "$morphex" dilate a.off --se ball:r=1/10,level=3 -o nosuch/x.off
  expect 2 "morphex: nosuch/s.json: cannot write in the folder .*nosuch: it does not exist" \
    "$morphex" bool union a.off b.off -o u.off --stats nosuch/s.json
  [ -e u.off ] && fail "the mesh was written"
  expect 2 "morphex: nosuch/r.json: cannot write in the folder" \
    "$morphex" run "$grow" --set out_dir=out --input a.off --report nosuch/r.json
  [ -e out/a-grown.off ] && fail "ran anyway"
  # a pipeline's write whose folder cannot be made: refused before the dilation, not after it
  expect 2 "grow.json: pipeline\[2\].path: cannot create the folder .*a.off/out: .*a.off is not a folder \(stage write#2\)" \
    "$morphex" run "$grow" --set out_dir=a.off/out --input a.off
  ;;
typos)  # item 14
  expect 2 "^morphex: unknown command 'dilat' \(did you mean 'dilate'\?\)" "$morphex" dilat a.off
  expect 2 "^morphex: dilate: unknown option '--ouput' \(did you mean '--output'\?\)" \
    "$morphex" dilate a.off --se cube:r=1 --ouput x.off
  expect 2 "^morphex: --se sphere:r=1: unknown structuring element shape 'sphere' \(did you mean 'ball'\?" \
    "$morphex" dilate a.off --se sphere:r=1 -o x.off
  expect 2 "^morphex: .*--output is required" "$morphex" dilate a.off --se cube:r=1
  expect 2 "^morphex: -k: expected a positive whole number, got '0'"$'\n' \
    "$morphex" query --db a.off -k 0 a.off
  expect 2 "^morphex: unknown command 'stage' \(did you mean 'stages'\?\)" "$morphex" --threads 1 stage
  ;;
inputs)  # item 15
  mkdir -p coll/sub && cp a.off coll/x.off && cp b.off coll/sub/y.off && echo text > coll/notes.txt
  expect 0 "indexed 2 meshes \(0 already up to date, 0 failed\)" \
    "$morphex" index coll --db i.sqlite --pipeline "$data/pipelines/quick-descriptors.json" -q
  expect 2 "morphex: 'nomatch\*.off': no file matches this pattern" \
    "$morphex" run "$grow" --set out_dir=out --input 'nomatch*.off'
  expect 2 "morphex: 'nomatch\*.off': no file matches this pattern" \
    "$morphex" index 'nomatch*.off' --db j.sqlite
  cp "$data/open_cube.off" open.off
  out=$("$morphex" index open.off --db k.sqlite --no-repair 2>&1)
  case $out in *"pipeline[0]"*) fail "internal stage location shown: $out" ;; esac
  out=$("$morphex" ls --db i.sqlite)
  case $out in *"||"*) fail "internal settings text shown: $out" ;; esac
  expect 0 "settings [0-9a-f]+: a fast descriptor pipeline .*\(read, solidify, describe\); descriptors version" \
    "$morphex" ls --db i.sqlite
  # an indexed mesh by name or by path: the same neighbours, itself left out
  by_name=$("$morphex" query --db i.sqlite x --json | sed 's/"query":"[^"]*"//')
  by_path=$("$morphex" query --db i.sqlite coll/x.off --json | sed 's/"query":"[^"]*"//')
  [ "$by_name" = "$by_path" ] || fail "by name $by_name, by path $by_path"
  case $by_path in *'"name":"x"'*) fail "the mesh is its own neighbour: $by_path" ;; esac
  printf 'PSB 1\n1 3\n\nshapes 0 3\nx\ny\nnosuch\n' > labels.cla
  expect 0 "1 labelled names not in the index skipped" \
    "$morphex" evaluate --db i.sqlite --labels labels.cla
  ;;
help)  # item 16
  expect 1 "crossing_cubes.off: .*self-intersect.*morphex repair" \
    "$morphex" check "$data/crossing_cubes.off"
  expect 2 "crossing_cubes.off: .*morphex repair" \
    "$morphex" dilate "$data/crossing_cubes.off" --se cube:r=1 -o x.off
  out=$("$morphex" check "$data/open_cube.off" 2>&1)
  case $out in *"genus -1"*|*"volume "[0-9]*) fail "meaningless genus or volume: $out" ;; esac
  expect 1 "\"genus\":null.*\"volume\":null" "$morphex" check --json "$data/open_cube.off"
  for sub in check repair bool dilate erode open close minkowski run validate stages describe \
      generate query evaluate index ls rm; do
    expect 0 "Example" "$morphex" $sub --help
  done
  ;;
*) fail "unknown item $item" ;;
esac
echo "ok $item"
