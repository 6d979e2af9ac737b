# Install rules: headers of every stage, the library, the tool, and an
# exported package so that find_package(hgridlab) gives hgridlab::core and
# hgridlab::hgridlab.
include(CMakePackageConfigHelpers)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hgridlab
        FILES_MATCHING PATTERN "*.hpp" PATTERN "cli" EXCLUDE
        PATTERN "mpi" EXCLUDE)  # the tool's MPI layer: not installed (its library is not)
install(FILES ${HGRID_VERSION_HPP} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hgridlab/grid)
# Two components, each with its own export file: core (the header-only grid,
# whose one dependency is OpenMP) and hgridlab (the library, with HDF5, GSL,
# nlohmann-json and toml++), so that a C++-only project can use the core.
install(TARGETS hgridlab_core EXPORT hgridlabCoreTargets INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
if(HGRID_BUILD_LIBRARY)
  install(TARGETS hgridlab EXPORT hgridlabTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
if(HGRID_BUILD_CLI)
  install(TARGETS hgrid RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
set(HGRID_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/hgridlab)
install(EXPORT hgridlabCoreTargets NAMESPACE hgridlab:: DESTINATION ${HGRID_CMAKE_DIR})
if(HGRID_BUILD_LIBRARY)
  install(EXPORT hgridlabTargets NAMESPACE hgridlab:: DESTINATION ${HGRID_CMAKE_DIR})
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/hgridlabConfig.cmake.in
  ${PROJECT_BINARY_DIR}/hgridlabConfig.cmake INSTALL_DESTINATION ${HGRID_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/hgridlabConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/hgridlabConfig.cmake ${PROJECT_BINARY_DIR}/hgridlabConfigVersion.cmake
        DESTINATION ${HGRID_CMAKE_DIR})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CITATION.cff
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/hgridlab)
