# `morphex run|validate|stages`: exit codes 0 / 1 / 2 of docs/conventions.md, reports, messages.
set(pipelines ${data}/pipelines)
set(pipe_out ${PROJECT_BINARY_DIR}/cli-pipeline-out)
file(MAKE_DIRECTORY ${pipe_out})
morphex_cli_test(stages_list 0 "dilate +dilation A . B.*minkowski +exact Minkowski" stages)
morphex_cli_test(stages_dilate 0 "se +structuring element +required.*ball:.*level" stages dilate)
morphex_cli_test(stages_unknown 2 "unknown stage 'erosion' \\(did you mean 'erode'\\?\\)" stages erosion)
morphex_cli_test(validate_ok 0 "valid pipeline, 3 stages" validate ${pipelines}/grow.json --set out_dir=/tmp)
morphex_cli_test(validate_missing_variable 2 "pipeline\\[2\\].path: unknown variable \\$\\{out_dir\\}"
  validate ${pipelines}/grow.json)
morphex_cli_test(validate_all_problems 2
  "pipeline\\[1\\].se.r: expected a positive number, got -1.*pipeline\\[2\\].type: unknown stage 'dilation' \\(did you mean 'dilate'\\?\\).*pipeline\\[3\\].inputs\\[1\\]: unknown tag 'opend'"
  validate ${pipelines}/invalid.json)
morphex_cli_test(validate_malformed 2 "malformed.json:2:[0-9]+: malformed JSON" validate ${pipelines}/malformed.json)
morphex_cli_test(validate_examples 0 "valid pipeline" validate ${PROJECT_SOURCE_DIR}/pipelines/examples/top-hat.json)
morphex_cli_test(run_invalid_runs_nothing 2 "unknown stage" run ${pipelines}/invalid.json
  --input ${data}/unit_cube.off)
morphex_cli_test(run_two_inputs 0 "2 runs, 2 succeeded, 0 failed"
  run ${pipelines}/grow.json --set out_dir=${pipe_out} --input ${data}/unit_cube.off ${data}/third_cube_exact.off)
morphex_cli_test(run_report 0 "\"name\":\"unit_cube\".*\"type\":\"dilate\".*\"volume\":\"27/8\""
  run ${pipelines}/grow.json --set out_dir=${pipe_out} --input ${data}/unit_cube.off --report -)
morphex_cli_test(run_one_bad_input 1
  "3 runs, 2 succeeded, 1 failed.*open_cube.off: pipeline\\[0\\] \\(read\\): .*open_cube.off: mesh is not closed"
  run ${pipelines}/grow.json --set out_dir=${pipe_out} --set r=1/2
  --input ${data}/unit_cube.off ${data}/open_cube.off ${data}/third_cube_exact.off)
morphex_cli_test(run_glob 0 "2 runs, 2 succeeded, 0 failed"
  run ${pipelines}/grow.json --set out_dir=${pipe_out} --input "${data}/[ut]*_*.off")
morphex_cli_test(run_bad_set 2 "--set r: expected name=value" run ${pipelines}/grow.json --set r)
# a --set that names no ${variable} of the pipeline is a mistake, not silently ignored
morphex_cli_test(run_unused_set 2 "--set out_dri: the pipeline uses no \\$\\{out_dri\\}"
  run ${pipelines}/grow.json --set out_dri=${pipe_out} --input ${data}/unit_cube.off)
morphex_cli_test(validate_unused_set 2 "--set nosuch: the pipeline uses no"
  validate ${pipelines}/grow.json --set nosuch=1)
# one parser for run, validate and index: an empty name is refused everywhere
morphex_cli_test(validate_bad_set 2 "--set =1/2: expected name=value"
  validate ${pipelines}/grow.json --set =1/2)
# validate looks at the files too (issue 23): a read of a missing file and a write whose folder
# cannot be created are reported with their stage, before anything runs; paths with a deferred
# ${input} are left to the run.
morphex_cli_test(validate_missing_files 2
  "pipeline\\[0\\].path: no such file '[^']*does_not_exist.off' \\(stage read#0\\).*pipeline\\[2\\].path: cannot create the folder [^ ]*unit_cube.off/out: [^ ]*unit_cube.off is not a folder \\(stage write#2\\)"
  validate ${pipelines}/missing_files.json --set dir=${data})
morphex_cli_test(validate_missing_input 2 "pipeline\\[0\\].path: no such file '[^']*nosuch.off'"
  validate ${pipelines}/grow.json --set out_dir=${pipe_out} --input ${data}/nosuch.off)
