# One static library per source folder, with the folders it may use stated (docs/layout.md).
#
#   orch_module(NAME [DEPS folder...] [LIBS target...] [SOURCES file...])
#
# builds orch_NAME from NAME/*.cpp (picked up at build time: a new file in an existing
# folder needs no CMake edit), links orch_<dep> for every DEPS folder (PUBLIC: a folder's
# headers may show its deps' types) and LIBS (outside libraries), and checks, at configure
# time and again at build time whenever one of its files changes, that NAME's sources
# include headers only from NAME itself and its DEPS: an include that climbs the layers
# stops the configuration or the build with the file, the line and the folders allowed
# (cmake/check_layers.cmake). A new folder is one line: orch_module(r157 DEPS core engine).
#
# ORCH_MODULE_ROOT: the folder holding the module folders (set before the first call).

include(${CMAKE_CURRENT_LIST_DIR}/check_layers.cmake)
set(ORCH_LAYER_ROOTS ${CMAKE_SOURCE_DIR}/orchestrator ${CMAKE_SOURCE_DIR}/adapters)
option(ORCH_CHECK_LAYERS "Refuse includes from folders a module does not depend on" ON)

# orch_layer_rule(NAME DIR DIR ALLOWED folder... [TARGET target]): checks DIR's includes now
# (configure) and, with TARGET, again whenever one of DIR's files changes (build): TARGET's
# sources compile only after the check passed.
function(orch_layer_rule)
  cmake_parse_arguments(R "" "NAME;DIR;TARGET" "ALLOWED" ${ARGN})
  if(NOT ORCH_CHECK_LAYERS)
    return()
  endif()
  orch_check_layers(NAME ${R_NAME} DIR ${R_DIR} ROOTS ${ORCH_LAYER_ROOTS} ALLOWED ${R_ALLOWED})
  if(R_TARGET)
    file(GLOB files CONFIGURE_DEPENDS ${R_DIR}/*.cpp ${R_DIR}/*.hpp ${R_DIR}/*.h)
    set(stamp ${CMAKE_BINARY_DIR}/layers/${R_NAME}.checked)
    string(REPLACE ";" "," allowed "${R_ALLOWED}")
    string(REPLACE ";" "," roots "${ORCH_LAYER_ROOTS}")
    add_custom_command(OUTPUT ${stamp}
      COMMAND ${CMAKE_COMMAND} -DNAME=${R_NAME} -DDIR=${R_DIR} -DALLOWED=${allowed} -DROOTS=${roots}
              -P ${CMAKE_SOURCE_DIR}/cmake/check_layers.cmake
      COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
      DEPENDS ${files} ${CMAKE_SOURCE_DIR}/cmake/check_layers.cmake
      COMMENT "Checking the includes of ${R_NAME}/ against its layer" VERBATIM)
    add_custom_target(${R_TARGET}_layers DEPENDS ${stamp})
    add_dependencies(${R_TARGET} ${R_TARGET}_layers)
  endif()
endfunction()

function(orch_module name)
  cmake_parse_arguments(M "" "" "DEPS;LIBS;SOURCES" ${ARGN})
  set(dir ${ORCH_MODULE_ROOT}/${name})
  file(GLOB sources CONFIGURE_DEPENDS ${dir}/*.cpp)
  add_library(orch_${name} STATIC ${sources} ${M_SOURCES})
  target_include_directories(orch_${name} PUBLIC ${ORCH_MODULE_ROOT})
  set(dep_targets)
  foreach(dep ${M_DEPS})
    if(NOT TARGET orch_${dep})
      message(FATAL_ERROR "orch_module(${name}): DEPS ${dep} is not defined yet; "
                          "modules are declared bottom-up, so a dep comes first")
    endif()
    list(APPEND dep_targets orch_${dep})
  endforeach()
  target_link_libraries(orch_${name} PUBLIC ${dep_targets} ${M_LIBS})
  set_property(GLOBAL APPEND PROPERTY ORCH_MODULES ${name})
  set_property(GLOBAL PROPERTY ORCH_MODULE_DEPS_${name} ${M_DEPS})
  orch_layer_rule(NAME ${name} DIR ${dir} ALLOWED ${M_DEPS} TARGET orch_${name})
endfunction()

# orch_module_closure(OUT module...): the modules and everything they depend on, each once,
# dependencies first (for builds outside CMake's targets, e.g. the clang fuzzers).
function(orch_module_closure out)
  set(done)
  set(pending ${ARGN})
  while(pending)
    list(POP_FRONT pending m)
    if(m IN_LIST done)
      continue()
    endif()
    get_property(deps GLOBAL PROPERTY ORCH_MODULE_DEPS_${m})
    set(missing)
    foreach(d ${deps})
      if(NOT d IN_LIST done)
        list(APPEND missing ${d})
      endif()
    endforeach()
    if(missing)
      list(PREPEND pending ${missing} ${m})
    else()
      list(APPEND done ${m})
    endif()
  endwhile()
  set(${out} ${done} PARENT_SCOPE)
endfunction()
