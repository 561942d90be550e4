# pathlet_add_pass(<name> SOURCES a.cpp ... [SHADERS x.frag ...] [TESTS tests/test_x.cpp ...]
#                  [NO_INSTALL])
#
# Builds a pass plugin: a MODULE library named pathlet_<name>.so (the host opens only files named
# so) whose shaders travel with it in a folder pathlet_<name>/ beside it (build tree and install
# tree alike), so the engine finds them.
# Used by the built-in passes and, through find_package(pathlet), by out-of-tree plugins.
# In tree, the plugin and its shaders join pathlet_runtime (what every GL test depends on; a
# NO_INSTALL test fixture joins pathlet_test_fixtures) and
# TESTS build as test_<name> (GoogleTest, labelled gl, with the test support library), so a
# pass's tests live in its folder and always run against its current code and shaders.
function(pathlet_add_pass name)
  cmake_parse_arguments(P "NO_INSTALL" "" "SOURCES;SHADERS;TESTS" ${ARGN})
  if(NOT PATHLET_PASS_OUTPUT_DIR)
    set(PATHLET_PASS_OUTPUT_DIR ${CMAKE_BINARY_DIR}/passes)
  endif()
  if(NOT PATHLET_PASS_INSTALL_DIR)
    set(PATHLET_PASS_INSTALL_DIR lib/pathlet/passes)
  endif()
  add_library(${name} MODULE ${P_SOURCES})
  target_link_libraries(${name} PRIVATE pathlet::pathlet)
  set_target_properties(${name} PROPERTIES
    PREFIX "pathlet_"
    LIBRARY_OUTPUT_DIRECTORY ${PATHLET_PASS_OUTPUT_DIR}
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    BUILD_RPATH_USE_ORIGIN ON
    INSTALL_RPATH "$ORIGIN/../..")
  # Unresolved symbols fail at link time, not at load time. Not under sanitizers: their
  # runtime symbols come from the executable that loads the plugin.
  if(NOT PATHLET_SANITIZED)
    target_link_options(${name} PRIVATE "LINKER:-z,defs")
  endif()
  foreach(shader ${P_SHADERS})
    get_filename_component(abs ${shader} ABSOLUTE)
    get_filename_component(fname ${shader} NAME)
    add_custom_command(TARGET ${name} POST_BUILD
      COMMAND ${CMAKE_COMMAND} -E make_directory ${PATHLET_PASS_OUTPUT_DIR}/pathlet_${name}
      COMMAND ${CMAKE_COMMAND} -E copy_if_different ${abs} ${PATHLET_PASS_OUTPUT_DIR}/pathlet_${name}/${fname})
  endforeach()
  # Shaders edited without a C++ change still get copied.
  if(P_SHADERS)
    add_custom_target(${name}_shaders ALL
      COMMAND ${CMAKE_COMMAND} -E make_directory ${PATHLET_PASS_OUTPUT_DIR}/pathlet_${name}
      COMMAND ${CMAKE_COMMAND} -E copy_if_different ${P_SHADERS} ${PATHLET_PASS_OUTPUT_DIR}/pathlet_${name}/
      WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
  endif()
  # Test fixtures (NO_INSTALL) join the tests' own target, so the runtime (what scripts/main.sh
  # builds) holds no test code.
  set(_joins pathlet_runtime)
  if(P_NO_INSTALL AND TARGET pathlet_test_fixtures)
    set(_joins pathlet_test_fixtures)
  endif()
  if(TARGET ${_joins})
    add_dependencies(${_joins} ${name})
    if(P_SHADERS)
      add_dependencies(${_joins} ${name}_shaders)
    endif()
  endif()
  if(P_TESTS AND COMMAND pathlet_add_test)
    pathlet_add_test(test_${name} SOURCES ${P_TESTS} LIBS pathlet::internal pathlet_test_support LABELS gl)
  endif()
  if(P_NO_INSTALL)  # test fixtures
    return()
  endif()
  install(TARGETS ${name} LIBRARY DESTINATION ${PATHLET_PASS_INSTALL_DIR})
  if(P_SHADERS)
    install(FILES ${P_SHADERS} DESTINATION ${PATHLET_PASS_INSTALL_DIR}/pathlet_${name})
  endif()
  # The pass's README (if any) travels with it: docs next to the plugin.
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/README.md)
    install(FILES ${CMAKE_CURRENT_SOURCE_DIR}/README.md DESTINATION ${PATHLET_PASS_INSTALL_DIR}/pathlet_${name})
  endif()
endfunction()
