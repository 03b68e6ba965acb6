# Command-line contract tests: exit codes and messages of docs/conventions.md and docs/cli.md.
set(data ${CMAKE_CURRENT_SOURCE_DIR}/data)
function(morphex_cli_test name code regex)
  add_test(NAME cli.${name} COMMAND ${CMAKE_COMMAND}
    "-DCOMMAND=$<TARGET_FILE:morphex>;${ARGN}" -DEXPECT_CODE=${code} "-DEXPECT_REGEX=${regex}"
    -P ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect.cmake)
endfunction()

morphex_cli_test(version 0 "morphex ${PROJECT_VERSION}" --version)
morphex_cli_test(help 0 "check" --help)
morphex_cli_test(check_help 0 "--json" check --help)
morphex_cli_test(no_subcommand 2 "subcommand" )
morphex_cli_test(unknown_option 2 "bogus" check --bogus ${data}/unit_cube.off)
morphex_cli_test(check_cube 0 "\"volume\":1.0" check --json ${data}/unit_cube.off)
morphex_cli_test(check_cube_exact 0 "\"volume_exact\":\"1\"" check --json --exact ${data}/unit_cube.off)
morphex_cli_test(check_cube_text 0 "valid closed solid" check ${data}/unit_cube.off)
morphex_cli_test(check_exact_third 0 "\"volume_exact\":\"1/27\"" check --json --exact ${data}/third_cube_exact.off)
morphex_cli_test(check_open 1 "open_cube.off: mesh is not closed: 4 border edges, first at vertex"
  check ${data}/open_cube.off)
morphex_cli_test(check_open_json 1 "\"border_edges\":4" check --json ${data}/open_cube.off)
morphex_cli_test(check_inward 1 "\"outward\":false" check --json ${data}/inward_cube.off)
morphex_cli_test(check_self_intersecting 1 "\"self_intersecting\":true"
  check --json ${data}/crossing_cubes.off)
morphex_cli_test(check_missing_file 2 "does_not_exist.off" check ${data}/does_not_exist.off)
morphex_cli_test(check_truncated 2 "truncated.off" check ${data}/truncated.off)
morphex_cli_test(threads_option 0 "volume" --threads 1 check --json ${data}/unit_cube.off)
morphex_cli_test(threads_invalid 2 "threads" --threads 0 check ${data}/unit_cube.off)

# CGAL's demo meshes, extracted from Debian's libcgal-demo by scripts/fetch-cgal-demo-meshes.
set(MORPHEX_CGAL_DEMO_DIR "$ENV{HOME}/.cache/morphex/cgal-demo" CACHE PATH "CGAL demo meshes")
foreach(mesh star cross eight elephant)
  add_test(NAME cli.check_demo_${mesh} COMMAND morphex check --json
           ${MORPHEX_CGAL_DEMO_DIR}/${mesh}.off)
  set_tests_properties(cli.check_demo_${mesh} PROPERTIES
    PASS_REGULAR_EXPRESSION "\"valid\":true" SKIP_RETURN_CODE 77)
endforeach()

# A separate CMake project links morphex::bool through find_package(morphex) against an
# installed tree: the packaging contract of the README.
add_test(NAME package.install COMMAND ${CMAKE_COMMAND} --install ${PROJECT_BINARY_DIR}
         --prefix ${PROJECT_BINARY_DIR}/test-install)
set(consumer_flags)
if(MORPHEX_SANITIZE)
  # A sanitized library needs the sanitizer runtime in whatever links it.
  set(consumer_flags -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=${MORPHEX_SANITIZE})
endif()
add_test(NAME package.consumer_configure COMMAND ${CMAKE_COMMAND}
  -S ${CMAKE_CURRENT_SOURCE_DIR}/consumer -B ${PROJECT_BINARY_DIR}/consumer-build
  -DCMAKE_PREFIX_PATH=${PROJECT_BINARY_DIR}/test-install -DCMAKE_BUILD_TYPE=Release
  ${consumer_flags})
add_test(NAME package.consumer_build COMMAND ${CMAKE_COMMAND}
  --build ${PROJECT_BINARY_DIR}/consumer-build)
add_test(NAME package.consumer_run COMMAND ${PROJECT_BINARY_DIR}/consumer-build/consumer
  ${data}/unit_cube.off ${data}/third_cube_exact.off)
set_tests_properties(package.consumer_run PROPERTIES PASS_REGULAR_EXPRESSION "valid 1 volume 26/27")
set_tests_properties(package.install PROPERTIES FIXTURES_SETUP morphex_installed)
set_tests_properties(package.consumer_configure PROPERTIES
  FIXTURES_REQUIRED morphex_installed FIXTURES_SETUP consumer_configured)
set_tests_properties(package.consumer_build PROPERTIES
  FIXTURES_REQUIRED consumer_configured FIXTURES_SETUP consumer_built)
