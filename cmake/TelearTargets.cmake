# Helpers shared by every layer: one place sets warnings and include roots.

# CMAKE_INSTALL_LIBDIR, CMAKE_INSTALL_INCLUDEDIR for every install() (cmake/TelearInstall.cmake).
include(GNUInstallDirs)

# telear_library(NAME SOURCES ... ) creates the static library telear_NAME, alias telear::NAME,
# whose public headers are included as "telear/NAME/file.hpp" from include/ (in the build
# tree and, installed, from the package's include directory). It is installed and exported
# as telear::NAME (find_package(telear)).
# Precompiled headers (issue 20): the third-party headers every unit of a layer parses through
# telear's own headers (Eigen everywhere; OpenCV from vision up; gRPC, protobuf and spdlog from
# net up; GoogleTest in the tests), parsed once per target instead of once per unit.
option(TELEAR_PCH "Precompile the heavy third-party headers of each target" ON)
# Unity builds of the libraries: their units instantiate the same Eigen, OpenCV and gRPC
# templates again and again (more than half of a core unit's compile time is template
# instantiation, which a precompiled header does not save); compiled in batches, each batch
# instantiates them once. File-local names are therefore unique within a library.
option(TELEAR_UNITY "Compile each library's sources in batches (CMake's UNITY_BUILD)" ON)
set(TELEAR_UNITY_BATCH_SIZE 8 CACHE STRING "sources per unity batch")
set(TELEAR_PCH_CORE <algorithm> <cmath> <functional> <map> <memory> <optional> <sstream> <string>
                    <vector> <Eigen/Core> <Eigen/Geometry>)
set(TELEAR_PCH_VISION ${TELEAR_PCH_CORE} <opencv2/core.hpp> <opencv2/imgproc.hpp>
                      <opencv2/calib3d.hpp>)
set(TELEAR_PCH_NET ${TELEAR_PCH_VISION} <grpcpp/grpcpp.h> <spdlog/spdlog.h>)
set(TELEAR_PCH_TEST <gtest/gtest.h> <gmock/gmock.h>)

# telear_precompile(TARGET core|vision|net [test]): the header set of that level (and the
# GoogleTest headers for a test target).
function(telear_precompile target level)
  if(NOT TELEAR_PCH)
    return()
  endif()
  string(TOUPPER ${level} level)
  set(headers ${TELEAR_PCH_${level}})
  if(ARGN STREQUAL "test")
    list(APPEND headers ${TELEAR_PCH_TEST})
  endif()
  target_precompile_headers(${target} PRIVATE ${headers})
endfunction()

# Which header set a layer's units share (what its public headers include).
function(telear_pch_level name out)
  if(name MATCHES "^(core|geometry|sim_robot)$")
    set(${out} core PARENT_SCOPE)
  elseif(name MATCHES "^(vision|render|sim_rig)$")
    set(${out} vision PARENT_SCOPE)
  else()
    set(${out} net PARENT_SCOPE)
  endif()
endfunction()

# telear_library(NAME SOURCES ... ) creates the static library telear_NAME, alias telear::NAME,
# whose public headers are included as "telear/NAME/file.hpp" from include/ (in the build
# tree and, installed, from the package's include directory). It is installed and exported
# as telear::NAME (find_package(telear)).
function(telear_library name)
  add_library(telear_${name} STATIC ${ARGN})
  add_library(telear::${name} ALIAS telear_${name})
  set_target_properties(telear_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(telear_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                   $<INSTALL_INTERFACE:include>)
  telear_warnings(telear_${name})
  telear_pch_level(${name} level)
  telear_precompile(telear_${name} ${level})
  if(TELEAR_UNITY)
    set_target_properties(telear_${name} PROPERTIES UNITY_BUILD ON
                                                    UNITY_BUILD_BATCH_SIZE ${TELEAR_UNITY_BATCH_SIZE})
  endif()
  # Every layer library is installed and exported (cmake/TelearInstall.cmake).
  set_property(GLOBAL APPEND PROPERTY TELEAR_EXPORTED_LIBRARIES telear_${name})
endfunction()

function(telear_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
endfunction()

# telear_test(NAME SOURCES ... LIBS ... [PCH core|vision|net] [SYSTEM] [PROPERTIES ...])
# registers one GoogleTest executable per layer (or per kind of test in a layer) with CTest:
# every test case is its own CTest entry (gtest_discover_tests), so merging executables does
# not merge entries. Cases are listed when CTest runs (DISCOVERY_MODE PRE_TEST), not at build
# time. Each entry is labelled with its layer (the tests/ sub-folder), or LAYER-system for a
# SYSTEM executable (end-to-end runs of the simulator through servers or processes): `ctest -L`
# takes a regular expression, so `ctest -L net` runs one layer and `ctest -L system` the
# end-to-end tests. (One label each: gtest_discover_tests splits list-valued properties.)
#
# Test units are compiled at -O1 (the libraries they call stay at the build type's -O3): a
# test's own code is assertions and set-up, and -O3 code generation was a third of the CI's
# compile time (docs/development.md).
function(telear_test name)
  cmake_parse_arguments(T "SYSTEM" "PCH" "SOURCES;LIBS;PROPERTIES" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} telear::test_util GTest::gtest GTest::gmock
                                        GTest::gtest_main)
  telear_warnings(${name})
  if(CMAKE_BUILD_TYPE STREQUAL "Release")
    target_compile_options(${name} PRIVATE -O1)
  endif()
  if(NOT T_PCH)
    set(T_PCH core)
  endif()
  telear_precompile(${name} ${T_PCH} test)
  get_filename_component(layer ${CMAKE_CURRENT_SOURCE_DIR} NAME)
  set(label ${layer})
  set(cost "")
  if(T_SYSTEM)
    set(label ${layer}-system)
    # Started first: a clean clone has no CTest timing data, and a minute-long test started
    # last holds the whole run up while the other cores idle.
    set(cost COST 1000)
  endif()
  gtest_discover_tests(${name} DISCOVERY_MODE PRE_TEST DISCOVERY_TIMEOUT 60
                       PROPERTIES ENVIRONMENT "TELEAR_DATA_DIR=${TELEAR_DATA_DIR}"
                                  LABELS ${label} ${cost} ${T_PROPERTIES})
endfunction()
