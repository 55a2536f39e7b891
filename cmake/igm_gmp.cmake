# GMP (C and C++ bindings) as the imported targets igm::gmp and igm::gmpxx; sets IGM_GMP_FOUND.
# Used by the build (igm_deps.cmake, where a miss is fatal) and by the installed package config
# (igmConfig.cmake, where a miss makes find_package(igm) fail with a message).
find_path(GMP_INCLUDE_DIR gmpxx.h)
find_library(GMP_LIBRARY gmp)
find_library(GMPXX_LIBRARY gmpxx)
if(GMP_INCLUDE_DIR AND GMP_LIBRARY AND GMPXX_LIBRARY)
  set(IGM_GMP_FOUND TRUE)
else()
  set(IGM_GMP_FOUND FALSE)
endif()
if(IGM_GMP_FOUND AND NOT TARGET igm::gmp)
  add_library(igm::gmp INTERFACE IMPORTED)
  set_target_properties(igm::gmp PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${GMP_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${GMP_LIBRARY}")
  add_library(igm::gmpxx INTERFACE IMPORTED)
  set_target_properties(igm::gmpxx PROPERTIES
    INTERFACE_LINK_LIBRARIES "${GMPXX_LIBRARY};igm::gmp")
endif()
