# Locates GMP (C and C++ bindings, cmake/igm_gmp.cmake), Eigen 3.4, Boost headers, Threads, the
# solvers (cmake/igm_solvers.cmake: CHOLMOD, oneTBB, Spectra, CBC) and, for the tests, doctest. The installed igmConfig.cmake (cmake/igmConfig.cmake.in) finds the
# same libraries again for a consumer.
include(${CMAKE_CURRENT_LIST_DIR}/igm_gmp.cmake)
if(NOT IGM_GMP_FOUND)
  message(FATAL_ERROR "GMP with its C++ bindings (gmpxx.h, libgmp, libgmpxx) not found: apt-get install libgmp-dev")
endif()
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(Boost 1.74 REQUIRED)
find_package(Threads REQUIRED)
include(${CMAKE_CURRENT_LIST_DIR}/igm_solvers.cmake)
if(NOT IGM_SOLVERS_FOUND)
  message(FATAL_ERROR "missing: ${IGM_SOLVERS_MISSING} (bash scripts/install-deps.sh installs them)")
endif()
if(IGM_BUILD_TESTS)
  find_package(doctest REQUIRED)
  include(doctest)
endif()
