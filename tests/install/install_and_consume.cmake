# Installs the sphys build tree into a scratch prefix, then configures and builds a small project
# that uses it only through find_package(sphys), and runs the result.
# Inputs: SPHYS_BUILD_DIR, CONSUMER_SOURCE_DIR, SPHYS_EXAMPLES_DIR (examples/, whose
# hello_world.cpp the consumer builds too), WORK_DIR; with the Python module, PYTHON and
# PYTHON_PACKAGE_DIR (where the package is installed, relative to the prefix).
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

function(run_step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "step failed (${result}): ${ARGN}\n${out}")
  endif()
endfunction()

run_step("${CMAKE_COMMAND}" --install "${SPHYS_BUILD_DIR}" --prefix "${prefix}")
run_step("${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${WORK_DIR}/build" -G Ninja
         -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}"
         "-DSPHYS_EXAMPLES_DIR=${SPHYS_EXAMPLES_DIR}")
run_step("${CMAKE_COMMAND}" --build "${WORK_DIR}/build")
run_step("${WORK_DIR}/build/runtime_consumer")
run_step("${WORK_DIR}/build/tools_consumer")
# Ten bunnies dropped: ten poses, every one above the plane (y >= 0 m) and none of them NaN.
execute_process(COMMAND "${WORK_DIR}/build/hello_world" RESULT_VARIABLE result OUTPUT_VARIABLE poses
                ERROR_VARIABLE poses)
string(REGEX MATCHALL "position +[-0-9.]+ +[0-9.]+ +[-0-9.]+ m" above "${poses}")
list(LENGTH above count)
if(NOT result EQUAL 0 OR NOT count EQUAL 10)
  message(FATAL_ERROR "hello_world (${result}): expected ten poses above the plane, got\n${poses}")
endif()
if(DEFINED PYTHON)
  # The installed package, not the build tree's: a cube of side 2 m at 1000 kg/m^3 weighs 8000 kg.
  set(site "${prefix}/${PYTHON_PACKAGE_DIR}")
  run_step("${CMAKE_COMMAND}" -E env "PYTHONPATH=${site}" "${PYTHON}" -c
           "import sys, sphys; assert sphys.__file__.startswith(sys.argv[1]), sphys.__file__; \
m = sphys.mass_properties(sphys.box((2.0, 2.0, 2.0)), density=1000.0).mass; assert abs(m - 8000.0) < 1e-9, m"
           "${site}")
endif()
message(STATUS "installed sphys consumed from ${prefix}")
