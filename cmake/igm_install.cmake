# `cmake --install BUILD --prefix P`: the public headers (P/include/igm, P/include/certify), the
# libraries (libigm_core.a, libigm_certify.a), the CLIs (igm, igm-certify) and the CMake package
# (P/lib/cmake/igm: igmConfig.cmake, igmConfigVersion.cmake, igmTargets.cmake), so that a
# consumer's find_package(igm) + target_link_libraries(app igm::core) works.
# Checked by tests/package (CTest package/consumer).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set_target_properties(igm_core PROPERTIES EXPORT_NAME core)
set_target_properties(igm_certify PROPERTIES EXPORT_NAME certify)
set(IGM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/igm)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/igm ${PROJECT_SOURCE_DIR}/certify/include/certify
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS igm_core igm_certify EXPORT igmTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS igm igm-certify RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT igmTargets NAMESPACE igm:: DESTINATION ${IGM_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/igmConfig.cmake.in
  ${PROJECT_BINARY_DIR}/igmConfig.cmake INSTALL_DESTINATION ${IGM_CMAKE_DIR})
# 0.x: a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/igmConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/igmConfig.cmake ${PROJECT_BINARY_DIR}/igmConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/igm_gmp.cmake
              ${PROJECT_SOURCE_DIR}/cmake/igm_solvers.cmake
        DESTINATION ${IGM_CMAKE_DIR})
