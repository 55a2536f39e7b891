# Locates GMP (C and C++ bindings), Eigen 3.4, Boost headers and doctest.
find_path(GMP_INCLUDE_DIR gmpxx.h REQUIRED)
find_library(GMP_LIBRARY gmp REQUIRED)
find_library(GMPXX_LIBRARY gmpxx REQUIRED)
if(NOT TARGET igm::gmp)
  add_library(igm::gmp INTERFACE IMPORTED)
  set_target_properties(igm::gmp PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${GMP_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${GMP_LIBRARY}")
  add_library(igm::gmpxx INTERFACE IMPORTED)
  set_target_properties(igm::gmpxx PROPERTIES
    INTERFACE_LINK_LIBRARIES "${GMPXX_LIBRARY};igm::gmp")
endif()
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(Boost 1.74 REQUIRED)
if(IGM_BUILD_TESTS)
  find_package(doctest REQUIRED)
  include(doctest)
endif()
