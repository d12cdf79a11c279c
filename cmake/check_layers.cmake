# The layering check (docs/layout.md): every #include "X/..." in a folder's sources names
# the folder itself or one of the folders it depends on, when X is a module folder (a folder
# under one of the roots). Used by cmake/orch_module.cmake at configure time and, as a
# script, at build time whenever a file of the folder changes:
#   cmake -DNAME=engine -DDIR=<folder> -DALLOWED=core,map -DROOTS=<root>,<root> -P check_layers.cmake

if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  cmake_minimum_required(VERSION 3.22)  # the project's policies (if IN_LIST) when run as a script
endif()

# orch_check_layers(NAME name DIR dir ROOTS root... ALLOWED folder...): stops with every
# offending file and line.
function(orch_check_layers)
  cmake_parse_arguments(C "" "NAME;DIR" "ALLOWED;ROOTS" ${ARGN})
  set(modules)
  foreach(root ${C_ROOTS})
    file(GLOB entries LIST_DIRECTORIES true RELATIVE ${root} ${root}/*)
    foreach(entry ${entries})
      if(IS_DIRECTORY ${root}/${entry})
        list(APPEND modules ${entry})
      endif()
    endforeach()
  endforeach()
  file(GLOB sources ${C_DIR}/*.cpp ${C_DIR}/*.hpp ${C_DIR}/*.h)
  set(offences)
  foreach(source ${sources})
    file(STRINGS ${source} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"[^\"/]+/")
    foreach(line ${includes})
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"/]+)/.*$" "\\1" folder "${line}")
      if(folder IN_LIST modules AND NOT folder STREQUAL C_NAME AND NOT folder IN_LIST C_ALLOWED)
        string(STRIP "${line}" line)
        list(APPEND offences "  ${source}: ${line}")
      endif()
    endforeach()
  endforeach()
  if(offences)
    list(JOIN offences "\n" text)
    if(C_ALLOWED)
      list(JOIN C_ALLOWED ", " allowed)
    else()
      set(allowed "none")
    endif()
    message(FATAL_ERROR "Layering: ${C_NAME}/ includes a folder it does not depend on:\n${text}\n"
            "${C_NAME}/ may include: ${allowed} (its DEPS, docs/layout.md). Move the code to the "
            "layer that owns it, or state the dependency if it really points downwards.")
  endif()
endfunction()

if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE AND DEFINED NAME)
  string(REPLACE "," ";" allowed "${ALLOWED}")
  string(REPLACE "," ";" roots "${ROOTS}")
  orch_check_layers(NAME ${NAME} DIR ${DIR} ROOTS ${roots} ALLOWED ${allowed})
endif()
