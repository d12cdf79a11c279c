# cmake -DSOURCE_DIR=<checkout> -DWORK=<scratch folder> -DCASE=upward|downward -P check_layers_test.cmake
# Builds a two-folder tree in WORK and runs the layering check of cmake/orch_module.cmake on
# it: engine/ including run/ (upward) must stop with the offending file and line; run/
# including engine/ (its stated dep) must pass.
cmake_minimum_required(VERSION 3.22)
include(${SOURCE_DIR}/cmake/check_layers.cmake)
file(REMOVE_RECURSE ${WORK})
file(WRITE ${WORK}/orchestrator/engine/engine.cpp "#include \"engine/engine.hpp\"\n#include <vector>\n")
file(WRITE ${WORK}/orchestrator/run/runner.cpp "#include \"engine/engine.hpp\"\n")
if(CASE STREQUAL "upward")
  file(APPEND ${WORK}/orchestrator/engine/engine.cpp "#include \"run/runner.hpp\"\n")
  orch_check_layers(NAME engine DIR ${WORK}/orchestrator/engine ROOTS ${WORK}/orchestrator ALLOWED core)
else()
  orch_check_layers(NAME run DIR ${WORK}/orchestrator/run ROOTS ${WORK}/orchestrator ALLOWED core engine)
endif()
message(STATUS "layering check passed")
