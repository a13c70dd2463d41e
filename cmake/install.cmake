# Installs headers, the static library and a CMake package so that another project can say
# find_package(specula) and link specula::specula.
include(CMakePackageConfigHelpers)

install(DIRECTORY include/specula DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS specula EXPORT speculaTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS specula_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/specula)
install(EXPORT speculaTargets NAMESPACE specula:: DESTINATION ${config_dir})
configure_package_config_file(cmake/speculaConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/speculaConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/speculaConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/speculaConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/speculaConfigVersion.cmake
        DESTINATION ${config_dir})