set_tests_properties(package.consumer_run PROPERTIES FIXTURES_REQUIRED consumer_built)
# The modules that `serve` and MPI runs load are installed where the command line looks for them
# (bin/../MORPHEX_MODULE_DIR, morphex/internal/modules.h; cli.lazy_libraries runs that layout).
set(installed_modules ${PROJECT_BINARY_DIR}/test-install/${MORPHEX_MODULE_DIR}/morphex_serve_http.so)
if(MORPHEX_MPI)
  list(APPEND installed_modules ${PROJECT_BINARY_DIR}/test-install/${MORPHEX_MODULE_DIR}/morphex_mpi.so)
endif()
add_test(NAME package.installed_modules COMMAND ls ${installed_modules})
set_tests_properties(package.installed_modules PROPERTIES FIXTURES_REQUIRED morphex_installed)
include(cli/cli_bool_tests.cmake)
include(cli/cli_pipeline_tests.cmake)
include(cli/cli_retrieval_tests.cmake)
include(cli/cli_io_tests.cmake)

# Every sh block of README.md runs as written (scripts/readme-examples documents the markers).
add_test(NAME readme.examples COMMAND ${PROJECT_SOURCE_DIR}/scripts/readme-examples
  --build ${PROJECT_BINARY_DIR})
set_tests_properties(readme.examples PROPERTIES TIMEOUT 180 DEPENDS cli.version)

# 3,000 random Booleans with exact identities and validity, fixed seed (tools/stress.cpp); a
# quarter of the operands are earlier results (separated features met again); every 20th case
# opens and closes by a cube, an octahedron or a ball in turn. About 25 s.
add_test(NAME stress.booleans_and_morphology COMMAND stress --seed 1 --count 3000
  --out ${PROJECT_BINARY_DIR}/stress-failures)
set_tests_properties(stress.booleans_and_morphology PROPERTIES TIMEOUT 900)
if(MORPHEX_SANITIZE)
  # The sanitizer pass skips the 3,000 cases above (tests/slow-tests.txt) and runs other ones.
  add_test(NAME stress.sanitized COMMAND stress --seed 2 --count 100
    --out ${PROJECT_BINARY_DIR}/stress-failures)
  set_tests_properties(stress.sanitized PROPERTIES TIMEOUT 1200)
endif()

# Limits and interruption (issue 8): clear refusals, and SIGINT leaves no partial output.
morphex_cli_test(max_faces 2 "unit_cube.off: too many faces: 12 \\(limit 5; raise it with --max-faces\\)"
  --max-faces 5 check ${data}/unit_cube.off)
if(NOT MORPHEX_SANITIZE MATCHES "address")
  # Not under ASan: it reserves terabytes of address space for its shadow memory at start, so an
  # address-space limit (RLIMIT_AS, what --max-memory-mb sets) cannot be exercised there. The
  # operation needs well over what the allocator has mapped when the cap is set.
  morphex_cli_test(max_memory 1 "out of memory: the operation needs more memory"
    --max-memory-mb 5 dilate ${data}/unit_cube.off --se ball:r=1/10,level=4 -o ${PROJECT_BINARY_DIR}/never.off)
endif()
add_test(NAME cli.progress_on_a_terminal COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/progress.sh
  $<TARGET_FILE:morphex> ${data} ${PROJECT_BINARY_DIR}/cli-progress)
set_tests_properties(cli.progress_on_a_terminal PROPERTIES PASS_REGULAR_EXPRESSION "PASS")
add_test(NAME cli.sigint_leaves_no_output COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/interrupt.sh
  $<TARGET_FILE:morphex> ${data} ${PROJECT_BINARY_DIR}/cli-interrupt)
# glibc's malloc with huge pages: the executables restart themselves once for it, keeping their
# arguments, standard input and the user's own tunables (morphex/internal/huge_pages.h).
if(MORPHEX_SANITIZE OR MORPHEX_FUZZ OR MORPHEX_SCALABLE_MALLOC)
  set(morphex_allocator other)
else()
  set(morphex_allocator glibc)
endif()
add_test(NAME cli.huge_page_malloc COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/huge_pages.sh
  $<TARGET_FILE:morphex> ${data} ${PROJECT_BINARY_DIR}/cli-huge-pages ${morphex_allocator})
set_tests_properties(cli.huge_page_malloc PROPERTIES PASS_REGULAR_EXPRESSION "PASS")

# lib3mf, cpp-httplib and Open MPI are loaded only by the commands that need them, from modules
# found beside the executable or in the installed layout (morphex/internal/modules.h).
add_test(NAME cli.lazy_libraries COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/lazy_libraries.sh
  $<TARGET_FILE:morphex> ${data} ${PROJECT_BINARY_DIR}/cli-lazy-libraries ${MORPHEX_MODULE_DIR}
  ${MORPHEX_3MF} ${MORPHEX_MPI})
