# `morphex bool`: the README's CLI example, the --stats keys and the refusal to overwrite inputs.
set(out ${PROJECT_BINARY_DIR}/cli-out)
file(MAKE_DIRECTORY ${out})
morphex_cli_test(bool_union 0 "\"closed\":true.*\"self_intersecting\":false.*\"volume\":\"1\""
  bool union ${data}/unit_cube.off ${data}/unit_cube.off -o ${out}/union.off --stats -)
morphex_cli_test(bool_difference_exact 0 "\"volume\":\"26/27\""
  bool difference ${data}/unit_cube.off ${data}/third_cube_exact.off -o ${out}/diff.off --exact --stats -)
morphex_cli_test(bool_refuses_overwrite 2 "refusing to overwrite"
  bool union ${data}/unit_cube.off ${data}/third_cube_exact.off -o ${data}/unit_cube.off)
morphex_cli_test(bool_invalid_operand 2 "open_cube.off.*not closed"
  bool union ${data}/open_cube.off ${data}/unit_cube.off -o ${out}/never.off)
morphex_cli_test(bool_unknown_op 2 "xor" bool xor ${data}/unit_cube.off ${data}/unit_cube.off -o ${out}/x.off)
# the exact output reads back with the same exact volume
morphex_cli_test(bool_exact_reread 0 "\"volume\":\"26/27\"" check --json ${out}/diff.off)
set_tests_properties(cli.bool_exact_reread PROPERTIES DEPENDS cli.bool_difference_exact)
