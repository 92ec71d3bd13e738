# The talus Python package, assembled in <build>/python/talus so that `import talus` works from
# the build tree without installing:
#   - pure-Python files from python/ (the package root and the project-wide tools: cli, results,
#     report, bench, plot, batch) and from every enabled component's python/ folder (talus.dem,
#     talus.flow, ... and the drop-in packages),
#   - the compiled modules (talus._dem, talus._flow, ...), one per component,
#   - the generated _build_config.py.
# The `talus` command (bin/talus) is a launcher that puts the package on sys.path.

set(TALUS_PYTHON_BUILD_DIR ${PROJECT_BINARY_DIR}/python)
set(TALUS_PYTHON_INSTALL_DIR
    "lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages"
    CACHE STRING "Where `cmake --install` puts the talus package, relative to the prefix")

## talus_python_module(<name> <source> <libraries...> [SOURCES <more sources...>]): compiled
## module talus.<name>, built from <source> and any further SOURCES.
function(talus_python_module name source)
  cmake_parse_arguments(PARSE_ARGV 2 MODULE "" "" "SOURCES")
  pybind11_add_module(${name} MODULE ${source} ${MODULE_SOURCES})
  target_link_libraries(${name} PRIVATE ${MODULE_UNPARSED_ARGUMENTS})
  talus_target_defaults(${name})
  # pybind11 code trips a few of our stricter warnings; they are not ours to fix.
  target_compile_options(${name} PRIVATE -Wno-old-style-cast)
  file(RELATIVE_PATH lib_from_python /${TALUS_PYTHON_INSTALL_DIR}/talus /${CMAKE_INSTALL_LIBDIR})
  set_target_properties(${name} PROPERTIES
    LIBRARY_OUTPUT_DIRECTORY ${TALUS_PYTHON_BUILD_DIR}/talus
    INSTALL_RPATH "$ORIGIN/${lib_from_python}")
  install(TARGETS ${name} LIBRARY DESTINATION ${TALUS_PYTHON_INSTALL_DIR}/talus)
endfunction()

## talus_assemble_python_package(): copy the pure-Python files and write the launchers. The
## top-level python/ folder holds the root of the package `talus`; each component's python/
## folder holds its sub-package (talus.<component>) and may hold drop-in packages with a peer's
## names (dem/python/yade: Yade's scripting interface).
function(talus_assemble_python_package)
  set(outputs)
  set(roots ${PROJECT_SOURCE_DIR}/python)
  foreach(component dem flow coupling fem)
    if(TALUS_COMPONENT_${component} AND EXISTS ${PROJECT_SOURCE_DIR}/${component}/python)
      list(APPEND roots ${PROJECT_SOURCE_DIR}/${component}/python)
    endif()
  endforeach()
  foreach(root IN LISTS roots)
    file(GLOB_RECURSE sources CONFIGURE_DEPENDS RELATIVE ${root} ${root}/*.py)
    foreach(rel IN LISTS sources)
      set(out ${TALUS_PYTHON_BUILD_DIR}/${rel})
      add_custom_command(OUTPUT ${out}
        COMMAND ${CMAKE_COMMAND} -E copy_if_different ${root}/${rel} ${out}
        DEPENDS ${root}/${rel} COMMENT "" VERBATIM)
      list(APPEND outputs ${out})
    endforeach()
  endforeach()
  set(config ${TALUS_PYTHON_BUILD_DIR}/talus/_build_config.py)
  add_custom_command(OUTPUT ${config}
    COMMAND ${CMAKE_COMMAND} -E copy_if_different ${PROJECT_BINARY_DIR}/generated/_build_config.py ${config}
    DEPENDS ${PROJECT_BINARY_DIR}/generated/_build_config.py VERBATIM)
  list(APPEND outputs ${config})
  add_custom_target(talus_python ALL DEPENDS ${outputs})

  # Launchers: the build-tree one points at <build>/python, the installed one at the package
  # directory relative to its own location, so an installed prefix can be moved.
  set(TALUS_LAUNCHER_PYTHON_DIR "${TALUS_PYTHON_BUILD_DIR}")
  configure_file(${PROJECT_SOURCE_DIR}/cmake/talus-launcher.in ${PROJECT_BINARY_DIR}/bin/talus @ONLY
                 FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                                  WORLD_READ WORLD_EXECUTE)
  file(RELATIVE_PATH python_from_bin /${CMAKE_INSTALL_BINDIR} /${TALUS_PYTHON_INSTALL_DIR})
  set(TALUS_LAUNCHER_PYTHON_DIR "relative:${python_from_bin}")
  configure_file(${PROJECT_SOURCE_DIR}/cmake/talus-launcher.in
                 ${PROJECT_BINARY_DIR}/generated/talus-installed @ONLY)

  install(DIRECTORY ${TALUS_PYTHON_BUILD_DIR}/ DESTINATION ${TALUS_PYTHON_INSTALL_DIR}
          FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
  install(PROGRAMS ${PROJECT_BINARY_DIR}/generated/talus-installed
          DESTINATION ${CMAKE_INSTALL_BINDIR} RENAME talus)
endfunction()