set_tests_properties(cli.lazy_libraries PROPERTIES PASS_REGULAR_EXPRESSION "PASS")

# The benchmarks run and agree with their exact peers on a small case (timings are not asserted).
if(MORPHEX_BUILD_BENCHMARKS)
  add_test(NAME bench.bool_smoke COMMAND bench_bool --max-level 2 --only "icospheres L2")
  set_tests_properties(bench.bool_smoke PROPERTIES PASS_REGULAR_EXPRESSION "=coref =Nef")
  add_test(NAME bench.morph_smoke COMMAND bench_morph --se cube:r=1/4 --peer l-shape)
  set_tests_properties(bench.morph_smoke PROPERTIES PASS_REGULAR_EXPRESSION
                       "agree with minkowski_sum_3")
  # A comma-separated list option takes one argument: the inputs after it stay inputs.
  add_test(NAME bench.list_options_leave_inputs
           COMMAND bench_morph --threads 1 --ops dilate,erode l-shape)
  set_tests_properties(bench.list_options_leave_inputs PROPERTIES PASS_REGULAR_EXPRESSION
                       "l-shape +erode")
  add_test(NAME bench.check_threads_leave_inputs
           COMMAND bench_check --no-peer --runs 1 --threads 1 fan-prism:40)
  set_tests_properties(bench.check_threads_leave_inputs PROPERTIES PASS_REGULAR_EXPRESSION
                       "fan-prism:40 ")
  # Manifold's columns when bench_morph was built with it, the note that it was not otherwise.
  add_test(NAME bench.morph_manifold_smoke
           COMMAND bench_morph --se cube:r=1/4 --ops dilate,erode,open --manifold l-shape)
  set_tests_properties(bench.morph_manifold_smoke PROPERTIES PASS_REGULAR_EXPRESSION
                       "Manifold volume rel. diff|bench_morph was built without Manifold")
  # A Manifold run past --manifold-timeout is stopped, and its row says so.
  add_test(NAME bench.morph_manifold_timeout COMMAND bench_morph --se octahedron:r=1/4 --ops close
           --manifold --manifold-timeout 0.001 l-shape)
  set_tests_properties(bench.morph_manifold_timeout PROPERTIES PASS_REGULAR_EXPRESSION
                       "Manifold stopped after 0.001 s|bench_morph was built without Manifold")
  # scripts/bench-targets' summary reads what the benchmarks write and judges issue 47's targets.
  add_test(NAME bench.targets_summary COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/bench_targets.sh
    $<TARGET_FILE_DIR:bench_morph> ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/bench-targets)
  set_tests_properties(bench.targets_summary PROPERTIES PASS_REGULAR_EXPRESSION "PASS")
  # scripts/bench-check-ab runs two builds' bench_check alternately and compares them.
  add_test(NAME bench.check_ab COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/bench_check_ab.sh
    $<TARGET_FILE_DIR:bench_check> ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/bench-check-ab)
  set_tests_properties(bench.check_ab PROPERTIES PASS_REGULAR_EXPRESSION "PASS")
endif()
# Paths that are not mesh files say so (not "unknown mesh format ''").
morphex_cli_test(check_directory 2 "tests/data: is a directory, not a mesh file" check ${data})
# `check -` reads standard input (tests/cli/cli_io_tests.cmake); nothing piped in is bad input.
morphex_sh_test(check_stdin 2 "<stdin>: empty input" "${mx} check - < /dev/null")
# Several files at once: one JSON line each, an unreadable one as an error object; worst exit code.
morphex_cli_test(check_many_json 2
  "\"file\":\"[^\"]*unit_cube.off\".*\"valid\":true.*\"error\":\"[^\"]*does_not_exist.off: cannot open file.*\"valid\":false.*\"border_edges\":4"
  check --json ${data}/unit_cube.off ${data}/does_not_exist.off ${data}/open_cube.off)
morphex_cli_test(check_many_invalid 1 "unit_cube.off: valid closed solid.*open_cube.off: NOT a valid solid"
  check ${data}/unit_cube.off ${data}/open_cube.off)
# Issue 44: outputs never replace inputs, every output path checked before work, deep JSON, small
# memory limits, failed writes to standard output, decimal volumes, typos, folders and help.
foreach(item side_outputs same_stem deep_json stdout_full volume folders typos inputs help)
  add_test(NAME cli.outputs_${item} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/outputs.sh
    $<TARGET_FILE:morphex> ${data} ${PROJECT_BINARY_DIR}/cli-outputs ${item})
endforeach()
if(NOT MORPHEX_SANITIZE MATCHES "address")  # see cli.max_memory
  add_test(NAME cli.outputs_memory COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/outputs.sh
    $<TARGET_FILE:morphex> ${data} ${PROJECT_BINARY_DIR}/cli-outputs memory)
endif()
