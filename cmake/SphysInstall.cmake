# Installs headers, libraries and a CMake package:
#   find_package(sphys)                   -> sphys::sphys  (runtime: Eigen, oneTBB)
#   find_package(sphys COMPONENTS tools)  -> sphys::tools  (offline: meshes, construction, files)
include(CMakePackageConfigHelpers)
set(SPHYS_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/sphys")

install(DIRECTORY include/sphys DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")

install(TARGETS sphys EXPORT sphysTargets
        ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
        LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}")
install(EXPORT sphysTargets NAMESPACE sphys:: DESTINATION "${SPHYS_CMAKE_DIR}")

if(SPHYS_BUILD_TOOLS)
  install(TARGETS sphys-tools EXPORT sphysToolsTargets
          ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
          LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}")
  install(EXPORT sphysToolsTargets NAMESPACE sphys:: DESTINATION "${SPHYS_CMAKE_DIR}")
  install(TARGETS sphys-cli RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
endif()

configure_package_config_file(cmake/sphysConfig.cmake.in
                              "${CMAKE_CURRENT_BINARY_DIR}/sphysConfig.cmake"
                              INSTALL_DESTINATION "${SPHYS_CMAKE_DIR}")
write_basic_package_version_file("${CMAKE_CURRENT_BINARY_DIR}/sphysConfigVersion.cmake"
                                 COMPATIBILITY SameMinorVersion)
install(FILES "${CMAKE_CURRENT_BINARY_DIR}/sphysConfig.cmake"
              "${CMAKE_CURRENT_BINARY_DIR}/sphysConfigVersion.cmake"
        DESTINATION "${SPHYS_CMAKE_DIR}")
