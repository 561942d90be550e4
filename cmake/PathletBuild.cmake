# How this project compiles: included by the top-level CMakeLists.txt before any target. Not
# installed (an out-of-tree plugin keeps its own settings). The measurements behind each choice
# are in docs/testing.md ("Build time").
#
#   ccache      every compile goes through ccache when it is installed, with one base directory
#               and the settings precompiled headers need. So scripts/main.sh's objects serve
#               scripts/test.sh and the lean bundle's build (another tree of the same sources).
#   -O2         the Release level: -O3 took longer to compile and no frame faster.
#   -Og tests   a test's own code (set-up and checks) compiles at -Og in Release; what it tests
#               (libpathlet, the plugins, the command) is the release build. A third less compile
#               time for the tests than -O2, and the suites take no longer (docs/testing.md).
#   gold        GCC's executables and libraries link with gold where it is found (binutils):
#               a tenth of ld.bfd's time for a test executable, and there are about eighty.
#   unity       multi-file targets compile in batches (pathlet_unity_build): the headers every
#               file includes (nlohmann/json, GLM, the standard library, the SDK) are parsed and
#               their templates compiled once a batch instead of once a file.
#   PCH         targets of a source or two (the pass plugins, the tests) share one precompiled
#               header of those third-party and standard headers (pathlet_share_pch).
#   unit times  every compile appends its CPU time to BUILD/unit-times.tsv (scripts/build-times.sh).

option(PATHLET_CCACHE "Compile through ccache when it is installed" ON)
option(PATHLET_UNITY "Compile multi-file targets in batches (unity build); OFF: file by file" ON)
set(PATHLET_UNITY_BATCH 16 CACHE STRING "Source files per unity batch")
option(PATHLET_PCH "Precompile the headers every pass and every test parses" ON)
option(PATHLET_UNIT_TIMES "Log each compile's CPU time in BUILD/unit-times.tsv" ON)
set(PATHLET_TEST_OPTIMIZE "-Og" CACHE STRING "Optimisation of the tests' own code in Release (empty: the build type's)")
option(PATHLET_GOLD "Link with gold when the compiler can" ON)

# A launcher the user chose (other than plain ccache) is kept as it is.
find_program(PATHLET_CCACHE_PROGRAM ccache)
mark_as_advanced(PATHLET_CCACHE_PROGRAM)
if(PATHLET_CCACHE AND PATHLET_CCACHE_PROGRAM)
  # BASEDIR: paths below the source tree are hashed relative to the build folder, so two build
  # trees side by side (build/, build-bundle-lean/) share entries. SLOPPINESS: what ccache must
  # allow to cache compiles that use a precompiled header, and headers generated during the build.
  set(_pathlet_ccache env CCACHE_BASEDIR=${PROJECT_SOURCE_DIR}
      CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime ${PATHLET_CCACHE_PROGRAM})
  foreach(lang C CXX)
    if(NOT CMAKE_${lang}_COMPILER_LAUNCHER OR CMAKE_${lang}_COMPILER_LAUNCHER MATCHES "^(.*/)?ccache$")
      set(CMAKE_${lang}_COMPILER_LAUNCHER ${_pathlet_ccache})
    endif()
  endforeach()
endif()

foreach(lang C CXX)
  string(REPLACE "-O3" "-O2" CMAKE_${lang}_FLAGS_RELEASE "${CMAKE_${lang}_FLAGS_RELEASE}")
endforeach()

