# orch_clang_fuzzer(NAME MAIN_SOURCE SOURCES...): a libFuzzer binary built with clang (the
# project's compiler may be g++), with ASan and UBSan (halt on error). One object per source,
# shared between the fuzzers, built in parallel (through ccache when installed), so a change
# rebuilds only what it touches.
find_program(ORCH_CCACHE ccache)
if(NOT ORCH_CCACHE)
  set(ORCH_CCACHE "")
endif()
set(ORCH_FUZZ_OBJECTS ${CMAKE_CURRENT_BINARY_DIR}/clang_fuzz.objects)
file(MAKE_DIRECTORY ${ORCH_FUZZ_OBJECTS})

function(orch_clang_fuzzer name main)
  set(flags -std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined
            -fno-sanitize-recover=undefined -I${CMAKE_SOURCE_DIR}/orchestrator -I${CMAKE_SOURCE_DIR}/tests
            -isystem /usr/include/eigen3 -DORCH_VERSION="${PROJECT_VERSION}"
            -DORCH_SOURCE_MAPS_DIR="${ORCH_SOURCE_MAPS_DIR}" -DORCH_FUZZ_MAPS_DIR="${ORCH_FUZZ_MAPS_DIR}"
            -DORCH_PROJ_SONAME="$<TARGET_SONAME_FILE_NAME:PROJ::proj>")  # geo_projection.cpp opens PROJ
  set(objects)
  foreach(source ${main} ${ARGN})
    get_filename_component(stem ${source} NAME_WE)
    get_filename_component(dir ${source} DIRECTORY)
    get_filename_component(folder ${dir} NAME)
    set(object ${ORCH_FUZZ_OBJECTS}/${folder}_${stem}.o)
    get_property(known DIRECTORY PROPERTY ORCH_FUZZ_OBJECT_LIST)
    if(NOT object IN_LIST known)
      add_custom_command(OUTPUT ${object}
        COMMAND ${ORCH_CCACHE} ${ORCH_CLANGXX} ${flags} -MD -MF ${object}.d -c ${source} -o ${object}
        DEPENDS ${source}
        DEPFILE ${object}.d
        COMMENT "clang fuzzer object ${folder}_${stem}.o" VERBATIM)
      set_property(DIRECTORY APPEND PROPERTY ORCH_FUZZ_OBJECT_LIST ${object})
    endif()
    list(APPEND objects ${object})
  endforeach()
  add_custom_command(OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/${name}
    COMMAND ${ORCH_CLANGXX} -fsanitize=fuzzer,address,undefined ${objects} -o ${CMAKE_CURRENT_BINARY_DIR}/${name}
            -lfmt -lpugixml -lcrypto -lpthread -lyaml-cpp -lboost_filesystem -lproj
    DEPENDS ${objects}
    COMMENT "Linking the libFuzzer target ${name}" VERBATIM)
  add_custom_target(${name}_build ALL DEPENDS ${CMAKE_CURRENT_BINARY_DIR}/${name})
  add_dependencies(${name}_build orch_scenario_executor)  # orch_scenario_executor generates the embedded catalog source
endfunction()
