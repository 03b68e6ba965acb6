# Streams, 3MF, glb and outputs the plain formats cannot hold (issue 23, items 6, 7 and 8).
set(io_out ${PROJECT_BINARY_DIR}/cli-io-out)
file(MAKE_DIRECTORY ${io_out})
set(mx $<TARGET_FILE:morphex>)
# A shell pipeline (no ';' in SCRIPT: it separates CMake list items), its exit code and output
# checked as morphex_cli_test does; the exit code is the last command's.
function(morphex_sh_test name code regex script)
  add_test(NAME cli.${name} COMMAND ${CMAKE_COMMAND} "-DCOMMAND=sh;-c;${script}"
    -DEXPECT_CODE=${code} "-DEXPECT_REGEX=${regex}" -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
endfunction()

# `-` is standard input and output: OFF (exact or plain), binary STL, the format read from the
# content; messages name <stdin>.
morphex_sh_test(stdout_exact_off_to_check 0 "\"file\":\"<stdin>\".*\"valid\":true.*\"volume_exact\":\"26/27\""
  "${mx} bool difference ${data}/unit_cube.off ${data}/third_cube_exact.off -o - --exact | ${mx} check --json --exact -")
morphex_sh_test(stdout_stl_to_check 0 "<stdin>: valid closed solid.*volume 1[^./0-9]"
  "${mx} bool union ${data}/unit_cube.off ${data}/unit_cube.off -o - --format stl | ${mx} check -")
morphex_sh_test(stdin_to_stdout_dilate 0 "\"valid\":true.*\"volume_exact\":\"27/8\""
  "${mx} dilate - --se cube:r=1/4 -o - --exact < ${data}/unit_cube.off | ${mx} check --json --exact -")
morphex_sh_test(stdin_repair_stats 0 "\"reversed\":true.*\"volume_exact\":\"1\""
  "${mx} repair - -o ${io_out}/turned.off --exact --stats - < ${data}/inward_cube.off")
morphex_sh_test(stdin_ascii_stl 0 "<stdin>: valid closed solid"
  "printf 'solid t\\nfacet normal 0 0 0\\nouter loop\\nvertex 0 0 0\\nvertex 0 1 0\\nvertex 1 0 0\\nendloop\\nendfacet\\nfacet normal 0 0 0\\nouter loop\\nvertex 0 0 0\\nvertex 0 0 1\\nvertex 0 1 0\\nendloop\\nendfacet\\nfacet normal 0 0 0\\nouter loop\\nvertex 0 0 0\\nvertex 1 0 0\\nvertex 0 0 1\\nendloop\\nendfacet\\nfacet normal 0 0 0\\nouter loop\\nvertex 1 0 0\\nvertex 0 1 0\\nvertex 0 0 1\\nendloop\\nendfacet\\nendsolid t\\n' | ${mx} check -")
morphex_sh_test(stdin_empty 2 "morphex: <stdin>: empty input: nothing was piped into standard input"
  "${mx} check - < /dev/null")
morphex_sh_test(stdin_garbage 2 "<stdin>: cannot tell the mesh format from the first bytes 'hello.*standard input takes OFF, STL"
  "echo hello | ${mx} check -")
morphex_sh_test(stdin_garbage_bool 2 "<stdin>: cannot tell the mesh format"
  "echo hello | ${mx} bool union - ${data}/unit_cube.off -o ${io_out}/never.off")
morphex_cli_test(stdin_twice 2 "standard input can be read only once"
  bool union - - -o ${io_out}/never.off)
morphex_cli_test(stdout_and_stats_stdout 2 "--stats -: standard output carries the mesh"
  bool union ${data}/unit_cube.off ${data}/unit_cube.off -o - --stats -)
morphex_cli_test(format_needs_stdout 2 "--format stl: only for -o -"
  bool union ${data}/unit_cube.off ${data}/unit_cube.off -o ${io_out}/never.off --format stl)
morphex_cli_test(format_unknown 2 "--format: unknown mesh format '.xyz'"
  bool union ${data}/unit_cube.off ${data}/unit_cube.off -o - --format xyz)
morphex_cli_test(exact_needs_off_early 2 "never.stl: the exact format is OFF"
  dilate ${data}/unit_cube.off --se ball:r=1/10,level=3 -o ${io_out}/never.stl --exact)

# Sizes out of proportion are refused before any work; results a plain format cannot hold are
# refused (exit 1: the operation ran) with the advice to write the exact format.
morphex_cli_test(se_too_small 2
  "--se ball:r=1e-300: ball: size: a side of [0-9.e-]+ is below 1e-12 of the mesh's size \\(1\\)"
  dilate ${data}/unit_cube.off --se ball:r=1e-300 -o ${io_out}/never.off)
set_tests_properties(cli.se_too_small PROPERTIES TIMEOUT 20)
morphex_cli_test(se_too_large 2 "--se cube:r=1e300: cube: size: an extent of 1e\\+300 is above 1e12"
  dilate ${data}/unit_cube.off --se cube:r=1e300 -o ${io_out}/never.off)
# an exact integer of 311 digits: a number, but no double holds it
string(REPEAT "0" 310 zeros)
morphex_cli_test(se_beyond_doubles 2 "cube: r: 10+ is outside the range of doubles"
  dilate ${data}/unit_cube.off --se cube:r=1${zeros} -o ${io_out}/never.off)
# Features thinner than a float's spacing (an octahedron of radius 1e-11 on a unit cube) are
# rounded into a valid solid, not refused (issue 42); --stats says what rounding did.
morphex_sh_test(tiny_features_float_output 0 "\"rounding\":\\{.*\"moved_vertices\":[1-9].*valid closed solid"
  "${mx} dilate ${data}/unit_cube.off --se octahedron:r=1e-11 -o ${io_out}/tiny.stl --stats - && ${mx} check ${io_out}/tiny.stl")
# A coordinate beyond the float range is the one thing a float format cannot hold: exit 1, no file.
morphex_sh_test(out_of_float_range_leaves_no_file 0 "outside the format's range.*exit 1, no file"
  "printf 'OFF\\n4 4 0\\n1e39 0 0\\n2e39 0 0\\n1e39 1e39 0\\n1e39 0 1e39\\n3 0 2 1\\n3 0 1 3\\n3 1 2 3\\n3 0 3 2\\n' | ${mx} repair - -o ${io_out}/huge.stl 2>&1
   status=$?
   ls -a ${io_out} | grep -q huge || echo \"exit $status, no file\"")

# 3MF through lib3mf (optional at build time), glb written for viewers.
if(MORPHEX_3MF)
  morphex_cli_test(bool_to_3mf 0 "\"volume\":3.375"
    dilate ${data}/unit_cube.off --se cube:r=1/4 -o ${io_out}/dilated.3mf --stats -)
  morphex_cli_test(check_3mf 0 "dilated.3mf: valid closed solid.*volume 3.375[^/0-9]"
    check ${io_out}/dilated.3mf)
  set_tests_properties(cli.check_3mf PROPERTIES DEPENDS cli.bool_to_3mf)
  morphex_sh_test(stdout_3mf_to_check 0 "<stdin>: valid closed solid.*volume 1[^./0-9]"
    "${mx} bool union ${data}/unit_cube.off ${data}/unit_cube.off -o - --format 3mf | ${mx} check -")
  morphex_sh_test(tiny_features_3mf_output 0 "tiny.3mf: valid closed solid"
    "${mx} dilate ${data}/unit_cube.off --se octahedron:r=1e-9 -o ${io_out}/tiny.3mf && ${mx} check ${io_out}/tiny.3mf")
else()
  morphex_cli_test(3mf_unavailable 2 "--output: 3MF is not available: this morphex was built without lib3mf"
    bool union ${data}/unit_cube.off ${data}/unit_cube.off -o ${io_out}/never.3mf)
endif()
morphex_cli_test(bool_to_glb 0 "\"faces\":12"
  bool union ${data}/unit_cube.off ${data}/unit_cube.off -o ${io_out}/cube.glb --stats -)
morphex_cli_test(glb_is_not_read 2 "glb files are written for viewers, not read"
  check ${io_out}/cube.glb)
set_tests_properties(cli.glb_is_not_read PROPERTIES DEPENDS cli.bool_to_glb)

# Meshes as they come (issue 43): solidify closes, turns and unites; a sheet bounds no volume.
morphex_sh_test(solidify_open_cube 0 "\"filled_holes\":1.*\"method\":\"soup\".*valid closed solid.*volume 1 "
  "${mx} solidify ${data}/open_cube.off -o ${io_out}/closed.off --stats - && ${mx} check ${io_out}/closed.off")
morphex_cli_test(solidify_inward 0 "\"turned_parts\":1.*\"valid\":true.*\"volume\":1(\\.0)?[,}]"
  solidify ${data}/inward_cube.off -o ${io_out}/turned.off --stats -)
morphex_cli_test(solidify_valid_unchanged 0 "\"method\":\"unchanged\""
  solidify ${data}/unit_cube.off -o ${io_out}/same.off --stats -)
morphex_sh_test(solidify_sheet 0 "cannot solidify: mesh bounds no .*exit 1"
  "printf 'OFF\\n4 2 0\\n0 0 0\\n1 0 0\\n1 1 0\\n0 1 0\\n3 0 1 2\\n3 0 2 3\\n' | ${mx} solidify - -o ${io_out}/sheet.off 2>&1
   echo \"exit $?\"")
morphex_sh_test(gzip_stdin_check 0 "<stdin>: valid closed solid"
  "gzip -c ${data}/unit_cube.off | ${mx} check -")
# index over a folder of meshes as they come (issue 43): open, inward, self-intersecting, a
# soup written as STL, and a sheet; every one but the sheet is solidified, described and indexed,
# what was done recorded per mesh (the STL, a valid union, is indexed as it is).
morphex_sh_test(index_damaged_folder 0 "sheet.off: pipeline.*solidify.*bounds no.*indexed 5 meshes \\(0 already up to date, 1 failed\\).*solidified 3"
  "rm -rf ${io_out}/wild && mkdir -p ${io_out}/wild && cp ${data}/open_cube.off ${data}/inward_cube.off ${data}/crossing_cubes.off ${data}/unit_cube.off ${data}/sheet.off ${io_out}/wild/ && ${mx} bool union ${data}/unit_cube.off ${data}/third_cube_exact.off -o ${io_out}/wild/soup.stl && rm -f ${io_out}/wild.sqlite
   ${mx} index ${io_out}/wild --db ${io_out}/wild.sqlite --pipeline ${data}/pipelines/quick-descriptors.json 2>&1
   echo solidified $(${mx} ls --json --db ${io_out}/wild.sqlite | grep -o '\"method\":\"[a-z]*\"' | grep -vc unchanged)")
# --stats onto a device writes into it, never renames a file over it (/dev/null stays one).
morphex_sh_test(outputs_onto_devices 0 "^still a device"
  "${mx} bool union ${data}/unit_cube.off ${data}/unit_cube.off -o ${io_out}/dev.off --stats /dev/null && test -c /dev/null && echo still a device")
