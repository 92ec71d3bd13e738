# Finds CHOLMOD (SuiteSparse) and defines the imported target CHOLMOD::CHOLMOD.
# Debian's libsuitesparse-dev ships no CMake package, so headers and libraries are located here.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig)
if(CHOLMOD_INCLUDE_DIR AND EXISTS ${CHOLMOD_INCLUDE_DIR}/cholmod_core.h)
  file(STRINGS ${CHOLMOD_INCLUDE_DIR}/cholmod_core.h _ver REGEX "#define CHOLMOD_(MAIN|SUB|SUBSUB)_VERSION ")
  string(REGEX REPLACE ".*CHOLMOD_MAIN_VERSION +([0-9]+).*" "\\1" _major "${_ver}")
  string(REGEX REPLACE ".*CHOLMOD_SUB_VERSION +([0-9]+).*" "\\1" _minor "${_ver}")
  string(REGEX REPLACE ".*SUBSUB_VERSION +([0-9]+).*" "\\1" _patch "${_ver}")
  set(CHOLMOD_VERSION "${_major}.${_minor}.${_patch}")
endif()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS CHOLMOD_LIBRARY SUITESPARSE_CONFIG_LIBRARY CHOLMOD_INCLUDE_DIR
  VERSION_VAR CHOLMOD_VERSION)
if(CHOLMOD_FOUND AND NOT TARGET CHOLMOD::CHOLMOD)
  add_library(CHOLMOD::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(CHOLMOD::CHOLMOD PROPERTIES
    IMPORTED_LOCATION ${CHOLMOD_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${CHOLMOD_INCLUDE_DIR}
    INTERFACE_LINK_LIBRARIES ${SUITESPARSE_CONFIG_LIBRARY})
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY SUITESPARSE_CONFIG_LIBRARY)
