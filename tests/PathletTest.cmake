# pathlet_add_test(name SOURCES a.cpp b.cpp [LIBS x y] [LABELS gl])
#
# A GoogleTest executable registered with ctest. A test labelled `gl` depends on
# pathlet_runtime: every built-in pass plugin, its shaders, the shared shaders and graphs and
# the `pathlet` command (and the test fixture plugins). So a test never runs against a stale plugin or shader, and no test
# lists its dependencies by hand. LIBS: pathlet::internal for the engine with its internals,
# pathlet_base and pathlet_data for the CPU-only ground floor and data code.
# PATHLET_TEST_SOURCE_DIR is the folder of the first source (goldens/ and fixtures beside it).
# Included by the top-level CMakeLists before passes/, so a pass folder can hold its own tests
# (pathlet_add_pass(... TESTS ...)).
find_package(GTest REQUIRED)
include(GoogleTest)

# Real third-party data lives beside the checkout (never copied into the repo).
set(PATHLET_REAL_DATA_DIR "${PROJECT_SOURCE_DIR}/../shared/data/real" CACHE PATH "shared/data/real")
# Every GL test runs on Mesa's llvmpipe, pinned, with a hermetic shader cache: one folder of this
# build tree that every test and the commands they start share (never the user's ~/.cache), so a
# shader is compiled by LLVM once a run, not once a process. Without it most of a small render is
# compiling (ScaleFree: 44 s without a cache, 10 s with a fresh one, 4.5 s with a warm one).
# Mesa keys an entry by the driver's build and the shader's source, so no entry goes stale.
# PATHLET_UPDATE_GOLDENS is never inherited from the caller: goldens change only through
# scripts/update-goldens.sh.
# XDG_CONFIG_HOME: the plugin trust file of every test run lives in the build tree, never in the
# user's ~/.config.
set(PATHLET_TEST_ENV "PATHLET_UPDATE_GOLDENS=0" "XDG_CONFIG_HOME=${PROJECT_BINARY_DIR}/test-config"
  "LIBGL_ALWAYS_SOFTWARE=1" "GALLIUM_DRIVER=llvmpipe" "MESA_SHADER_CACHE_DISABLE=false"
  "MESA_SHADER_CACHE_DIR=${PROJECT_BINARY_DIR}/test-shader-cache"
  "PATHLET_REAL_DATA_DIR=${PATHLET_REAL_DATA_DIR}" "PATHLET_PLUGIN_PATH=" "DISPLAY=" "WAYLAND_DISPLAY=")

if(NOT TARGET pathlet_runtime)
  add_custom_target(pathlet_runtime)
endif()
# The test fixture plugins (pathlet_add_pass(... NO_INSTALL)): GL tests get them beside the runtime.
add_custom_target(pathlet_test_fixtures)

function(pathlet_add_test name)
  # RUN_SERIAL: alone on the machine (a test that measures the machine's own load against a run)
  cmake_parse_arguments(T "RUN_SERIAL" "" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  set_property(GLOBAL APPEND PROPERTY PATHLET_TEST_TARGETS ${name})  # they share a precompiled header
  list(LENGTH T_SOURCES count)
  if(count GREATER 2)  # gtest and the helpers parsed once a batch (cmake/PathletBuild.cmake)
    pathlet_unity_build(${name})
  endif()
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  pathlet_test_optimize(${name})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)  # header-only helpers (cli_run.hpp)
  list(GET T_SOURCES 0 first)
  get_filename_component(first "${first}" ABSOLUTE)
  get_filename_component(source_dir "${first}" DIRECTORY)
  target_compile_definitions(${name} PRIVATE
    PATHLET_TEST_SOURCE_DIR="${source_dir}"
    PATHLET_TEST_BINARY_DIR="${CMAKE_CURRENT_BINARY_DIR}"
    PATHLET_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    PATHLET_BUILD_DIR="${PROJECT_BINARY_DIR}"
    PATHLET_CLI="${PROJECT_BINARY_DIR}/bin/pathlet")
  if("gl" IN_LIST T_LABELS)
    add_dependencies(${name} pathlet_runtime pathlet_test_fixtures)
  endif()
  # The environment goes through `env` as the test's launcher: gtest_discover_tests passes
  # PROPERTIES as name/value pairs, so a list-valued ENVIRONMENT set only its first variable
  # and shifted the rest into bogus properties. `env` sets every one, for discovery and runs.
  set_target_properties(${name} PROPERTIES CROSSCOMPILING_EMULATOR "env;${PATHLET_TEST_ENV}")
  # Only the properties that have a value: an empty LABELS vanished from the flattened list and
  # the next name became the label. The list is flattened into name/value pairs, so one label.
  list(LENGTH T_LABELS n)
  if(n GREATER 1)
    message(FATAL_ERROR "pathlet_add_test(${name}): one label at most (gtest_discover_tests flattens a list)")
  endif()
  set(props)
  if(T_LABELS)
    list(APPEND props LABELS "${T_LABELS}")
  endif()
  if(T_RUN_SERIAL)
    list(APPEND props RUN_SERIAL TRUE)
  endif()
  gtest_discover_tests(${name} PROPERTIES ${props} DISCOVERY_TIMEOUT 60)
endfunction()
