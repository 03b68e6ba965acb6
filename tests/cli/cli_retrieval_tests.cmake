# `morphex describe|generate|index|query|evaluate`: the retrieval workflow end to end on a small
# procedural collection, resumability, failure isolation, a copy found first, the metrics table.
set(rdir ${PROJECT_BINARY_DIR}/cli-retrieval)
set(quick ${data}/pipelines/quick-descriptors.json)
morphex_cli_test(describe_cube 0 "\"granulometry\":\\[1.0,1.0,1.0,1.0,1.0,1.0,1.0,1.0\\].*\"name\":\"unit_cube\""
  describe --json ${data}/unit_cube.off)
morphex_cli_test(describe_open_mesh 0 "\"solidify\":\\{\"changed\":true.*\"filled_holes\":1.*\"method\":\"soup\".*\"summary\":\"soup: filled holes 1\""
  describe --json --scales 2 ${data}/open_cube.off)
morphex_cli_test(describe_open_mesh_refused 2 "open_cube.off: mesh is not closed"
  describe --no-repair ${data}/open_cube.off)
# the options of describe are the library's table of descriptor settings, checked by the library
morphex_cli_test(describe_bad_setting 2 "--d2-bins: expected an integer from 4 to 4096, got 2"
  describe --d2-bins 2 ${data}/unit_cube.off)
morphex_cli_test(describe_radii_not_growing 2 "--close-from: open_from/close_from must not exceed"
  describe --close-from 0.5 --close-to 0.4 ${data}/unit_cube.off)
morphex_cli_test(describe_sheet 2 "sheet.off: cannot solidify: mesh bounds no"
  describe ${data}/sheet.off)
# A fresh, existing directory: the index tests create their databases in it, whether or not a
# generate test has run before them.
add_test(NAME cli.retrieval_setup COMMAND ${CMAKE_COMMAND} -E rm -rf ${rdir})
add_test(NAME cli.retrieval_mkdir COMMAND ${CMAKE_COMMAND} -E make_directory ${rdir})
set_tests_properties(cli.retrieval_mkdir PROPERTIES DEPENDS cli.retrieval_setup)
set_tests_properties(cli.retrieval_setup cli.retrieval_mkdir PROPERTIES FIXTURES_SETUP retrieval)
morphex_cli_test(generate 0 "wrote 6 meshes in 6 classes" generate ${rdir}/coll --per-class 1 --seed 3)
set_tests_properties(cli.generate PROPERTIES FIXTURES_REQUIRED retrieval)
# a second collection member per class for the evaluation, and a copy of one mesh under a new name
morphex_cli_test(generate_more 0 "wrote 12 meshes" generate ${rdir}/coll2 --per-class 2 --seed 3)
set_tests_properties(cli.generate_more PROPERTIES FIXTURES_REQUIRED retrieval)
morphex_cli_test(index_first 0 "indexed 3 meshes \\(0 already up to date, 0 failed\\)"
  index ${rdir}/coll2/bar-0.off ${rdir}/coll2/ell-0.off ${rdir}/coll2/tee-0.off
  --db ${rdir}/index.sqlite --pipeline ${quick})
set_tests_properties(cli.index_first PROPERTIES DEPENDS cli.generate_more)
morphex_cli_test(index_bad_set 2 "--set =1: expected name=value"
  index ${rdir}/coll2/bar-0.off --db ${rdir}/never.sqlite --pipeline ${quick} --set =1)
# resumable: the second run skips what the first committed and does the rest
morphex_cli_test(index_resume 0 "indexed 9 meshes \\(3 already up to date, 0 failed\\)"
  index "${rdir}/coll2/*.off" --db ${rdir}/index.sqlite --pipeline ${quick})
set_tests_properties(cli.index_resume PROPERTIES DEPENDS cli.index_first)
# failure isolation: an open mesh is recorded as failed, the others are indexed, exit 1
# (meshes are repaired by default: the open one is refused by the repair stage, exit 1)
# An open mesh is solidified and indexed (issue 43); a sheet bounds no volume and fails alone.
morphex_cli_test(index_bad_mesh 1 "indexed 3 meshes \\(0 already up to date, 1 failed\\).*sheet.off: pipeline\\[1\\] \\(solidify\\).*bounds no"
  index ${data}/open_cube.off ${data}/sheet.off ${data}/unit_cube.off ${data}/third_cube_exact.off
  --db ${rdir}/other.sqlite --pipeline ${quick})
set_tests_properties(cli.index_bad_mesh PROPERTIES FIXTURES_REQUIRED retrieval)
morphex_cli_test(index_no_repair 1 "indexed 1 meshes \\(0 already up to date, 1 failed\\).*crossing_cubes.off: pipeline\\[0\\] \\(read\\).*self-intersects"
  index ${data}/crossing_cubes.off ${data}/unit_cube.off --no-repair
  --db ${rdir}/unrepaired.sqlite --pipeline ${quick})
set_tests_properties(cli.index_no_repair PROPERTIES FIXTURES_REQUIRED retrieval)
# a self-intersecting mesh is repaired, indexed, and the index records what changed
morphex_cli_test(index_repairs 0 "indexed 2 meshes \\(0 already up to date, 0 failed\\)"
  index ${data}/crossing_cubes.off ${data}/unit_cube.off --db ${rdir}/repaired.sqlite
  --pipeline ${quick})