# GCC only: clang's sanitizer runtimes make gold warn about every symbol they export.
if(PATHLET_GOLD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  include(CheckLinkerFlag)
  check_linker_flag(CXX -fuse-ld=gold PATHLET_HAS_GOLD)
  if(PATHLET_HAS_GOLD)
    add_link_options(-fuse-ld=gold)
  endif()
endif()

if(PATHLET_UNIT_TIMES AND CMAKE_GENERATOR MATCHES "Makefiles|Ninja")
  set_property(GLOBAL PROPERTY RULE_LAUNCH_COMPILE
    "${PROJECT_SOURCE_DIR}/cmake/unit_time.sh ${CMAKE_BINARY_DIR}/unit-times.tsv")
endif()

# pathlet_unity_build(TARGET... [SKIP file...]): TARGETs compile in batches. SKIP files compile
# alone: one that defines a library's implementation macros, or one whose text differs between
# the full and the lean build (the lean build's batches must be the full build's for ccache).
function(pathlet_unity_build)
  cmake_parse_arguments(U "" "" "SKIP" ${ARGN})
  if(NOT PATHLET_UNITY)
    return()
  endif()
  set_target_properties(${U_UNPARSED_ARGUMENTS} PROPERTIES UNITY_BUILD ON
    UNITY_BUILD_BATCH_SIZE ${PATHLET_UNITY_BATCH})
  if(U_SKIP)
    set_source_files_properties(${U_SKIP} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
  endif()
endfunction()

# What nearly every file parses before its own code, precompiled.
set(PATHLET_PCH_HEADERS <nlohmann/json.hpp> <glm/glm.hpp> <algorithm> <cmath> <filesystem> <functional>
    <map> <memory> <optional> <set> <sstream> <string> <vector>)

# pathlet_share_pch(HOLDER TARGETS target... [HEADERS <h>...] [LIBS lib...]): the TARGETS, all of
# one kind with the same options (pass plugins, tests, fuzz targets), reuse one precompiled
# header, compiled by the object library HOLDER under the first one's flags (LIBS: what brings the
# macros HEADERS test, e.g. gtest's). GCC refuses a header precompiled under other flags (-fPIC
# for -fPIE) or macros (the <target>_EXPORTS CMake gives a MODULE, so the TARGETS do without it).
function(pathlet_share_pch holder)
  cmake_parse_arguments(P "" "" "TARGETS;HEADERS;LIBS" ${ARGN})
  if(NOT PATHLET_PCH OR NOT P_TARGETS)
    return()
  endif()
  set(source ${CMAKE_CURRENT_BINARY_DIR}/${holder}.cpp)
  file(CONFIGURE OUTPUT ${source} CONTENT "// Compiles the precompiled header of ${holder} (cmake/PathletBuild.cmake).\n")
  add_library(${holder} OBJECT ${source})
  target_precompile_headers(${holder} PRIVATE ${PATHLET_PCH_HEADERS} ${P_HEADERS})
  target_link_libraries(${holder} PRIVATE ${P_LIBS})
  list(GET P_TARGETS 0 first)
  foreach(p CXX_VISIBILITY_PRESET VISIBILITY_INLINES_HIDDEN COMPILE_OPTIONS)
    get_target_property(v ${first} ${p})
    if(v)
      set_target_properties(${holder} PROPERTIES ${p} "${v}")
    endif()
  endforeach()
  get_target_property(type ${first} TYPE)
  if(type STREQUAL EXECUTABLE)
    set_target_properties(${holder} PROPERTIES POSITION_INDEPENDENT_CODE OFF)
    target_compile_options(${holder} PRIVATE ${CMAKE_CXX_COMPILE_OPTIONS_PIE})
  endif()
  if(CMAKE_CXX_COMPILER_ID MATCHES Clang)  # no timestamps in the file, so ccache can reuse it
    target_compile_options(${holder} PRIVATE -Xclang -fno-pch-timestamp)
  endif()
  foreach(t ${P_TARGETS})
    set_target_properties(${t} PROPERTIES DEFINE_SYMBOL "")
    target_precompile_headers(${t} REUSE_FROM ${holder})
  endforeach()
endfunction()

# pathlet_test_optimize(TARGET...): the TARGETS' own code (a test's set-up and checks, not the
# engine it links) at PATHLET_TEST_OPTIMIZE in Release, after the build type's -O2 so it wins.
function(pathlet_test_optimize)
  if(PATHLET_TEST_OPTIMIZE)
    foreach(t ${ARGN})
      target_compile_options(${t} PRIVATE "$<$<CONFIG:Release>:${PATHLET_TEST_OPTIMIZE}>")  # may be a list
    endforeach()
  endif()
endfunction()
