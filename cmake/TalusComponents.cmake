# Bookkeeping of components (dem, flow, ...) and optional features (openmp, hdf5, ...).
#
# Each has an ON/OFF state and a one-line note: for ON, what was found; for OFF, why it is off.
# States live in internal cache variables (TALUS_COMPONENT_<name>, TALUS_FEATURE_<name>) so a
# component folder can switch itself off when it finds a dependency missing, and every other
# folder sees the result. They are recomputed on every configure.

function(_talus_set kind name enabled note)
  if(enabled)
    set(state ON)
  else()
    set(state OFF)
  endif()
  set(TALUS_${kind}_${name} ${state} CACHE INTERNAL "")
  set(TALUS_${kind}_${name}_NOTE "${note}" CACHE INTERNAL "")
  get_property(names GLOBAL PROPERTY TALUS_${kind}_NAMES)
  if(NOT name IN_LIST names)
    set_property(GLOBAL APPEND PROPERTY TALUS_${kind}_NAMES ${name})
  endif()
endfunction()

## talus_component(<name> <enabled> <note>): declare or update a component.
function(talus_component name enabled note)
  _talus_set(COMPONENT ${name} "${enabled}" "${note}")
endfunction()

## talus_feature(<name> <enabled> <note>): declare or update an optional feature.
function(talus_feature name enabled note)
  _talus_set(FEATURE ${name} "${enabled}" "${note}")
endfunction()

## talus_need_mpi(<COMPONENT|FEATURE> <name> <out-var>): <out-var> TRUE when MPI and an mpirun
## (cached as TALUS_MPIEXEC) are found; otherwise FALSE, and <name> is switched off with the reason.
function(talus_need_mpi kind name out)
  set(${out} FALSE PARENT_SCOPE)
  if(NOT MPI_FOUND)
    _talus_set(${kind} ${name} OFF "MPI not found (apt-get install libopenmpi-dev openmpi-bin)")
    return()
  endif()
  find_program(TALUS_MPIEXEC NAMES mpirun mpiexec)
  if(NOT TALUS_MPIEXEC)
    _talus_set(${kind} ${name} OFF "MPI headers found but no mpirun (apt-get install openmpi-bin)")
    return()
  endif()
  set(${out} TRUE PARENT_SCOPE)
endfunction()

## talus_config_entries(<out-var>): "name:ON:note" items of all components, then all features.
function(_talus_entries kind out)
  get_property(names GLOBAL PROPERTY TALUS_${kind}_NAMES)
  set(entries)
  foreach(name IN LISTS names)
    list(APPEND entries "${name}|${TALUS_${kind}_${name}}|${TALUS_${kind}_${name}_NOTE}")
  endforeach()
  set(${out} "${entries}" PARENT_SCOPE)
endfunction()

## _talus_split_entry(<entry> <name-var> <state-var> <note-var>): the fields of an entry of
## _talus_entries.
macro(_talus_split_entry entry name state note)
  string(REPLACE "|" ";" _talus_parts "${entry}")
  list(GET _talus_parts 0 ${name})
  list(GET _talus_parts 1 ${state})
  list(GET _talus_parts 2 ${note})
endmacro()

## talus_write_build_config(): write the component table for C++ (header) and Python (module).
function(talus_write_build_config)
  set(cxx_rows "")
  set(py_components "")
  set(py_features "")
  foreach(kind COMPONENT FEATURE)
    _talus_entries(${kind} entries)
    foreach(entry IN LISTS entries)
      _talus_split_entry("${entry}" name state note)
      string(REPLACE "\"" "'" note "${note}")
      if(state)
        set(py_state True)
        set(cxx_state true)
      else()
        set(py_state False)
        set(cxx_state false)
      endif()
      string(TOLOWER ${kind} lkind)
      string(APPEND cxx_rows "    {\"${lkind}\", \"${name}\", ${cxx_state}, \"${note}\"},\n")
      if(kind STREQUAL COMPONENT)
        string(APPEND py_components "    \"${name}\": (${py_state}, \"${note}\"),\n")
      else()
        string(APPEND py_features "    \"${name}\": (${py_state}, \"${note}\"),\n")
      endif()
    endforeach()
  endforeach()
  set(TALUS_CONFIG_CXX_ROWS "${cxx_rows}")
  set(TALUS_CONFIG_PY_COMPONENTS "${py_components}")
  set(TALUS_CONFIG_PY_FEATURES "${py_features}")
  configure_file(${PROJECT_SOURCE_DIR}/cmake/build_config.cpp.in
                 ${PROJECT_BINARY_DIR}/generated/build_config.cpp @ONLY)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/_build_config.py.in
                 ${PROJECT_BINARY_DIR}/generated/_build_config.py @ONLY)
endfunction()

## talus_print_summary(): the table users read at the end of the configure step.
function(talus_print_summary)
  message(STATUS "")
  message(STATUS "Talus ${PROJECT_VERSION} configuration (${CMAKE_BUILD_TYPE})")
  foreach(kind COMPONENT FEATURE)
    if(kind STREQUAL COMPONENT)
      message(STATUS "  components:")
    else()
      message(STATUS "  features:")
    endif()
    _talus_entries(${kind} entries)
    foreach(entry IN LISTS entries)
      _talus_split_entry("${entry}" name state note)
      string(LENGTH "${name}" len)
      math(EXPR pad "14 - ${len}")
      string(REPEAT " " ${pad} spaces)
      if(state)
        set(state "ON ")
      endif()
      message(STATUS "    ${name}${spaces}${state}  ${note}")
    endforeach()
  endforeach()
  message(STATUS "")
endfunction()
