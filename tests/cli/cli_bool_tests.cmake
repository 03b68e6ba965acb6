# `morphex bool`: the README's CLI example, the --stats keys and the refusal to overwrite inputs.
set(out ${PROJECT_BINARY_DIR}/cli-out)
file(MAKE_DIRECTORY ${out})
morphex_cli_test(bool_union 0 "\"closed\":true.*\"self_intersecting\":false.*\"volume_exact\":\"1\""
  bool union ${data}/unit_cube.off ${data}/unit_cube.off -o ${out}/union.off --stats - --exact)
morphex_cli_test(bool_difference_exact 0 "\"volume_exact\":\"26/27\""
  bool difference ${data}/unit_cube.off ${data}/third_cube_exact.off -o ${out}/diff.off --exact --stats -)
morphex_cli_test(bool_refuses_overwrite 2 "refusing to overwrite"
  bool union ${data}/unit_cube.off ${data}/third_cube_exact.off -o ${data}/unit_cube.off)
morphex_cli_test(bool_invalid_operand 2 "open_cube.off.*not closed"
  bool union ${data}/open_cube.off ${data}/unit_cube.off -o ${out}/never.off)
morphex_cli_test(bool_unknown_op 2 "xor" bool xor ${data}/unit_cube.off ${data}/unit_cube.off -o ${out}/x.off)
# the exact output reads back with the same exact volume
morphex_cli_test(bool_exact_reread 0 "\"volume_exact\":\"26/27\"" check --json --exact ${out}/diff.off)
set_tests_properties(cli.bool_exact_reread PROPERTIES DEPENDS cli.bool_difference_exact)

# `morphex dilate|erode|open|close|minkowski`: exact volumes, SE errors, invalid inputs.
morphex_cli_test(dilate_cube 0 "\"closed\":true.*\"se\":\"cube:r=1/4\".*\"volume_exact\":\"27/8\""
  dilate ${data}/unit_cube.off --se cube:r=1/4 -o ${out}/dilated.off --exact --stats -)
morphex_cli_test(erode_cube 0 "\"volume_exact\":\"1/8\""
  erode ${data}/unit_cube.off --se box:x=1/4,y=1/4,z=1/4 -o ${out}/eroded.off --stats - --exact)
morphex_cli_test(erode_to_nothing 0 "\"faces\":0.*\"volume_exact\":\"0\""
  erode ${data}/unit_cube.off --se cube:r=1 -o ${out}/nothing.off --stats - --exact)
# eroded to [1/8,7/8]^3, dilated back with chamfered edges: 8a^3+24a^2r+12ar^2+4r^3/3, a=3/8, r=1/8
morphex_cli_test(open_cube 0 "\"volume_exact\":\"11/12\""
  open ${data}/unit_cube.off --se octahedron:r=1/8 -o ${out}/opened.off --stats - --exact)
morphex_cli_test(close_cube 0 "\"volume_exact\":\"1\""
  close ${data}/unit_cube.off --se cube:r=1/8 -o ${out}/closed.off --stats - --exact)
morphex_cli_test(minkowski_cubes 0 "\"volume_exact\":\"8\""
  minkowski ${data}/unit_cube.off ${data}/unit_cube.off -o ${out}/sum.off --stats - --exact)
morphex_cli_test(dilate_bad_se 2 "--se ball:radius=1: ball: radius: unknown parameter"
  dilate ${data}/unit_cube.off --se ball:radius=1 -o ${out}/never.off)
morphex_cli_test(dilate_missing_se 2 "--se is required" dilate ${data}/unit_cube.off -o ${out}/never.off)
morphex_cli_test(dilate_invalid_input 2 "open_cube.off: mesh is not closed"
  dilate ${data}/open_cube.off --se cube:r=1 -o ${out}/never.off)
morphex_cli_test(dilate_refuses_overwrite 2 "refusing to overwrite"
  dilate ${data}/unit_cube.off --se cube:r=1 -o ${data}/unit_cube.off)
morphex_cli_test(dilate_chained_exact 0 "\"volume_exact\":\"125/8\""
  dilate ${out}/dilated.off --se cube:r=1/2 -o ${out}/dilated_twice.off --stats - --exact)
set_tests_properties(cli.dilate_chained_exact PROPERTIES DEPENDS cli.dilate_cube)

# `morphex repair`: a self-intersecting mesh becomes its positive-winding solid exactly; what
# cannot be repaired is bad input (exit 2) naming the file and the first open edge.
morphex_cli_test(repair_crossing_cubes 0
  "\"intersecting_pairs\":18.*\"valid\":true.*\"volume_exact\":\"15/8\""
  repair ${data}/crossing_cubes.off -o ${out}/repaired.off --exact --stats -)
morphex_cli_test(repair_valid_unchanged 0 "\"changed\":false.*\"volume_exact\":\"1\""
  repair ${data}/unit_cube.off -o ${out}/unchanged.off --stats - --exact)
morphex_cli_test(repair_inward_turned 0 "\"reversed\":true.*\"volume_exact\":\"1\""
  repair ${data}/inward_cube.off -o ${out}/turned.off --stats - --exact)
morphex_cli_test(repair_open_refused 2
  "open_cube.off: cannot repair: mesh is not closed: the edge between vertices"
  repair ${data}/open_cube.off -o ${out}/never.off)
morphex_cli_test(repair_refuses_overwrite 2 "refusing to overwrite"
  repair ${data}/crossing_cubes.off -o ${data}/crossing_cubes.off)
morphex_cli_test(repair_reread_valid 0 "\"valid\":true.*\"volume_exact\":\"15/8\""
  check --json --exact ${out}/repaired.off)
set_tests_properties(cli.repair_reread_valid PROPERTIES DEPENDS cli.repair_crossing_cubes)
# describe makes a valid solid of what it is given (solidify, issue 43) unless --no-repair.
morphex_cli_test(describe_repair 0 "\"solidify\":\\{\"changed\":true.*\"method\":\"repair\".*\"summary\":\"repaired: intersecting pairs"
  describe --repair --json --scales 2 ${data}/crossing_cubes.off)
morphex_cli_test(describe_without_repair 2 "crossing_cubes.off: mesh self-intersects"
  describe --no-repair --json ${data}/crossing_cubes.off)
# The doorstep (issue 23): global options after the subcommand, clear refusals before any work.
morphex_cli_test(bool_threads_after_subcommand 0 "\"volume_exact\":\"1\""
  bool union ${data}/unit_cube.off ${data}/unit_cube.off -o ${out}/threads.off --threads 2 --stats - --exact)
morphex_cli_test(threads_zero 2 "expected a positive number of threads, got '0'"
  --threads 0 check ${data}/unit_cube.off)
morphex_cli_test(bool_unknown_output_format 2 "--output: unknown mesh format '.xyz'"
  bool union ${data}/unit_cube.off ${data}/unit_cube.off -o ${out}/never.xyz)
morphex_cli_test(dilate_unknown_output_format 2 "--output: unknown mesh format '.wrl'"
  dilate ${data}/unit_cube.off --se cube:r=1 -o ${out}/never.wrl)
