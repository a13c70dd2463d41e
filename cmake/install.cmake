# Installs the headers, the CLI and each library as a component of the CMake package specula
# (core, fit, cost, queries, render, gl, report, serve: cmake/specula-components.cmake), so that
# another project can say find_package(specula COMPONENTS core) and link specula::core — and need
# none of the packages that only render, gl, report or serve link. find_package(specula)
# without components loads them all and specula::specula, which links every one.
include(CMakePackageConfigHelpers)
include(${CMAKE_CURRENT_LIST_DIR}/specula-components.cmake)

# The components named in specula-components.cmake are exactly the libraries src/ makes.
get_property(built DIRECTORY ${PROJECT_SOURCE_DIR}/src PROPERTY BUILDSYSTEM_TARGETS)
list(FILTER built INCLUDE REGEX "^specula_")
list(TRANSFORM built REPLACE "^specula_" "")
set(listed ${specula_components})
list(SORT built)
list(SORT listed)
if(NOT built STREQUAL listed)
  message(FATAL_ERROR "cmake/specula-components.cmake lists the components '${listed}' but src/ builds "
                      "the libraries '${built}': add the new library's component there")
endif()

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/specula)
install(DIRECTORY include/specula DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# One export set and file per component: specula-<component>-targets.cmake defines
# specula::<component>, which refers to the components it builds on by their exported names.
foreach(component IN LISTS specula_components)
  install(TARGETS specula_${component} EXPORT specula-${component} ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT specula-${component} NAMESPACE specula:: FILE specula-${component}-targets.cmake
          DESTINATION ${config_dir})
endforeach()
install(TARGETS specula EXPORT specula-all)
install(EXPORT specula-all NAMESPACE specula:: FILE specula-all-targets.cmake DESTINATION ${config_dir})
install(TARGETS specula_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

configure_package_config_file(cmake/speculaConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/speculaConfig.cmake INSTALL_DESTINATION ${config_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/speculaConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/speculaConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/speculaConfigVersion.cmake
              ${CMAKE_CURRENT_LIST_DIR}/specula-components.cmake
        DESTINATION ${config_dir})
