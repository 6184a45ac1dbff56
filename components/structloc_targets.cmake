# How every structloc library and executable is declared, so that the naming
# rule (folder = target = namespace: components/world_model is the target
# structloc_world_model, alias structloc::world_model, namespace
# structloc::world_model), the warning flags, the header layout
# (include/structloc/<folder>/) and the install rules live in one place.

# structloc_library(NAME [INTERFACE] [INSTALL] [PRECOMPILE_EIGEN] SOURCES ... PUBLIC ... PRIVATE ...)
# INSTALL: the library and its headers are installed and exported in
# structlocTargets (the DDS-free core that other CMake projects may link).
# PRECOMPILE_EIGEN: Eigen is parsed once for the library, not once per file;
# the three libraries that compile longest take a fifth less CPU time so
# (166 -> 133 s on our machine), which a first build (the demo's) waits for.
function(structloc_library name)
  cmake_parse_arguments(arg "INTERFACE;INSTALL;PRECOMPILE_EIGEN" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  set(target structloc_${name})
  set(include_dir ${CMAKE_CURRENT_SOURCE_DIR}/include)
  if(NOT EXISTS ${include_dir})
    set(include_dir ${CMAKE_CURRENT_SOURCE_DIR})
  endif()
  if(arg_INTERFACE)
    add_library(${target} INTERFACE)
    set(scope INTERFACE)
  else()
    add_library(${target} STATIC ${arg_SOURCES})
    target_compile_options(${target} PRIVATE ${STRUCTLOC_WARNINGS})
    target_link_libraries(${target} PRIVATE ${arg_PRIVATE})
    if(arg_PRECOMPILE_EIGEN)
      target_precompile_headers(${target} PRIVATE <Eigen/Dense> <algorithm> <cmath> <string>
                                <vector>)
    endif()
    set(scope PUBLIC)
  endif()
  target_include_directories(${target} ${scope} $<BUILD_INTERFACE:${include_dir}>
                             $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} ${scope} ${arg_PUBLIC})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  add_library(structloc::${name} ALIAS ${target})
  if(arg_INSTALL)
    install(TARGETS ${target} EXPORT structlocTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/include)
      install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endif()
  endif()
endfunction()

# structloc_executable(TARGET [OUTPUT_NAME NAME] SOURCES ... LINK ...): a
# program installed into bin/ (the CLI and the components).
function(structloc_executable target)
  cmake_parse_arguments(arg "" "OUTPUT_NAME" "SOURCES;LINK" ${ARGN})
  add_executable(${target} ${arg_SOURCES})
  target_link_libraries(${target} PRIVATE ${arg_LINK})
  target_compile_options(${target} PRIVATE ${STRUCTLOC_WARNINGS})
  if(arg_OUTPUT_NAME)
    set_target_properties(${target} PROPERTIES OUTPUT_NAME ${arg_OUTPUT_NAME})
  endif()
  install(TARGETS ${target} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
