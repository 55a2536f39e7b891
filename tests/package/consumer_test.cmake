# CTest package/consumer (cmake -P): installs this build into WORK/prefix, checks the installed
# files, then configures, builds and runs tests/package/consumer against it.
# Variables: BUILD_DIR, SOURCE_DIR (tests/package/consumer), WORK, CXX, BUILD_TYPE, LAUNCHER
# (may be empty), SANITIZE (ON/OFF: the installed libraries then need the sanitizer runtimes).
file(REMOVE_RECURSE ${WORK})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK}/prefix)
foreach(f bin/igm bin/igm-certify include/igm/pipeline/pipeline.h include/certify/certify.h
          lib/libigm_core.a lib/libigm_certify.a lib/cmake/igm/igmConfig.cmake
          lib/cmake/igm/igmConfigVersion.cmake lib/cmake/igm/igmTargets.cmake)
  if(NOT EXISTS ${WORK}/prefix/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
run(${WORK}/prefix/bin/igm --help)

set(args -DCMAKE_PREFIX_PATH=${WORK}/prefix -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX})
if(LAUNCHER)
  list(APPEND args -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
if(SANITIZE)
  list(APPEND args "-DCMAKE_CXX_FLAGS=-fsanitize=address,undefined"
                   "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined")
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK}/build ${args})
run(${CMAKE_COMMAND} --build ${WORK}/build)
execute_process(COMMAND ${WORK}/build/igm_consumer RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "igm_consumer: ${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "igm_consumer exited ${rc}")
endif()
# A version the package does not offer is refused.
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK}/build-v9 ${args} -DIGM_WANT=9.0
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "find_package(igm 9.0) succeeded against version 0.x")
endif()
