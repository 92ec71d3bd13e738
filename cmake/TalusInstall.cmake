# `cmake --install`: libraries, headers, the Python package, the talus command, and a CMake
# package so another project can `find_package(Talus)` and link Talus::dem (and friends).
include(CMakePackageConfigHelpers)

set(TALUS_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Talus)
get_property(_talus_targets GLOBAL PROPERTY TALUS_INSTALL_TARGETS)
set_target_properties(${_talus_targets} PROPERTIES INSTALL_RPATH "$ORIGIN")
install(TARGETS ${_talus_targets} EXPORT TalusTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT TalusTargets NAMESPACE Talus:: DESTINATION ${TALUS_CMAKE_INSTALL_DIR})

set(TALUS_INSTALLED_COMPONENTS)
get_property(_names GLOBAL PROPERTY TALUS_COMPONENT_NAMES)
foreach(_name IN LISTS _names)
  if(TALUS_COMPONENT_${_name})
    list(APPEND TALUS_INSTALLED_COMPONENTS ${_name})
  endif()
endforeach()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/TalusConfig.cmake.in
  ${PROJECT_BINARY_DIR}/generated/TalusConfig.cmake INSTALL_DESTINATION ${TALUS_CMAKE_INSTALL_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/generated/TalusConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/generated/TalusConfig.cmake
              ${PROJECT_BINARY_DIR}/generated/TalusConfigVersion.cmake
        DESTINATION ${TALUS_CMAKE_INSTALL_DIR})
