# The Debian-packaged solvers igm builds on (design card): SuiteSparse's CHOLMOD (sparse Cholesky),
# oneTBB (threads), Spectra (eigenproblems, headers only) and COIN-OR CBC (integer programs), as
# the imported targets igm::cholmod, igm::tbb, igm::spectra and igm::cbc; sets IGM_SOLVERS_FOUND
# and IGM_SOLVERS_MISSING. Used by the build (igm_deps.cmake, where a miss is fatal) and by the
# installed package config (igmConfig.cmake): the static igm::core links them.
set(IGM_SOLVERS_MISSING "")

find_path(IGM_CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(IGM_CHOLMOD_LIBRARY cholmod)
find_library(IGM_SUITESPARSECONFIG_LIBRARY suitesparseconfig)
if(IGM_CHOLMOD_INCLUDE_DIR AND IGM_CHOLMOD_LIBRARY AND IGM_SUITESPARSECONFIG_LIBRARY)
  if(NOT TARGET igm::cholmod)
    add_library(igm::cholmod INTERFACE IMPORTED)
    set_target_properties(igm::cholmod PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${IGM_CHOLMOD_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${IGM_CHOLMOD_LIBRARY};${IGM_SUITESPARSECONFIG_LIBRARY}")
  endif()
else()
  list(APPEND IGM_SOLVERS_MISSING "CHOLMOD (libsuitesparse-dev)")
endif()

find_package(TBB CONFIG QUIET)
if(TBB_FOUND)
  if(NOT TARGET igm::tbb)
    add_library(igm::tbb INTERFACE IMPORTED)
    set_target_properties(igm::tbb PROPERTIES INTERFACE_LINK_LIBRARIES TBB::tbb)
  endif()
else()
  list(APPEND IGM_SOLVERS_MISSING "oneTBB (libtbb-dev)")
endif()

find_path(IGM_SPECTRA_INCLUDE_DIR Spectra/SymEigsShiftSolver.h)
if(IGM_SPECTRA_INCLUDE_DIR)
  if(NOT TARGET igm::spectra)
    add_library(igm::spectra INTERFACE IMPORTED)
    set_target_properties(igm::spectra PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${IGM_SPECTRA_INCLUDE_DIR}")
  endif()
else()
  list(APPEND IGM_SOLVERS_MISSING "Spectra (libspectra-dev)")
endif()

find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(IGM_CBC QUIET IMPORTED_TARGET GLOBAL cbc)
endif()
if(IGM_CBC_FOUND)
  if(NOT TARGET igm::cbc)
    add_library(igm::cbc INTERFACE IMPORTED)
    set_target_properties(igm::cbc PROPERTIES INTERFACE_LINK_LIBRARIES PkgConfig::IGM_CBC)
  endif()
else()
  list(APPEND IGM_SOLVERS_MISSING "CBC (coinor-libcbc-dev, pkg-config)")
endif()

if(IGM_SOLVERS_MISSING)
  set(IGM_SOLVERS_FOUND FALSE)
else()
  set(IGM_SOLVERS_FOUND TRUE)
endif()
