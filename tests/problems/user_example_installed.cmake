# CTest script: install OCPBench into a fresh prefix, configure and build the user example
# (examples/user_example/) as an outside project against that install, and run:
#  - my_problem (exits non-zero when a method misses the known optimum);
#  - my_bounded_problem (state bounds and a free initial state; the same);
#  - my_ocpbench, a full `ocpbench` with the example's problem and solver registered: its solver
#    is listed and described, a bad option of it is refused like a built-in's (exit 2, the valid
#    keys listed), and the example suite mixing it with built-in methods runs, with its rows in
#    summary.md and every record valid against results/record.schema.json.
# The install comes from BUILD_DIR, or with PLAIN=ON from a build made here the way the user
# guide documents it (no preset, the default generator and compiler, Release, warnings not
# errors): the path a user takes, which the presets' builds do not cover (their unity batches
# and flags differ).
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... (-DBUILD_DIR=... -DCXX=... | -DPLAIN=ON [-DJOBS=n])
#         [-DFLAGS=...] [-DLINK_FLAGS=...] -P this
set(required SOURCE_DIR WORK_DIR)
if(NOT PLAIN)
  list(APPEND required BUILD_DIR CXX)
endif()
foreach(var ${required})
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "user_example_installed: ${var} is not set")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "user_example_installed: '${ARGN}' failed (${rc})")
  endif()
endfunction()
set(example_compiler)
if(PLAIN)
  # The user guide's install (examples/user_example/README.md, section 1), with one addition:
  # CMAKE_UNITY_BUILD=ON, one translation unit per library, which bounds the test's cost (GCC 12,
  # this build: 387 s of CPU in unity batches against 974 s file by file, measured 2026-12-06).
  # The file-by-file build was checked by hand (results/notes/2026-12-06-plain-builds.md).
  if(NOT JOBS)
    set(JOBS 2)
  endif()
  set(BUILD_DIR ${WORK_DIR}/ocpbench-build)
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BUILD_DIR} -DCMAKE_BUILD_TYPE=Release
      -DOCPB_BUILD_TESTS=OFF -DOCPB_BUILD_BENCHMARKS=OFF -DCMAKE_UNITY_BUILD=ON
      -DCMAKE_UNITY_BUILD_BATCH_SIZE=0)
  run(${CMAKE_COMMAND} --build ${BUILD_DIR} --parallel ${JOBS})
else()
  set(example_compiler -DCMAKE_CXX_COMPILER=${CXX})
endif()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
# FLAGS (the tests' build: an optimization level, which must be given, and its sanitizers)
# replace the Release type's own -O3 when given; without them the example builds as the user
# guide says.
set(example_flags)
if(FLAGS)
  set(example_flags -DCMAKE_CXX_FLAGS_RELEASE=-DNDEBUG)
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/user_example -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix ${example_compiler} ${example_flags}
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=${FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS} ${LINK_FLAGS}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/my_problem)
run(${WORK_DIR}/build/my_bounded_problem)

set(cli ${WORK_DIR}/build/my_ocpbench)
function(expect_output what needle)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${out}${err}" "${needle}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "user_example_installed: ${what}: '${needle}' not in the output of "
                        "'${ARGN}' (exit ${rc}):\n${out}${err}")
  endif()
  set(last_rc ${rc} PARENT_SCOPE)
endfunction()
expect_output("list" "projected-gradient" ${cli} list solvers)
expect_output("describe" "max_backtracks (integer, default 40)" ${cli} describe solver projected-gradient)
expect_output("bad option" "projected-gradient: unknown option 'stepsize' (valid: step, "
              ${cli} solve --problem my-lq --solver projected-gradient --option stepsize=2)
if(NOT last_rc EQUAL 2)
  message(FATAL_ERROR "user_example_installed: a bad option exited ${last_rc}, not 2")
endif()
run(${cli} run ${SOURCE_DIR}/examples/user_example/my_suite.json --out ${WORK_DIR}/results)
file(READ ${WORK_DIR}/results/summary.md summary)
foreach(row "| projected-gradient, penalty, N=50 | 1 | 1 converged |"
            "| hamiltonian, penalty, N=50 |" "| ipopt + euler, penalty, N=50 |")
  string(FIND "${summary}" "${row}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "user_example_installed: no row '${row}' in summary.md:\n${summary}")
  endif()
endforeach()
run(/usr/bin/python3 ${SOURCE_DIR}/tests/tools/validate_records.py
    --schema ${SOURCE_DIR}/results/record.schema.json --min-records 5 ${WORK_DIR}/results)
file(REMOVE_RECURSE ${WORK_DIR})