set_tests_properties(cli.index_repairs PROPERTIES FIXTURES_REQUIRED retrieval)
morphex_cli_test(index_no_describe 2 "needs a describe stage"
  index ${data}/unit_cube.off --db ${rdir}/never.sqlite --pipeline ${PROJECT_SOURCE_DIR}/pipelines/examples/granulometry.json)
# a renamed copy of an indexed mesh finds the original first, at distance 0
add_test(NAME cli.copy_mesh COMMAND ${CMAKE_COMMAND} -E copy ${rdir}/coll2/frame-1.off ${rdir}/copy-of-frame.off)
set_tests_properties(cli.copy_mesh PROPERTIES DEPENDS cli.index_resume)
morphex_cli_test(query_copy_first 0 "\"neighbours\":\\[\\{\"distance\":0.0,\"name\":\"frame-1\""
  query --db ${rdir}/index.sqlite ${rdir}/copy-of-frame.off -k 3 --json)
set_tests_properties(cli.query_copy_first PROPERTIES DEPENDS cli.copy_mesh)
morphex_cli_test(query_by_name 0 "\"query\":\"ell-1\"" query --db ${rdir}/index.sqlite ell-1 -k 2 --json --descriptor d2)
set_tests_properties(cli.query_by_name PROPERTIES DEPENDS cli.index_resume)
morphex_cli_test(query_unknown_name 2 "nosuch: neither a mesh file nor the name of an indexed mesh"
  query --db ${rdir}/index.sqlite nosuch)
set_tests_properties(cli.query_unknown_name PROPERTIES DEPENDS cli.index_resume)
morphex_cli_test(evaluate 0 "Nearest Neighbor +First Tier +Second Tier +E-measure +DCG.*granulometry.*d2.*12 labelled models"
  evaluate --db ${rdir}/index.sqlite --labels ${rdir}/coll2/labels.cla)
set_tests_properties(cli.evaluate PROPERTIES DEPENDS cli.index_resume)
morphex_cli_test(evaluate_bad_labels 2 "unit_cube.off: line 1: expected the header"
  evaluate --db ${rdir}/index.sqlite --labels ${data}/unit_cube.off)
set_tests_properties(cli.evaluate_bad_labels PROPERTIES DEPENDS cli.index_resume)
morphex_cli_test(evaluate_no_labelled_model 2 "unindexed-labels.cla: none of its 2 models is in the index"
  evaluate --db ${rdir}/index.sqlite --labels ${data}/unindexed-labels.cla)
set_tests_properties(cli.evaluate_no_labelled_model PROPERTIES DEPENDS cli.index_resume)
# killed with SIGKILL midway, the index keeps what it committed and the re-run does the rest
add_test(NAME cli.index_killed_and_resumed COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/index_kill.sh
  $<TARGET_FILE:morphex> ${quick} ${PROJECT_BINARY_DIR}/cli-index-kill)
# the collection manager: absolute paths, failures skipped until --retry-failed, changed files,
# ls, rm, --quiet, --json
add_test(NAME cli.index_manage COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/index_manage.sh
  $<TARGET_FILE:morphex> ${quick} ${data} ${PROJECT_BINARY_DIR}/cli-index-manage)
if(MORPHEX_MPI)
  # three MPI ranks store the rows of a single-process run, resume and skip as it does
  add_test(NAME cli.index_mpi COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/index_mpi.sh
    $<TARGET_FILE:morphex> ${MPIEXEC_EXECUTABLE} ${quick} ${PROJECT_BINARY_DIR}/cli-index-mpi)
endif()
# index files are untrusted input: stored pipelines, foreign, empty, damaged and mixed indexes,
# non-finite descriptors (issue 44, items 7-10)
add_test(NAME cli.index_untrusted COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/index_untrusted.sh
  $<TARGET_FILE:morphex> ${quick} ${data} ${PROJECT_BINARY_DIR}/cli-index-untrusted)
# the repair's work budget: a hostile soup is refused by repair, recorded as failed by index
# The memory cap keeps a failing budget from swapping; AddressSanitizer's shadow memory cannot
# live under one (as cli.max_memory).
set(repair_budget_cap "--max-memory-mb 2000")
if(MORPHEX_SANITIZE MATCHES "address")
  set(repair_budget_cap "")
endif()
add_test(NAME cli.repair_budget COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/repair_budget.sh
  $<TARGET_FILE:morphex> ${quick} ${data} ${PROJECT_BINARY_DIR}/cli-repair-budget
  "${repair_budget_cap}")
# describe runs the describe stage: the same description as `morphex run` of that pipeline
add_test(NAME cli.describe_is_the_describe_stage COMMAND bash
  ${CMAKE_CURRENT_SOURCE_DIR}/cli/describe_stage.sh $<TARGET_FILE:morphex> ${data}
  ${PROJECT_BINARY_DIR}/cli-describe-stage)
# plots as files: evaluate --plot and describe --plot write SVG an XML parser reads (issue 46)
add_test(NAME cli.plots COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/plots.sh
  $<TARGET_FILE:morphex> ${quick} ${data} ${PROJECT_BINARY_DIR}/cli-plots)
